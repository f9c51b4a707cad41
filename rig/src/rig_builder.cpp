#include "wirerig/rig/rig_builder.h"

#include <algorithm>
#include <cstdio>
#include <optional>

#include "wirerig/rig/part_assignment.h"
#include "wirerig/rig/spine_curves.h"
#include "wirerig/rig/triangle_bvh.h"

namespace wirerig {
namespace {

double MeanRadius(const RigPart& part) {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t k = 0; k < part.profiles.size(); ++k)
    for (const Vec3& p : part.profiles[k].points) {
      sum += (p - part.spine_points[k]).norm();
      ++count;
    }
  return count ? sum / double(count) : 0.0;
}

// Section of each wire (see rig_builder.h).
// Fails (naming the skin thickness) when a section would not be positive and finite.
Status AssignWires(RigPart& part, const Material& material, double thickness) {
  const double radius = std::max(MeanRadius(part), 1e-6);
  const double wall = std::min(thickness, 2.0 * radius);
  if (Status s = ValidateTube(radius, wall); !s) return s;
  part.spine_wire = {material, TubeSection(radius, wall)};
  const std::size_t n = part.profiles.size();
  part.profile_wires.clear();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& here = part.profiles[k].origin;
    const Vec3& prev = part.profiles[k > 0 ? k - 1 : std::min<std::size_t>(1, n - 1)].origin;
    const Vec3& next = part.profiles[k + 1 < n ? k + 1 : (n >= 2 ? n - 2 : 0)].origin;
    const double spacing = std::max(0.5 * ((here - prev).norm() + (next - here).norm()), 1e-6);
    if (Status s = ValidateStrip(spacing, thickness); !s) return s;
    part.profile_wires.push_back({material, StripSection(spacing, thickness)});
  }
  return Status::Ok();
}

void Warn(RigBuildReport& report, const std::string& part, const ProfileDiagnostics& d) {
  auto add = [&](std::size_t count, const char* what) {
    if (count)
      report.warnings.push_back("part '" + part + "': " + std::to_string(count) + " " + what);
  };
  add(d.misses, "rays missed the surface");
  add(d.other_part_hits, "rays met another part first");
  add(d.wrap_hits, "rays escaped through holes: the wrap's surface stood in");
  add(d.open_profiles, "profiles are open");
  add(d.empty_profiles, "profiles had fewer than 2 hits and were dropped");
  add(d.self_intersecting, "profiles cross themselves");
  add(d.crossing_neighbour, "pairs of adjacent profiles cross");
  add(d.outside_profiles, "profiles had their origin outside the part and were dropped");
}

// Six times the signed volume enclosed by the triangles (positive when they face outwards).
double SignedVolume6(const Mesh& mesh) {
  double volume = 0.0;
  for (const Triangle& t : mesh.welded_triangles)
    volume += mesh.welded_positions[t[0]].dot(
        mesh.welded_positions[t[1]].cross(mesh.welded_positions[t[2]]));
  return volume;
}

// The description without part `dropped` (not the root): its children hang from its parent, and
// the vertices given to it go to its parent.
RigDescription WithoutPart(const RigDescription& description, std::size_t dropped) {
  RigDescription out = description;
  const std::string parent = description.parts[dropped].parent;
  int parent_index = -1;
  for (std::size_t i = 0; i < description.parts.size(); ++i)
    if (description.parts[i].name == parent) parent_index = int(i);
  for (PartDescription& part : out.parts)
    if (part.parent == description.parts[dropped].name) part.parent = parent;
  out.parts.erase(out.parts.begin() + std::ptrdiff_t(dropped));
  for (int& p : out.vertex_part) {
    if (p == int(dropped))
      p = parent_index;
    else if (p > int(dropped))
      --p;
  }
  return out;
}

// The description without its root (part 0): the root's child with the largest subtree of
// parts (then the most vertices given by vertex_part) takes its place, its skin and its other
// children; or nullopt when the root has no child.
std::optional<RigDescription> WithoutRoot(const RigDescription& description) {
  const std::size_t n = description.parts.size();
  const std::string& root = description.parts[0].name;
  std::vector<std::size_t> subtree(n, 1);  // parents precede children: sum from the back
  for (std::size_t i = n; i-- > 1;)
    for (std::size_t p = 0; p < i; ++p)
      if (description.parts[p].name == description.parts[i].parent) subtree[p] += subtree[i];
  int heir = -1;
  std::pair<std::size_t, std::size_t> best{0, 0};
  for (std::size_t i = 1; i < n; ++i) {
    if (description.parts[i].parent != root) continue;
    const std::pair<std::size_t, std::size_t> size{
        subtree[i], std::size_t(std::count(description.vertex_part.begin(),
                                           description.vertex_part.end(), int(i)))};
    if (heir < 0 || size > best) heir = int(i), best = size;
  }
  if (heir < 0) return std::nullopt;
  // New order: the heir, then every other part as it was (parents still precede children).
  std::vector<int> order{heir};
  for (int i = 1; i < int(description.parts.size()); ++i)
    if (i != heir) order.push_back(i);
  std::vector<int> index_of(description.parts.size(), 0);  // old index -> new
  for (std::size_t k = 0; k < order.size(); ++k) index_of[std::size_t(order[k])] = int(k);
  index_of[0] = 0;  // the old root's skin goes to the heir
  RigDescription out = description;
  out.parts.clear();
  for (int i : order) {
    PartDescription part = description.parts[std::size_t(i)];
    if (i == heir)
      part.parent.clear();
    else if (part.parent == root)
      part.parent = description.parts[std::size_t(heir)].name;
    out.parts.push_back(std::move(part));
  }
  for (int& p : out.vertex_part)
    if (p >= 0) p = index_of[std::size_t(p)];
  return out;
}

// A skinless bone (rig_description.h): its spine is its central curve's 2 points, its wire a
// tube as thick as its parent's (it carries no skin, only its children).
RigPart SkinlessPart(const PartDescription& d, const RigDescription& description, const Rig& rig,
                     const std::vector<Curve>& spines) {
  RigPart part;
  part.name = d.name;
  part.skin = false;
  part.central_curve = d.central_curve;
  part.spine_points = d.central_curve;
  part.joint = d.joint;
  for (std::size_t p = 0; p < rig.parts.size(); ++p)
    if (description.parts[p].name == d.parent) part.parent = int(p);
  // Where its children hang: the parent's flesh they met before the bone came between (its
  // follow of the parent is rigid, so any point of it will do at rest).
  part.attachment = ClosestParameter(spines[std::size_t(part.parent)], part.spine_points.back());
  part.spine_wire = rig.parts[std::size_t(part.parent)].spine_wire;
  part.spine_wire.material = description.material;
  return part;
}

// One attempt; `failed` gets the part whose profiles missed the surface, if that stopped it.
Result<BuiltRig> BuildRigOnce(const Mesh& mesh, const RigDescription& description,
                              const std::string& mesh_path, const RigBuildOptions& options,
                              int* failed) {
  if (std::string error = ValidateRigDescription(description); !error.empty())
    return Error{"description: " + error};
  if (mesh.welded_triangles.empty()) return Error{"the mesh has no triangles"};
  if (!(options.skin_thickness > 0.0)) return Error{"skin thickness must be positive"};

  Result<std::vector<bool>> passive = FindPassiveTriangles(mesh, description);
  if (!passive) return Error{passive.error()};
  const std::vector<std::uint32_t> active = ActiveTriangles(passive.value());
  const TriangleBvh mesh_bvh =
      TriangleBvh::Build(mesh.welded_positions, mesh.welded_triangles, active);
  Result<PartAssignment> assignment = AssignParts(mesh, description, mesh_bvh, passive.value());
  if (!assignment) return Error{assignment.error()};
  const PartAssignment& parts = assignment.value();

  BuiltRig built;
  Rig& rig = built.rig;
  rig.mesh = mesh_path;
  rig.import = description.import;
  rig.mesh_vertices = mesh.welded_positions.size();
  rig.mesh_triangles = mesh.welded_triangles.size();
  rig.vertex_part = parts.vertex_part;
  built.report.occluded_fallbacks = parts.occluded_fallbacks;

  const bool inward_facing = SignedVolume6(mesh) < 0.0;
  if (inward_facing) built.report.warnings.push_back("the mesh's triangles face inwards");
  std::optional<TriangleBvh> wrap_bvh;
  if (options.wrap != nullptr && !options.wrap->welded_triangles.empty())
    wrap_bvh = TriangleBvh::Build(options.wrap->welded_positions, options.wrap->welded_triangles);
  std::vector<Curve> spines;
  for (std::size_t i = 0; i < description.parts.size(); ++i) {
    const PartDescription& d = description.parts[i];
    if (!d.skin) {
      RigPart part = SkinlessPart(d, description, rig, spines);
      Result<Curve> spine = BuildSpineCurve(part.spine_points);
      if (!spine) return Error{"part '" + d.name + "': " + spine.error()};
      spines.push_back(std::move(spine).value());
      PartReport report;
      report.name = d.name;
      built.report.parts.push_back(report);
      rig.parts.push_back(std::move(part));
      continue;
    }
    Curve central;
    const auto interpolation =
        d.central_curve.size() >= 3 ? CurveInterpolation::kCubic : CurveInterpolation::kLinear;
    if (Status s = Curve::Build(d.central_curve, false, interpolation, &central); !s)
      return Error{"part '" + d.name + "': central curve: " + ToString(s)};
    const TriangleBvh part_bvh =
        TriangleBvh::Build(mesh.welded_positions, mesh.welded_triangles, parts.part_triangles[i]);
    ProfileRequest request;
    request.central_curve = &central;
    request.profile_count = d.profile_count;
    request.points_per_profile = d.points_per_profile;
    request.part_bvh = &part_bvh;
    request.mesh_bvh = &mesh_bvh;
    request.wrap_bvh = wrap_bvh ? &*wrap_bvh : nullptr;
    request.triangle_part = parts.triangle_part;
    request.part = int(i);
    request.positions = mesh.welded_positions;
    request.triangles = mesh.welded_triangles;
    request.inward_facing = inward_facing;
    ProfileSet profiles = GenerateProfiles(request);

    RigPart part;
    part.name = d.name;
    part.central_curve = d.central_curve;
    part.profile_count = d.profile_count;
    part.points_per_profile = d.points_per_profile;
    part.profiles = std::move(profiles.profiles);
    part.spine_points = SpinePoints(part.profiles, profiles.foreign_points);
    Result<Curve> spine = BuildSpineCurve(part.spine_points);
    if (!spine) {
      *failed = int(i);
      return Error{"part '" + d.name + "': " + std::to_string(part.profiles.size()) + " of " +
                   std::to_string(d.profile_count) +
                   " profiles hit its surface; is its central curve inside the mesh? (" +
                   spine.error() + ")"};
    }
    if (Status s = AssignWires(part, description.material, options.skin_thickness); !s) {
      char thickness[32];
      std::snprintf(thickness, sizeof thickness, "%g", options.skin_thickness);
      return Error{"part '" + d.name + "': skin thickness " + thickness +
                   " m: its wire sections: " + ToString(s)};
    }
    part.joint = d.joint;
    if (!d.parent.empty()) {
      for (std::size_t p = 0; p < i; ++p)
        if (description.parts[p].name == d.parent) part.parent = int(p);
      part.attachment = ClosestParameter(spines[part.parent], part.spine_points.front());
    }
    spines.push_back(std::move(spine).value());

    PartReport report;
    report.name = d.name;
    report.vertices =
        std::size_t(std::count(parts.vertex_part.begin(), parts.vertex_part.end(), int(i)));
    report.triangles = parts.part_triangles[i].size();
    report.profiles = profiles.diagnostics;
    Warn(built.report, d.name, profiles.diagnostics);
    built.report.parts.push_back(report);
    rig.parts.push_back(std::move(part));
  }
  if (parts.occluded_fallbacks)
    built.report.warnings.push_back(
        std::to_string(parts.occluded_fallbacks) +
        " vertices are hidden from every central curve by the surface itself (concave "
        "detail) and went to the nearest curve");
  if (parts.far_vertices)
    built.report.notes.push_back(
        std::to_string(parts.far_vertices) +
        " vertices lay over 3 times a part's typical distance from its curve and went to the "
        "nearest part above or beside it");
  if (parts.island_vertices)
    built.report.notes.push_back(
        std::to_string(parts.island_vertices) +
        " vertices lay in islands of a part's skin inside another part's and joined the part "
        "around them");
  return built;
}

}  // namespace

Result<BuiltRig> BuildRig(const Mesh& mesh, const RigDescription& description,
                          const std::string& mesh_path, const RigBuildOptions& options) {
  RigDescription attempt = description;
  std::vector<std::string> dropped;
  for (;;) {
    int failed = -1;
    Result<BuiltRig> built = BuildRigOnce(mesh, attempt, mesh_path, options, &failed);
    if (built || !options.drop_parts_without_profiles || failed < 0) {
      if (built)
        for (const std::string& d : dropped) built.value().report.warnings.push_back(d);
      return built;
    }
    if (failed == 0) {  // the root: its largest child becomes the root and takes its skin
      std::optional<RigDescription> rerooted = WithoutRoot(attempt);
      if (!rerooted) return built;
      dropped.push_back(built.error() + "; dropped: its skin follows '" + rerooted->parts[0].name +
                        "', the new root");
      attempt = std::move(*rerooted);
      continue;
    }
    const PartDescription& part = attempt.parts[std::size_t(failed)];
    dropped.push_back(built.error() + "; dropped: its skin follows '" + part.parent + "'");
    attempt = WithoutPart(attempt, std::size_t(failed));
  }
}

}  // namespace wirerig
