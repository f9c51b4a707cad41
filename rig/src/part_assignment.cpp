#include "wirerig/rig/part_assignment.h"

#include <algorithm>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "part_tree.h"
#include "wirerig/io/name_hint.h"

namespace wirerig {
namespace {

struct CurveProjection {
  double distance = std::numeric_limits<double>::max();
  Vec3 point = Vec3::Zero();
  bool at_root = false;  // the closest point is the curve's first point
};

CurveProjection Project(const std::vector<Vec3>& curve, const Vec3& p) {
  CurveProjection best;
  for (std::size_t k = 0; k + 1 < curve.size(); ++k) {
    const Vec3 a = curve[k], ab = curve[k + 1] - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    const Vec3 q = a + t * ab;
    const double d = (p - q).norm();
    if (d < best.distance) best = {d, q, k == 0 && t == 0.0};
  }
  return best;
}

// True if the segment from `from` to `to` leaves the mesh before reaching `to`.
bool Occluded(const TriangleBvh& bvh, const Vec3& from, const Vec3& to) {
  const Vec3 d = to - from;
  const double length = d.norm();
  if (length <= 0.0) return false;
  const double margin = 1e-4 * length + 1e-9;
  return bvh.Raycast(from, d / length, margin, length - margin).has_value();
}

int MajorityPart(const std::vector<int>& vertex_part, const Triangle& t) {
  const int a = vertex_part[t[0]], b = vertex_part[t[1]], c = vertex_part[t[2]];
  if (b == c && b != a) return b;
  return a;
}

// With clean_assignment: a child part's skin lies within a few of its typical distances from its
// curve (the median over its vertices). A vertex of a child part more than kFarFromCurve times
// that from its curve goes to the nearest part that sees it, other than the child and the parts
// below it: a rump nearest a tail that lies along it, a chest nearest a leg's curve passing
// under it. Returns how many moved.
constexpr double kFarFromCurve = 3.0;
std::size_t ReturnFarVertices(const Mesh& mesh, const RigDescription& description,
                              const TriangleBvh& bvh, const std::vector<bool>& fixed,
                              const std::vector<bool>& restricted, const std::vector<int>& parent,
                              std::vector<int>* vertex_part) {
  const std::size_t part_count = description.parts.size();
  std::vector<int>& part = *vertex_part;
  std::vector<std::vector<double>> own(part_count);
  std::vector<double> distance(part.size(), 0.0);
  for (std::size_t v = 0; v < part.size(); ++v) {
    if (fixed[v]) continue;
    const std::size_t q = std::size_t(part[v]);
    distance[v] = Project(description.parts[q].central_curve, mesh.welded_positions[v]).distance;
    own[q].push_back(distance[v]);
  }
  std::vector<double> typical(part_count, 0.0);
  for (std::size_t q = 0; q < part_count; ++q) {
    if (own[q].empty()) continue;
    const auto middle = own[q].begin() + long(own[q].size() / 2);
    std::nth_element(own[q].begin(), middle, own[q].end());
    typical[q] = *middle;
  }
  std::size_t moved = 0;
  std::vector<CurveProjection> projections(part_count);
  std::vector<std::pair<double, int>> others;
  for (std::size_t v = 0; v < part.size(); ++v) {
    const int q = part[v];
    if (fixed[v] || parent[std::size_t(q)] < 0 ||
        !(distance[v] > kFarFromCurve * typical[std::size_t(q)]))
      continue;
    const Vec3& p = mesh.welded_positions[v];
    others.clear();
    for (std::size_t i = 0; i < part_count; ++i) {
      if (restricted[i] || AtOrBelow(parent, int(i), q)) continue;
      projections[i] = Project(description.parts[i].central_curve, p);
      others.emplace_back(projections[i].distance, int(i));
    }
    std::sort(others.begin(), others.end());
    for (const auto& [d, i] : others) {
      if (Occluded(bvh, projections[std::size_t(i)].point, p)) continue;
      part[v] = i;
      ++moved;
      break;
    }
  }
  return moved;
}

}  // namespace

Result<std::vector<bool>> FindPassiveTriangles(const Mesh& mesh,
                                               const RigDescription& description) {
  std::vector<bool> passive(mesh.welded_triangles.size(), false);
  for (const std::string& name : description.passive_mesh_parts) {
    bool found = false;
    for (const MeshPart& mesh_part : mesh.parts) {
      if (mesh_part.name != name) continue;
      found = true;
      for (std::uint32_t f = 0; f < mesh_part.triangle_count; ++f)
        passive[mesh_part.first_triangle + f] = true;
    }
    if (!found) {
      std::vector<std::string> names;
      for (const MeshPart& mesh_part : mesh.parts) names.push_back(mesh_part.name);
      return Error{"passive mesh part '" + name + "' is not in the mesh" +
                   NameHint(name, names, "mesh parts")};
    }
  }
  return passive;
}

std::vector<std::uint32_t> ActiveTriangles(const std::vector<bool>& passive) {
  std::vector<std::uint32_t> active;
  for (std::size_t f = 0; f < passive.size(); ++f)
    if (!passive[f]) active.push_back(std::uint32_t(f));
  return active;
}

Result<PartAssignment> AssignParts(const Mesh& mesh, const RigDescription& description,
                                   const TriangleBvh& active_bvh,
                                   const std::vector<bool>& passive) {
  const std::size_t vertex_count = mesh.welded_positions.size();
  const std::size_t part_count = description.parts.size();
  PartAssignment result;
  result.vertex_part.assign(vertex_count, -1);

  if (!description.vertex_part.empty()) {
    if (description.vertex_part.size() != vertex_count)
      return Error{"vertex_part has " + std::to_string(description.vertex_part.size()) +
                   " entries for " + std::to_string(vertex_count) + " welded vertices"};
    result.vertex_part = description.vertex_part;
  }
  // Vertices the user assigned (by index or by mesh part) keep their part.
  std::vector<bool> fixed(vertex_count);
  for (std::size_t v = 0; v < vertex_count; ++v) fixed[v] = result.vertex_part[v] >= 0;

  // Parts that claim mesh parts by name take their vertices outright.
  std::map<std::string, int> claimed_by;
  for (std::size_t p = 0; p < part_count; ++p)
    for (const std::string& name : description.parts[p].mesh_parts) claimed_by[name] = int(p);
  std::vector<bool> restricted(part_count, false);
  for (std::size_t p = 0; p < part_count; ++p)  // skinless parts take no vertices at all
    restricted[p] = !description.parts[p].mesh_parts.empty() || !description.parts[p].skin;
  for (const MeshPart& mesh_part : mesh.parts) {
    const auto it = claimed_by.find(mesh_part.name);
    if (it == claimed_by.end()) continue;
    for (std::uint32_t f = 0; f < mesh_part.triangle_count; ++f)
      for (std::uint32_t w : mesh.welded_triangles[mesh_part.first_triangle + f]) {
        result.vertex_part[w] = it->second;
        fixed[w] = true;
      }
  }
  for (const auto& [name, part] : claimed_by) {
    // A reference of its own: lambdas capture no structured bindings before clang 16.
    const std::string& wanted = name;
    const bool found = std::any_of(mesh.parts.begin(), mesh.parts.end(),
                                   [&](const MeshPart& m) { return m.name == wanted; });
    if (!found)
      return Error{"part '" + description.parts[part].name + "' names mesh part '" + name +
                   "', which the mesh does not have"};
  }

  // The rest: the nearest visible central curve. A child whose closest point is its own root
  // end (the vertex lies behind the joint, e.g. torso skin behind the shoulder) is taken only
  // when no other curve sees the vertex. Curves more than kFarther times as far as the nearest
  // one are never taken: a curve end lying outside the surface (a fingertip) sees far-away
  // skin through the air (a hand would take the toes of the other foot).
  constexpr double kFarther = 3.0;
  std::vector<std::pair<double, int>> order(part_count);
  std::vector<CurveProjection> projections(part_count);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    if (result.vertex_part[v] >= 0) continue;
    const Vec3& p = mesh.welded_positions[v];
    std::size_t candidates = 0;
    for (std::size_t i = 0; i < part_count; ++i) {
      if (restricted[i]) continue;
      projections[i] = Project(description.parts[i].central_curve, p);
      order[candidates++] = {projections[i].distance, int(i)};
    }
    if (candidates == 0) continue;
    std::sort(order.begin(), order.begin() + long(candidates));
    auto behind_child_root = [&](int i) {
      return projections[i].at_root && !description.parts[i].parent.empty();
    };
    int chosen = -1;
    for (int pass = 0; pass < 2 && chosen < 0; ++pass)
      for (std::size_t c = 0; c < candidates && chosen < 0; ++c) {
        const int i = order[c].second;
        if (order[c].first > kFarther * order[0].first) break;
        if (behind_child_root(i) == (pass == 0)) continue;
        if (!Occluded(active_bvh, projections[i].point, p)) chosen = i;
      }
    if (chosen < 0) {
      chosen = order[0].second;
      ++result.occluded_fallbacks;
    }
    result.vertex_part[v] = chosen;
  }
  for (int& part : result.vertex_part)
    if (part < 0) part = 0;  // no unrestricted part could take it: the root keeps it
  if (description.clean_assignment) {
    std::vector<int> parent(part_count, -1);
    for (std::size_t p = 0; p < part_count; ++p)
      for (std::size_t q = 0; q < p; ++q)
        if (description.parts[q].name == description.parts[p].parent) parent[p] = int(q);
    result.far_vertices = ReturnFarVertices(mesh, description, active_bvh, fixed, restricted,
                                            parent, &result.vertex_part);
    result.island_vertices =
        MergePartIslands(mesh.welded_triangles, parent, fixed, restricted, &result.vertex_part);
  }

  // Triangles of passive mesh parts belong to a part but are not among its ray targets.
  result.triangle_part.resize(mesh.welded_triangles.size());
  result.part_triangles.assign(part_count, {});
  for (std::size_t f = 0; f < mesh.welded_triangles.size(); ++f) {
    const int part = MajorityPart(result.vertex_part, mesh.welded_triangles[f]);
    result.triangle_part[f] = part;
    if (!passive[f]) result.part_triangles[part].push_back(std::uint32_t(f));
  }
  return result;
}

}  // namespace wirerig
