// The rest normals the rotated-normal mode (NormalMode::kRotated) turns with each vertex's frame.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "vertex_stage.h"
#include "wirerig/runtime/spine_interpolation.h"

namespace wirerig {

std::vector<Vec3> RestNormalsInSlotFrames(const RigModel& model, const RigEvaluationLayout& layout,
                                          std::span<const std::uint32_t> vertex_of_slot) {
  // The rest wires and spine points by global profile, as the evaluation builds them at rest.
  std::vector<std::vector<Vec3>> wires;
  std::vector<Vec3> origins;
  std::vector<Mat3> cap_axes;
  for (const PartModel& part : model.parts)
    for (std::size_t p = 0; p < part.profiles.size(); ++p) {
      Vec3 origin;
      cap_axes.push_back(FrameAxes(InterpolateSpine(part.spine_points, part.spine_frames,
                                                    part.profiles[p].spine_v, &origin)));
      wires.push_back(RestProfilePoints(part, p, &origin));
      origins.push_back(origin);
    }
  // Rest positions (the bridges move nothing at rest) and each vertex's rest frame.
  const std::size_t n = model.vertices.size();
  std::vector<Vec3> position(n, Vec3::Zero());
  std::vector<Mat3> frame(n, Mat3::Identity());
  for (std::size_t v = 0; v < n; ++v) {
    const VertexAttachment& a = model.vertices[v];
    const std::uint32_t g = layout.profile_base[a.part] + a.profile;
    if (a.cap) {
      frame[v] = cap_axes[g];
      position[v] = origins[g] + cap_axes[g] * a.cap_local;
      continue;
    }
    const PartModel& part = model.parts[a.part];
    const WirePolyline wire_i{wires[g], part.profiles[a.profile].closed};
    const WirePolyline wire_j{wires[g + 1], part.profiles[a.profile + 1].closed};
    position[v] = ApplyPairBinding(a.pair, wire_i, wire_j, origins[g], origins[g + 1]);
    ApplyPairFrame(a.pair, wire_i, wire_j, origins[g], origins[g + 1], &frame[v]);
  }
  // Area-weighted vertex normals of the rest mesh, as the triangle pass sums them.
  std::vector<Vec3> normal(n, Vec3::Zero());
  for (const Triangle& t : model.triangles) {
    const Vec3 face = (position[t[1]] - position[t[0]]).cross(position[t[2]] - position[t[0]]);
    for (const std::uint32_t index : t) normal[index] += face;
  }
  std::vector<Vec3> local;
  local.reserve(vertex_of_slot.size());
  for (const std::uint32_t v : vertex_of_slot) {
    const double length = normal[v].norm();
    local.push_back(length > 0.0 ? Vec3(frame[v].transpose() * (normal[v] / length))
                                 : Vec3::Zero());
  }
  return local;
}

}  // namespace wirerig
