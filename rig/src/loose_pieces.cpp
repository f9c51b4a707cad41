#include "loose_pieces.h"

#include <algorithm>
#include <limits>
#include <map>

#include "disjoint_sets.h"
#include "wirerig/runtime/spine_interpolation.h"

namespace wirerig {
namespace {

// Connected pieces of the welded triangles (sharing a vertex joins): a label per vertex.
std::vector<std::uint32_t> Pieces(std::size_t vertex_count,
                                  const std::vector<Triangle>& triangles) {
  DisjointSets sets(vertex_count);
  for (const Triangle& t : triangles) {
    sets.Union(t[0], t[1]);
    sets.Union(t[0], t[2]);
  }
  std::vector<std::uint32_t> root(vertex_count);
  for (std::uint32_t v = 0; v < vertex_count; ++v) root[v] = sets.Find(v);
  return root;
}

}  // namespace

LoosePieces BindLoosePieces(const Mesh& mesh, RigModel* model) {
  const std::vector<Vec3>& positions = mesh.welded_positions;
  LoosePieces out;
  out.loose.assign(positions.size(), 0);
  const std::vector<std::uint32_t> piece = Pieces(positions.size(), mesh.welded_triangles);
  std::map<std::uint32_t, std::vector<std::uint32_t>> members;
  for (std::uint32_t v = 0; v < positions.size(); ++v) members[piece[v]].push_back(v);
  std::size_t largest = 0;
  for (const auto& [label, vertices] : members) largest = std::max(largest, vertices.size());
  const double limit = kLoosePieceFraction * double(positions.size());
  for (const auto& [label, vertices] : members) {
    if (vertices.size() == largest || double(vertices.size()) > limit) continue;
    // The part most of its vertices follow, and the profile nearest its centroid.
    std::map<std::uint32_t, std::size_t> votes;
    Vec3 centroid = Vec3::Zero();
    for (std::uint32_t v : vertices) {
      ++votes[model->vertices[v].part];
      centroid += positions[v];
    }
    centroid /= double(vertices.size());
    const std::uint32_t part_index =
        std::max_element(votes.begin(), votes.end(), [](const auto& a, const auto& b) {
          return a.second < b.second;
        })->first;
    const PartModel& part = model->parts[part_index];
    std::uint32_t profile = 0;
    double nearest = std::numeric_limits<double>::infinity();
    for (std::uint32_t k = 0; k < part.profiles.size(); ++k) {
      Vec3 origin;
      InterpolateSpine(part.spine_points, part.spine_frames, part.profiles[k].spine_v, &origin);
      const double d = (origin - centroid).squaredNorm();
      if (d < nearest) nearest = d, profile = k;
    }
    Vec3 origin;
    const Mat3 axes = FrameAxes(InterpolateSpine(part.spine_points, part.spine_frames,
                                                 part.profiles[profile].spine_v, &origin));
    for (std::uint32_t v : vertices) {
      VertexAttachment& a = model->vertices[v];
      a.part = part_index;
      a.cap = true;
      a.profile = profile;
      a.cap_local = axes.transpose() * (positions[v] - origin);
      a.joints = {};
      out.loose[v] = 1;
    }
    ++out.pieces;
    out.vertices += vertices.size();
  }
  return out;
}

}  // namespace wirerig
