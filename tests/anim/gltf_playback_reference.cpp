#include "gltf_playback_reference.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <Eigen/Geometry>

namespace wirerig::testing {
namespace {

using Affine = Eigen::Affine3d;

// Where t falls: between keys `key` and key + 1 at fraction `u` (u = 0 at and beyond the ends).
struct Segment {
  std::size_t key = 0;
  double u = 0.0;
};

Segment FindSegment(const std::vector<double>& times, double t) {
  if (t <= times.front()) return {0, 0.0};
  if (t >= times.back()) return {times.size() - 1, 0.0};
  const auto next = std::upper_bound(times.begin(), times.end(), t);
  const auto key = static_cast<std::size_t>(next - times.begin()) - 1;
  return {key, (t - times[key]) / (times[key + 1] - times[key])};
}

// The joints of the bake's spines in export order: parent joint (-1 for a root) and, per key,
// the world transform.
struct Joints {
  std::vector<int> parent;
  std::vector<Affine> rest;   // #J world at rest
  std::vector<Affine> world;  // #K x #J world per key, key-major
};

Affine Frame(const Quat& rotation, const Vec3& point) {
  Affine frame = Affine::Identity();
  frame.linear() = rotation.normalized().toRotationMatrix();
  frame.translation() = point;
  return frame;
}

Joints CollectJoints(const BakedAnimation& bake) {
  Joints joints;
  std::vector<int> first;
  for (const BakedSpine& spine : bake.spines) {
    first.push_back(static_cast<int>(joints.parent.size()));
    for (std::size_t s = 0; s < spine.SampleCount(); ++s) {
      const int previous = static_cast<int>(joints.parent.size()) - 1;
      const int root = spine.parent < 0 ? -1 : first[spine.parent] + spine.parent_joint;
      joints.parent.push_back(s == 0 ? root : previous);
      joints.rest.push_back(Frame(spine.rest_rotations[s], spine.rest_points[s]));
    }
  }
  for (std::size_t k = 0; k < bake.KeyCount(); ++k) {
    for (const BakedSpine& spine : bake.spines) {
      const std::size_t n = spine.SampleCount();
      for (std::size_t s = 0; s < n; ++s) {
        joints.world.push_back(Frame(spine.rotations[k * n + s], spine.points[k * n + s]));
      }
    }
  }
  return joints;
}

// Joint world transforms at `segment`: locals at both keys interpolated, composed down.
std::vector<Affine> JointWorlds(const Joints& joints, const Segment& segment, std::size_t keys) {
  const std::size_t count = joints.parent.size();
  const std::size_t next = std::min(segment.key + 1, keys - 1);
  auto local = [&](std::size_t key, std::size_t j) {
    const Affine& world = joints.world[key * count + j];
    const int parent = joints.parent[j];
    return parent < 0 ? world : Affine(joints.world[key * count + parent].inverse() * world);
  };
  std::vector<Affine> worlds(count);
  for (std::size_t j = 0; j < count; ++j) {
    const Affine a = local(segment.key, j);
    const Affine b = local(next, j);
    const Quat qa(a.linear());
    Quat qb(b.linear());
    if (qa.dot(qb) < 0.0) qb.coeffs() = -qb.coeffs();
    Affine blended = Affine::Identity();
    blended.linear() = qa.slerp(segment.u, qb).normalized().toRotationMatrix();
    blended.translation() = (1.0 - segment.u) * a.translation() + segment.u * b.translation();
    const int parent = joints.parent[j];
    worlds[j] = parent < 0 ? blended : Affine(worlds[static_cast<std::size_t>(parent)] * blended);
  }
  return worlds;
}

// Per joint G_j B_j^-1 (#J), for `worlds` = G.
std::vector<Affine> SkinMatrices(const Joints& joints, const std::vector<Affine>& worlds) {
  std::vector<Affine> matrices;
  for (std::size_t j = 0; j < worlds.size(); ++j) {
    matrices.push_back(worlds[j] * joints.rest[j].inverse());
  }
  return matrices;
}

// Vertex v's blended matrix sum_i w_i S_{j_i}, weights normalized.
Affine Blend(const BakedAnimation& bake, const std::vector<Affine>& skin, std::size_t v) {
  const Vec4f& w = bake.skin_weights[v];
  const double sum = static_cast<double>(w.sum());
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  for (int i = 0; i < 4; ++i) {
    m += static_cast<double>(w[i]) / sum * skin[bake.skin_joints[v][i]].matrix();
  }
  return Affine(m);
}

// The residual at `key` of vertex v at rest position p.
Vec3 Residual(const BakedAnimation& bake, const std::vector<Affine>& skin, std::size_t key,
              std::size_t v, const Vec3& p) {
  const Affine m = Blend(bake, skin, v);
  const Vec3 miss = bake.positions[key * bake.vertex_count + v].cast<double>() - m * p;
  const Mat3 a = m.linear();
  return std::abs(a.determinant()) < 1e-9 ? miss : Vec3(a.inverse() * miss);
}

std::vector<Vec3> MorphPositions(const BakedAnimation& bake, const Segment& s) {
  const std::size_t n = bake.vertex_count;
  const std::size_t next = std::min(s.key + 1, bake.KeyCount() - 1);
  std::vector<Vec3> out;
  for (std::size_t v = 0; v < n; ++v) {
    out.push_back((1.0 - s.u) * bake.positions[s.key * n + v].cast<double>() +
                  s.u * bake.positions[next * n + v].cast<double>());
  }
  return out;
}

std::vector<Vec3> SkinPositions(const Mesh& mesh, const BakedAnimation& bake, const Segment& s,
                                bool residual) {
  const Joints joints = CollectJoints(bake);
  const std::size_t keys = bake.KeyCount();
  const std::vector<Affine> now = SkinMatrices(joints, JointWorlds(joints, s, keys));
  std::vector<Affine> at_key;
  std::vector<Affine> at_next;
  if (residual) {
    at_key = SkinMatrices(joints, JointWorlds(joints, {s.key, 0.0}, keys));
    at_next = SkinMatrices(joints, JointWorlds(joints, {std::min(s.key + 1, keys - 1), 0.0}, keys));
  }
  std::vector<Vec3> out;
  for (std::size_t v = 0; v < bake.vertex_count; ++v) {
    Vec3 p = mesh.positions[v];
    if (residual) {
      const std::size_t next = std::min(s.key + 1, keys - 1);
      p += (1.0 - s.u) * Residual(bake, at_key, s.key, v, mesh.positions[v]) +
           s.u * Residual(bake, at_next, next, v, mesh.positions[v]);
    }
    out.push_back(Blend(bake, now, v) * p);
  }
  return out;
}

}  // namespace

std::vector<double> FloatKeyTimes(const BakedAnimation& bake) {
  std::vector<double> times;
  for (double t : bake.times) times.push_back(static_cast<double>(static_cast<float>(t)));
  return times;
}

std::vector<Vec3> GltfPositionsAt(const Mesh& mesh, const BakedAnimation& bake,
                                  GltfPlayback playback, double t) {
  const Segment segment = FindSegment(FloatKeyTimes(bake), t);
  if (playback == GltfPlayback::kMorph) return MorphPositions(bake, segment);
  return SkinPositions(mesh, bake, segment, playback == GltfPlayback::kSkinResidual);
}

}  // namespace wirerig::testing
