#include "wirerig/anim/spine_skin.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>

namespace wirerig {
namespace {

std::string Indexed(const char* field, std::size_t i) {
  std::string s = field;
  s.append("[").append(std::to_string(i)).append("]");
  return s;
}

std::optional<std::string> CheckInput(const RigModel& model, const Mesh& mesh,
                                      const SpineSkinOptions& options) {
  if (!(options.spread >= 1.0 && options.spread <= 2.0))
    return "options.spread: must lie in [1, 2]";
  if (mesh.weld_map.size() != mesh.positions.size()) {
    return "mesh.weld_map: not one entry per render vertex (weld the mesh first)";
  }
  if (model.vertices.size() != mesh.welded_positions.size()) {
    return "model.vertices: not one attachment per welded vertex of the mesh";
  }
  for (std::size_t r = 0; r < mesh.weld_map.size(); ++r) {
    if (mesh.weld_map[r] >= mesh.welded_positions.size()) {
      return Indexed("mesh.weld_map", r).append(": beyond the welded vertices");
    }
  }
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    // A skinless bone (no profiles) has joints but weighs no vertex.
    if (model.parts[p].spine_points.size() < 2 || model.parts[p].profiles.size() == 1) {
      return Indexed("model.parts", p).append(": fewer than 2 spine points or profiles");
    }
  }
  for (std::size_t w = 0; w < model.vertices.size(); ++w) {
    const VertexAttachment& a = model.vertices[w];
    if (a.part >= model.parts.size())
      return Indexed("model.vertices", w).append(".part: out of range");
    const std::size_t profiles = model.parts[a.part].profiles.size();
    if (a.profile >= profiles || (!a.cap && a.profile + 1 >= profiles)) {
      return Indexed("model.vertices", w).append(".profile: out of range");
    }
    const Vec3& p = mesh.welded_positions[w];
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
      return Indexed("mesh.welded_positions", w).append(": not finite");
    }
  }
  return std::nullopt;
}

// The spine parameter in [v0, v1] of the point of the rest spine polyline closest to `p`.
double ProjectOntoSpine(const PartModel& part, const Vec3& p, double v0, double v1) {
  const std::size_t n = part.spine_points.size();
  const double last = static_cast<double>(n - 1);
  if (v1 < v0) std::swap(v0, v1);
  double best_v = v0;
  double best_distance = std::numeric_limits<double>::max();
  const auto first = static_cast<std::size_t>(std::clamp(std::floor(v0 * last), 0.0, last - 1.0));
  const auto end = static_cast<std::size_t>(std::clamp(std::ceil(v1 * last), 1.0, last));
  for (std::size_t s = first; s < end; ++s) {
    const Vec3& a = part.spine_points[s];
    const Vec3 ab = part.spine_points[s + 1] - a;
    // Segment parameter range inside [v0, v1], in [0, 1].
    const double lo = std::clamp(v0 * last - static_cast<double>(s), 0.0, 1.0);
    const double hi = std::clamp(v1 * last - static_cast<double>(s), 0.0, 1.0);
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, lo, hi) : lo;
    const double distance = (a + t * ab - p).squaredNorm();
    if (distance < best_distance) {
      best_distance = distance;
      best_v = (static_cast<double>(s) + t) / last;
    }
  }
  return best_v;
}

// Tent weights of the samples around u (sample units), the 4 largest, normalized.
void TentWeights(double u, std::size_t n, double spread, std::uint32_t joint_offset,
                 std::array<std::uint32_t, 4>* joints, Vec4f* weights) {
  std::vector<std::pair<double, std::uint32_t>> tent;
  const auto low = static_cast<long>(std::ceil(u - spread));
  const auto high = static_cast<long>(std::floor(u + spread));
  for (long s = std::max(low, 0L); s <= std::min(high, static_cast<long>(n) - 1); ++s) {
    const double w = 1.0 - std::abs(u - static_cast<double>(s)) / spread;
    if (w > 0.0) tent.emplace_back(w, joint_offset + static_cast<std::uint32_t>(s));
  }
  std::sort(tent.begin(), tent.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  if (tent.size() > 4) tent.resize(4);
  double sum = 0.0;
  for (const auto& t : tent) sum += t.first;
  *joints = {0, 0, 0, 0};
  *weights = Vec4f::Zero();
  for (std::size_t c = 0; c < tent.size(); ++c) {
    (*joints)[c] = tent[c].second;
    (*weights)[static_cast<Eigen::Index>(c)] = static_cast<float>(tent[c].first / sum);
  }
}

}  // namespace

Result<SpineSkin> BuildSpineSkin(const RigModel& model, const Mesh& mesh,
                                 const SpineSkinOptions& options) {
  if (auto problem = CheckInput(model, mesh, options)) return Error{*problem};
  std::vector<std::uint32_t> joint_offset;
  std::uint32_t joints = 0;
  for (const PartModel& part : model.parts) {
    joint_offset.push_back(joints);
    joints += static_cast<std::uint32_t>(part.spine_points.size());
  }
  // Influences per welded vertex, then copied to its render vertices.
  std::vector<std::array<std::uint32_t, 4>> welded_joints(model.vertices.size());
  std::vector<Vec4f> welded_weights(model.vertices.size());
  for (std::size_t w = 0; w < model.vertices.size(); ++w) {
    const VertexAttachment& a = model.vertices[w];
    const PartModel& part = model.parts[a.part];
    const double last = static_cast<double>(part.spine_points.size() - 1);
    if (a.cap) {
      const double v = part.profiles[a.profile].spine_v;
      const auto nearest = static_cast<std::uint32_t>(std::clamp(std::round(v * last), 0.0, last));
      welded_joints[w] = {joint_offset[a.part] + nearest, 0, 0, 0};
      welded_weights[w] = Vec4f(1.0f, 0.0f, 0.0f, 0.0f);
      continue;
    }
    const double v =
        ProjectOntoSpine(part, mesh.welded_positions[w], part.profiles[a.profile].spine_v,
                         part.profiles[a.profile + 1].spine_v);
    TentWeights(v * last, part.spine_points.size(), options.spread, joint_offset[a.part],
                &welded_joints[w], &welded_weights[w]);
  }
  SpineSkin skin;
  for (std::uint32_t w : mesh.weld_map) {
    skin.joints.push_back(welded_joints[w]);
    skin.weights.push_back(welded_weights[w]);
  }
  return skin;
}

}  // namespace wirerig
