#include "wirerig/rig/rig_model_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "joint_growth.h"
#include "joint_skin_spread.h"
#include "loose_pieces.h"
#include "wirerig/rig/spine_curves.h"
#include "wirerig/runtime/joint_bridge.h"
#include "wirerig/runtime/rig_evaluation.h"
#include "wirerig/runtime/spine_interpolation.h"

namespace wirerig {
namespace {

// v of the point of the sampled spine polyline closest to p.
double ProjectOnSamples(const std::vector<Vec3>& samples, const Vec3& p) {
  const std::size_t n = samples.size();
  double best_distance = std::numeric_limits<double>::max(), best_v = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const Vec3 a = samples[k], ab = samples[k + 1] - a;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    const double d = (a + t * ab - p).squaredNorm();
    if (d < best_distance) best_distance = d, best_v = (double(k) + t) / double(n - 1);
  }
  return best_v;
}

// Mass properties of the solid a tube of closed loops encloses (each loop the same number of
// points, in order from `first_centre` to `last_centre`, which fan-cap its ends); an empty
// MassProperties when the loops do not close a solid.
MassProperties LoopSolid(const std::vector<std::vector<Vec3>>& loops, const Vec3& first_centre,
                         const Vec3& last_centre, double density) {
  const std::size_t m = loops.front().size();
  std::vector<Vec3> positions;
  for (const std::vector<Vec3>& loop : loops)
    positions.insert(positions.end(), loop.begin(), loop.end());
  const auto first = std::uint32_t(positions.size());
  positions.push_back(first_centre);
  positions.push_back(last_centre);
  std::vector<Triangle> triangles;
  const auto count = std::uint32_t(loops.size());
  const auto mm = std::uint32_t(m);
  for (std::uint32_t k = 0; k + 1 < count; ++k)
    for (std::uint32_t j = 0; j < mm; ++j) {
      const std::uint32_t a = k * mm + j, b = k * mm + (j + 1) % mm;
      const std::uint32_t c = a + mm, d = b + mm;
      triangles.push_back({a, b, d});
      triangles.push_back({a, d, c});
    }
  for (std::uint32_t j = 0; j < mm; ++j) {
    triangles.push_back({first, (j + 1) % mm, j});
    triangles.push_back({first + 1, (count - 1) * mm + j, (count - 1) * mm + (j + 1) % mm});
  }
  MassProperties mass;
  if (ComputeSolidMassProperties(positions, triangles, density, &mass)) return mass;
  // Rays turn the other way round: the loops' orientation made the surface face inwards.
  for (Triangle& t : triangles) std::swap(t[1], t[2]);
  if (ComputeSolidMassProperties(positions, triangles, density, &mass)) return mass;
  return {};
}

// A skinless bone's mass: a solid rod along its bone, kSkinlessRodRadius x its length in radius
// (an octagonal prism): articulated dynamics need every body to have some.
MassProperties SkinlessRod(const RigPart& part, double density) {
  constexpr int kSides = 8;
  const Vec3 a = part.spine_points.front(), b = part.spine_points.back();
  const Vec3 axis = (b - a).normalized();
  const Vec3 x = axis.unitOrthogonal(), y = axis.cross(x);
  const double r = kSkinlessRodRadius * (b - a).norm();
  std::vector<std::vector<Vec3>> loops;
  for (const Vec3& end : {a, b}) {
    std::vector<Vec3>& loop = loops.emplace_back();
    for (int k = 0; k < kSides; ++k) {
      const double angle = 2.0 * std::acos(-1.0) * k / kSides;
      loop.push_back(end + r * (std::cos(angle) * x + std::sin(angle) * y));
    }
  }
  return LoopSolid(loops, a, b, density);
}

// Mass properties of the solid the part's closed profiles enclose (a tube of their loops with
// fan caps); an empty MassProperties when the profiles are open or differ in point count.
MassProperties ProfileSolid(const RigPart& part, double density) {
  if (part.profiles.empty()) return SkinlessRod(part, density);
  const std::size_t m = part.profiles.front().points.size();
  std::vector<std::vector<Vec3>> loops;
  for (const ProfileCurve& p : part.profiles) {
    if (!p.closed || p.points.size() != m) return {};
    loops.push_back(p.points);
  }
  return LoopSolid(loops, part.spine_points.front(), part.spine_points.back(), density);
}

// The limb's radius at its root: the smallest mean distance from the spine to a profile's
// points among the profiles of the part's first half (the first profiles of a thigh or an upper
// arm also take in the buttock or the shoulder), m.
double RootRadius(const PartModel& part) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const ProfileModel& profile : part.profiles) {
    if (profile.spine_v > 0.5 && std::isfinite(smallest)) break;
    double sum = 0.0;
    for (const Vec3& q : profile.local_points) sum += q.head<2>().norm();
    if (!profile.local_points.empty())
      smallest = std::min(smallest, sum / double(profile.local_points.size()));
  }
  return std::isfinite(smallest) ? smallest : 0.0;
}

// A hinge whose bones meet at more than this at rest (radians) bends its bridge with them.
constexpr double kBentAtRest = 0.35;

// The length of part `i`'s bone, m: from its joint to the farthest of its children's joints,
// or its spine's length where that is longer (a leaf: the spine only). A spine runs between
// its first and last profiles, so it is shorter than the bone of a short segment between two
// joints (a spine segment's 8 cm spine in a 12 cm bone).
double BoneLength(const RigModel& model, std::size_t i) {
  const PartModel& part = model.parts[i];
  double length = part.spine_length;
  for (const PartModel& child : model.parts)
    if (child.parent == int(i))
      length = std::max(length, (child.spine_points.front() - part.spine_points.front()).norm());
  return length;
}

// The joint of a part with a parent: axes from the bone's rest direction and the described
// axis, limits and type as described, the skin bridge's size from the limb. `bone`: the
// part's BoneLength; `parent`: the part's parent, `skin_parent` its nearest skinned ancestor
// (SkinParent: the parent unless that is a skinless bone), whose flesh the bridge meets.
// A skinless bone's own joint has no limb: its bridge is only the blend of its two sides' rigid
// motions (skinless_spread.h), half its bone long, with no radius.
Result<JointModel> MakeJoint(const PartModel& part, double bone, const PartModel& parent,
                             const PartModel& skin_parent, const JointDescription& description) {
  JointModel joint;
  joint.type = description.type;
  joint.min_degrees = description.min_degrees;
  joint.max_degrees = description.max_degrees;
  const Vec3 z = part.spine_frames.front().tangent.normalized();
  Vec3 x = description.axis ? description.axis->normalized() : part.spine_frames.front().normal;
  x -= x.dot(z) * z;
  if (x.norm() < 1e-6)
    return Error{"joint/axis: lies along the bone; a hinge or bend axis must cross it"};
  x.normalize();
  joint.axes.col(0) = x;
  joint.axes.col(1) = z.cross(x);
  joint.axes.col(2) = z;
  if (IsSkinless(part)) {
    joint.parent_axis = z;
    joint.blend_length = kSkinlessBlendFraction * part.spine_length;
    if (Status s = ValidateJoint(joint); !s)
      return Error{"joint/" + std::string(s.field) + ": " + std::string(s.reason)};
    return joint;
  }
  joint.radius = RootRadius(part);
  // A child continuing its parent's chain (hung from the parent's spine end) meets the
  // parent's own flesh there: the parent's radius at its last profile, within 1-1.6 of the
  // child's. A branch off a parent's side (a shoulder on a chest) meets only its own.
  joint.parent_radius = joint.radius;
  const bool continues =
      &parent == &skin_parent && part.attachment > 0.85 &&
      (part.spine_points.front() - parent.spine_points.back()).norm() < 2.0 * joint.radius;
  joint.parent_axis = z;
  // A hinge bent at rest (an elbow): the bridge bends with it, entering along the parent's bone.
  const Vec3 parent_bone = (part.spine_points.front() - parent.spine_points.front()).normalized();
  if (continues && joint.type == JointType::kHinge && parent_bone.dot(z) < std::cos(kBentAtRest))
    joint.parent_axis = parent_bone;
  if (continues) {
    double sum = 0.0;
    for (const Vec3& q : skin_parent.profiles.back().local_points) sum += q.head<2>().norm();
    const double last =
        sum / double(std::max<std::size_t>(1, skin_parent.profiles.back().local_points.size()));
    joint.parent_radius = std::clamp(last, joint.radius, 1.6 * joint.radius);
  }
  joint.blend_length = description.blend_length.value_or(std::min(
      {(continues ? kBlendRadii : kBranchBlendRadii) * joint.radius, kBlendMaxFraction * bone,
       parent.parent >= 0
           ? kBlendMaxFraction * (part.spine_points.front() - parent.spine_points.front()).norm()
           : std::numeric_limits<double>::infinity()}));
  if (Status s = ValidateJoint(joint); !s)
    return Error{"joint/" + std::string(s.field) + ": " + std::string(s.reason)};
  return joint;
}

// Where p projects on a part's spine (v) and how far from it (m).
struct SpineProjection {
  double v = 0.0, distance = 0.0;
};
SpineProjection ProjectOnSpine(const PartModel& part, const Vec3& p) {
  SpineProjection out;
  out.v = ProjectOnSamples(part.spine_points, p);
  Vec3 point;
  InterpolateSpine(part.spine_points, part.spine_frames, out.v, &point);
  out.distance = (p - point).norm();
  return out;
}

// The part a vertex at p should follow: its assigned part, unless p lies beyond that part's
// end profiles (a cap) but around another part's spine (within kAroundRadii of its largest
// radius) and nearer to it than kNearer times its distance to its own spine: part assignment by the
// nearest visible central curve can hand skin to a curve that sees it from inside the body (an ear
// to the chest, the throat to the chest when the chin hides it from the neck's curve), and a
// chain's skin must follow its bone.
// A ball around each part's spine samples: a lower bound of the distance to the spine.
struct SpineBounds {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
};
std::vector<SpineBounds> BoundSpines(const RigModel& model) {
  std::vector<SpineBounds> out;
  for (const PartModel& part : model.parts) {
    SpineBounds b;
    for (const Vec3& q : part.spine_points) b.centre += q;
    b.centre /= double(part.spine_points.size());
    for (const Vec3& q : part.spine_points) b.radius = std::max(b.radius, (q - b.centre).norm());
    out.push_back(b);
  }
  return out;
}

int NeighbourAround(const RigModel& model, const std::vector<SpineBounds>& bounds, int own,
                    const Vec3& p) {
  constexpr double kAroundRadii = 1.5;
  constexpr double kNearer = 0.8;
  const PartModel& part = model.parts[std::size_t(own)];
  const SpineProjection mine = ProjectOnSpine(part, p);
  int best = own;
  double best_distance = kNearer * mine.distance;
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const PartModel& other = model.parts[i];
    if (int(i) == own) continue;
    const double lower = (p - bounds[i].centre).norm() - bounds[i].radius;
    if (lower >= best_distance || lower >= kAroundRadii * other.max_radius) continue;
    const SpineProjection there = ProjectOnSpine(other, p);
    if (there.distance < kAroundRadii * other.max_radius && there.distance < best_distance) {
      best = int(i);
      best_distance = there.distance;
    }
  }
  return best;
}

// The joint bridges of the vertex at p owned by part `own` (its own joint's and its children's;
// the strongest kJointInfluences).
// `rest_bridges`: per part, its joint's bridge at rest (unused for the root).
void BindJoints(const RigModel& model, const std::vector<RestBridge>& rest_bridges,
                std::uint32_t own, std::uint32_t sample, const Vec3& p, VertexAttachment* a) {
  a->joints = {};
  for (std::size_t c = 1; c < model.parts.size(); ++c) {
    const PartModel& child = model.parts[c];
    if (IsSkinless(child)) continue;  // its bridge only blends: SpreadSkinlessJoints
    JointSide side;
    if (c == own)
      side = JointSide::kChild;
    else if (SkinParent(model, c) == int(own))
      side = JointSide::kParent;
    else
      continue;  // another part: its own motion
    // Skin a side claimed up to one bridge half-length across the joint follows the other side.
    const double reach = child.joint.blend_length;
    const JointBinding b = BindToJoint(child.joint, rest_bridges[c], p, side, reach);
    if (!(b.weight > 0.0)) continue;
    AddJointInfluence(model, {int(c), sample, b.u, b.weight, b.bridge, b.section}, a);
  }
}

// The rig's geometry (central curves, profile origins and points, spine points) lies within the
// mesh's box grown by kRigReach of its diagonal on every side; else the first point that does
// not is named ("part 'arm': profiles[3].points[5]: ...").
std::string CheckRigWithinMesh(const Mesh& mesh, const Rig& rig) {
  if (mesh.welded_positions.empty()) return {};
  Vec3 low = mesh.welded_positions.front(), high = low;
  for (const Vec3& p : mesh.welded_positions) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const double diagonal = (high - low).norm();
  const double reach = kRigReach * diagonal;
  auto outside = [&](const Vec3& p) {
    for (int c = 0; c < 3; ++c)
      if (!(p[c] >= low[c] - reach && p[c] <= high[c] + reach)) return true;  // NaN too
    return false;
  };
  auto name = [](const std::string& field, std::size_t i) {
    return field + "[" + std::to_string(i) + "]";
  };
  auto refuse = [&](const RigPart& part, const std::string& field, const Vec3& p) {
    char text[256];
    std::snprintf(text, sizeof text,
                  ": (%.4g, %.4g, %.4g) m lies far outside the mesh's box (more than %g x its "
                  "diagonal, %.4g m, beyond it): a rig for another mesh, or other units?",
                  p.x(), p.y(), p.z(), kRigReach, diagonal);
    return "part '" + part.name + "': " + field + text;
  };
  for (const RigPart& part : rig.parts) {
    for (std::size_t i = 0; i < part.central_curve.size(); ++i)
      if (outside(part.central_curve[i]))
        return refuse(part, name("central_curve", i), part.central_curve[i]);
    for (std::size_t i = 0; i < part.spine_points.size(); ++i)
      if (outside(part.spine_points[i]))
        return refuse(part, name("spine_points", i), part.spine_points[i]);
    for (std::size_t j = 0; j < part.profiles.size(); ++j) {
      const ProfileCurve& profile = part.profiles[j];
      if (outside(profile.origin))
        return refuse(part, name("profiles", j) + ".origin", profile.origin);
      for (std::size_t i = 0; i < profile.points.size(); ++i)
        if (outside(profile.points[i]))
          return refuse(part, name("profiles", j) + name(".points", i), profile.points[i]);
    }
  }
  return {};
}

}  // namespace

void SetWireProperties(const Rig& rig, RigModel* model) {
  for (std::size_t i = 0; i < rig.parts.size() && i < model->parts.size(); ++i) {
    const RigPart& part = rig.parts[i];
    PartModel& out = model->parts[i];
    out.spine_stiffness = ComputeStiffness(part.spine_wire.material, part.spine_wire.section);
    out.mass = ProfileSolid(part, part.spine_wire.material.density);
    for (std::size_t p = 0; p < out.profiles.size() && p < part.profile_wires.size(); ++p)
      out.profiles[p].stiffness =
          ComputeStiffness(part.profile_wires[p].material, part.profile_wires[p].section);
  }
}

Result<BuiltRigModel> BuildRigModel(const Mesh& mesh, const Rig& rig,
                                    const RigModelOptions& options) {
  if (mesh.welded_positions.size() != rig.mesh_vertices ||
      mesh.welded_triangles.size() != rig.mesh_triangles)
    return Error{"the mesh has " + std::to_string(mesh.welded_positions.size()) + " vertices and " +
                 std::to_string(mesh.welded_triangles.size()) +
                 " triangles; the rig was built for " + std::to_string(rig.mesh_vertices) +
                 " and " + std::to_string(rig.mesh_triangles)};
  if (std::string far = CheckRigWithinMesh(mesh, rig); !far.empty()) return Error{far};
  BuiltRigModel built;
  RigModel& model = built.model;
  model.triangles = mesh.welded_triangles;
  for (const RigPart& part : rig.parts) {
    PartModel out;
    out.name = part.name;
    out.parent = part.parent;
    out.attachment = part.attachment;
    // A skinless bone is rigid: no flesh to bend it.
    out.kind = part.skin ? options.spine_kind : SpineKind::kRigid;
    Result<Curve> spine = BuildSpineCurve(part.spine_points);
    if (!spine) return Error{"part '" + part.name + "': " + spine.error()};
    const int samples = std::max(options.min_spine_samples, 4 * int(part.profiles.size()));
    out.spine_points.resize(std::size_t(samples));
    spine.value().Resample(out.spine_points);
    out.spine_frames.resize(std::size_t(samples));
    PropagateSpineFrames(out.spine_points, spine.value().FrameAt(0.0), out.spine_frames);
    out.spine_length = spine.value().length();
    for (std::size_t p = 0; p < part.profiles.size(); ++p) {
      ProfileModel profile;
      profile.spine_v = ProjectOnSamples(out.spine_points, part.spine_points[p]);
      profile.closed = part.profiles[p].closed;
      Vec3 origin;
      const Mat3 axes =
          FrameAxes(InterpolateSpine(out.spine_points, out.spine_frames, profile.spine_v, &origin));
      for (const Vec3& q : part.profiles[p].points) {
        profile.local_points.push_back(axes.transpose() * (q - origin));
        out.max_radius = std::max(out.max_radius, profile.local_points.back().head<2>().norm());
      }
      out.profiles.push_back(std::move(profile));
    }
    model.parts.push_back(std::move(out));
  }
  SetWireProperties(rig, &model);
  for (std::size_t i = 1; i < model.parts.size(); ++i) {
    PartModel& part = model.parts[i];
    Result<JointModel> joint =
        MakeJoint(part, BoneLength(model, i), model.parts[std::size_t(part.parent)],
                  model.parts[std::size_t(SkinParent(model, i))], rig.parts[i].joint);
    if (!joint) return Error{"part '" + part.name + "': " + joint.error()};
    part.joint = joint.value();
  }

  // Vertex bindings, against the model's own rest geometry (so rest is reproduced exactly).
  std::vector<std::vector<std::vector<Vec3>>> rest_profiles(model.parts.size());
  std::vector<std::vector<Vec3>> rest_origins(model.parts.size());
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    for (std::size_t k = 0; k < model.parts[i].profiles.size(); ++k) {
      Vec3 origin;
      rest_profiles[i].push_back(RestProfilePoints(model.parts[i], k, &origin));
      rest_origins[i].push_back(origin);
    }
  }
  model.vertices.resize(mesh.welded_positions.size());
  std::vector<std::uint32_t> own_samples(mesh.welded_positions.size());
  const std::vector<SpineBounds> spine_bounds = BoundSpines(model);
  std::vector<RestBridge> rest_bridges(model.parts.size());
  for (std::size_t i = 1; i < model.parts.size(); ++i)
    rest_bridges[i] = MakeRestBridge(RestBridgeEnds(model.parts[i]));
  for (std::size_t v = 0; v < mesh.welded_positions.size(); ++v) {
    const Vec3& p = mesh.welded_positions[v];
    VertexAttachment& a = model.vertices[v];
    a.part = std::uint32_t(NeighbourAround(model, spine_bounds, rig.vertex_part[v], p));
    built.report.reowned_vertices += int(a.part) != rig.vertex_part[v];
    const PartModel& part = model.parts[a.part];
    const double s = ProjectOnSamples(part.spine_points, p);
    own_samples[v] = std::uint32_t(std::lround(s * double(part.spine_points.size() - 1)));
    BindJoints(model, rest_bridges, a.part, own_samples[v], p, &a);
    const std::size_t last = part.profiles.size() - 1;
    std::size_t pair = 0;
    while (pair + 1 < last && part.profiles[pair + 1].spine_v <= s) ++pair;
    a.cap = s <= part.profiles.front().spine_v || s >= part.profiles.back().spine_v;
    if (a.cap) ++built.report.cap_vertices;
    if (!a.cap) {
      a.profile = std::uint32_t(pair);
      const WirePolyline wire_i{rest_profiles[a.part][pair], part.profiles[pair].closed};
      const WirePolyline wire_j{rest_profiles[a.part][pair + 1], part.profiles[pair + 1].closed};
      if (BindToWirePair(p, wire_i, wire_j, rest_origins[a.part][pair],
                         rest_origins[a.part][pair + 1], &a.pair)) {
        built.report.flagged_vertices += a.pair.flags != 0;
        continue;
      }
      ++built.report.fallback_vertices;
      a.cap = true;
    }
    // Rigidly with a profile's frame: the nearer end profile for caps; for a pair the binding
    // refused, the nearer profile of the pair.
    if (s <= part.profiles.front().spine_v) {
      a.profile = 0;
    } else if (s >= part.profiles.back().spine_v) {
      a.profile = std::uint32_t(last);
    } else {
      const bool lower = s - part.profiles[pair].spine_v <= part.profiles[pair + 1].spine_v - s;
      a.profile = std::uint32_t(lower ? pair : pair + 1);
    }
    Vec3 origin;
    const Mat3 axes = FrameAxes(InterpolateSpine(part.spine_points, part.spine_frames,
                                                 part.profiles[a.profile].spine_v, &origin));
    a.cap_local = axes.transpose() * (p - origin);
  }
  const LoosePieces loose = BindLoosePieces(mesh, &model);
  built.report.loose_pieces = loose.pieces;
  built.report.loose_vertices = loose.vertices;
  // The spread walks the mesh's edges from joint-bound skin: it never reaches a loose piece.
  const LostInfluences lost = SpreadJointBindings(mesh.welded_positions, own_samples, &model);
  built.report.lost_joint_influences = lost.count;
  built.report.strongest_lost_influence = lost.strongest;
  for (const VertexAttachment& a : model.vertices)
    built.report.bridged_vertices += a.joints[0].joint >= 0;
  FitJointGrowth(mesh.welded_positions, &model);
  return built;
}

}  // namespace wirerig
