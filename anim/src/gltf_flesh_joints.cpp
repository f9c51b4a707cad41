#include "gltf_flesh_joints.h"
#include "gltf_skin_weights.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "motion_rotation.h"

namespace wirerig::gltf {
namespace {

constexpr std::size_t kPathKeys = 64;  // keys a residual path is compared over, at most
constexpr int kClusterRounds = 12;     // Lloyd rounds of the spherical k-means
constexpr double kAlike = 0.9;         // paths this alike (cosine) or more share a seed

Vec3 RestPosition(const BaseVertices& base, std::size_t v) {
  return Eigen::Map<const Eigen::Vector3f>(&base.positions[v * 3]).cast<double>();
}

// The rigid x -> R x + t minimising sum |R a_i + t - b_i|^2 (Kabsch: the rotation nearest to
// the centred points' covariance).
RigidTransform Kabsch(std::span<const Vec3> a, std::span<const Vec3> b) {
  Vec3 ca = Vec3::Zero(), cb = Vec3::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) ca += a[i], cb += b[i];
  ca /= double(a.size()), cb /= double(b.size());
  Mat3 covariance = Mat3::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) covariance += (b[i] - cb) * (a[i] - ca).transpose();
  const Mat3 r = NearestRotation(covariance);
  return {Quat(r), cb - r * ca};
}

}  // namespace

FleshJoints FindFleshJoints(const SkinInfluences& influences, const BaseVertices& base,
                            const BakedAnimation& bake, std::span<const RigidTransform> rest,
                            std::span<const Mat3> rotation, std::span<const Vec3> translation,
                            std::size_t budget, double min_error) {
  FleshJoints out;
  const std::size_t joints = rest.size(), keys = bake.KeyCount(), vertices = base.Count();
  const std::size_t slots = influences.slots;
  if (budget == 0 || keys == 0 || joints == 0) return out;
  const std::size_t stride = (keys + kPathKeys - 1) / kPathKeys;
  std::vector<std::size_t> path_keys;
  for (std::size_t k = 0; k < keys; k += stride) path_keys.push_back(k);
  const auto dims = static_cast<Eigen::Index>(3 * path_keys.size());

  // The missed vertices' residual paths (unit columns) and their lengths.
  std::vector<std::uint32_t> missed;
  std::vector<double> length;
  std::vector<Eigen::VectorXd> paths;
  Eigen::VectorXd path(dims);
  for (std::size_t v = 0; v < vertices; ++v) {
    const Vec3 r = RestPosition(base, v);
    double worst = 0.0;
    std::size_t next = 0;
    for (std::size_t k = 0; k < keys; ++k) {
      const Vec3 skinned =
          SkinnedByTransforms(influences, v, r, rotation.subspan(k * joints, joints),
                              translation.subspan(k * joints, joints));
      const Vec3 miss = bake.positions[k * vertices + v].cast<double>() - skinned;
      worst = std::max(worst, miss.norm());
      if (next < path_keys.size() && path_keys[next] == k)
        path.segment<3>(static_cast<Eigen::Index>(3 * next++)) = miss;
    }
    const double norm = path.norm();
    if (!(worst > min_error) || !(norm > 0.0)) continue;
    missed.push_back(static_cast<std::uint32_t>(v));
    length.push_back(norm);
    paths.push_back(path / norm);
  }
  if (missed.size() < kMinFleshMembers) return out;

  // Seeds, farthest first: the longest path, then each time the path least like the seeds so
  // far, weighed by its length, among those less than kAlike like any (deterministic, so bakes
  // stay byte-identical).
  std::vector<Eigen::VectorXd> centres;
  std::vector<double> likeness(missed.size(), -std::numeric_limits<double>::infinity());
  for (std::size_t c = 0; c < budget; ++c) {
    std::size_t pick = 0;
    double best = -1.0;
    for (std::size_t i = 0; i < missed.size(); ++i) {
      if (likeness[i] >= kAlike) continue;
      const double score = centres.empty() ? length[i] : length[i] * (1.0 - likeness[i]);
      if (score > best) best = score, pick = i;
    }
    if (!(best > 0.0)) break;
    centres.push_back(paths[pick]);
    for (std::size_t i = 0; i < missed.size(); ++i)
      likeness[i] = std::max(likeness[i], paths[i].dot(centres.back()));
  }
  // Spherical k-means: each path to its most alike centre, each centre the direction of its
  // members' paths summed at their lengths.
  std::vector<std::size_t> member_of(missed.size(), 0);
  for (int round = 0; round < kClusterRounds; ++round) {
    for (std::size_t i = 0; i < missed.size(); ++i) {
      double best = -std::numeric_limits<double>::infinity();
      for (std::size_t c = 0; c < centres.size(); ++c) {
        const double like = paths[i].dot(centres[c]);
        if (like > best) best = like, member_of[i] = c;
      }
    }
    std::vector<Eigen::VectorXd> sums(centres.size(), Eigen::VectorXd::Zero(dims));
    for (std::size_t i = 0; i < missed.size(); ++i) sums[member_of[i]] += length[i] * paths[i];
    for (std::size_t c = 0; c < centres.size(); ++c)
      if (sums[c].norm() > 0.0) centres[c] = sums[c].normalized();
  }

  // A joint per cluster large enough, under the joint that moves its vertices most.
  std::vector<std::vector<std::uint32_t>> clusters(centres.size());
  for (std::size_t i = 0; i < missed.size(); ++i) clusters[member_of[i]].push_back(missed[i]);
  std::erase_if(clusters, [](const auto& members) { return members.size() < kMinFleshMembers; });
  const std::size_t added = clusters.size();
  out.rotation.resize(keys * added);
  out.translation.resize(keys * added);
  std::vector<Vec3> from, to;
  for (std::size_t n = 0; n < added; ++n) {
    std::vector<double> share(joints, 0.0);
    Vec3 centroid = Vec3::Zero();
    from.clear();
    for (std::uint32_t v : clusters[n]) {
      for (std::size_t s = 0; s < slots; ++s)
        share[influences.joints[v * slots + s]] += influences.weights[v * slots + s];
      from.push_back(RestPosition(base, v));
      centroid += from.back();
    }
    const auto parent =
        static_cast<std::size_t>(std::max_element(share.begin(), share.end()) - share.begin());
    out.parent.push_back(static_cast<int>(parent));
    out.rest.push_back({rest[parent].rotation, centroid / double(clusters[n].size())});
    for (std::size_t k = 0; k < keys; ++k) {
      to.clear();
      for (std::uint32_t v : clusters[n])
        to.push_back(bake.positions[k * vertices + v].cast<double>());
      const RigidTransform fit = Kabsch(from, to);
      out.rotation[k * added + n] = fit.rotation.toRotationMatrix();
      out.translation[k * added + n] = fit.translation;
    }
  }
  return out;
}

}  // namespace wirerig::gltf
