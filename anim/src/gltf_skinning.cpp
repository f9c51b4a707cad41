#include "gltf_skinning.h"

#include <algorithm>
#include <cmath>

namespace wirerig::gltf {

std::vector<Mat4d> JointGlobals(const Skeleton& skeleton, std::span<const Vec3f> translations,
                                std::span<const Quatf> rotations) {
  std::vector<Mat4d> world(skeleton.JointCount());
  for (std::size_t j = 0; j < world.size(); ++j) {
    Mat4d local = Mat4d::Identity();
    local.topLeftCorner<3, 3>() = rotations[j].cast<double>().normalized().toRotationMatrix();
    local.topRightCorner<3, 1>() = translations[j].cast<double>();
    const int p = skeleton.parent[j];
    world[j] = p < 0 ? local : Mat4d(world[static_cast<std::size_t>(p)] * local);
  }
  return world;
}

std::vector<Mat4d> SkinMatrices(const Skeleton& skeleton, std::size_t key) {
  const std::size_t joints = skeleton.JointCount();
  std::vector<Mat4d> skin =
      JointGlobals(skeleton, std::span(skeleton.translations).subspan(key * joints, joints),
                   std::span(skeleton.rotations).subspan(key * joints, joints));
  for (std::size_t j = 0; j < joints; ++j)
    skin[j] = skin[j] * skeleton.inverse_bind[j].cast<double>();
  return skin;
}

Mat4d BlendedSkinMatrix(const SkinInfluences& influences, std::span<const Mat4d> skin_matrices,
                        std::size_t v) {
  Mat4d m = Mat4d::Zero();
  const std::size_t slots = influences.slots;
  for (std::size_t c = 0; c < slots; ++c) {
    const float w = influences.weights[v * slots + c];
    if (w != 0.0f) m += static_cast<double>(w) * skin_matrices[influences.joints[v * slots + c]];
  }
  return m;
}

SkinFit FitSkin(const Skeleton& skeleton, const SkinInfluences& influences,
                const BaseVertices& base, const BakedAnimation& bake, bool residuals,
                bool residual_normals) {
  SkinFit fit;
  const std::size_t keys = bake.KeyCount();
  const std::size_t vertices = base.Count();
  const bool normals =
      residuals && residual_normals && !base.normals.empty() && !bake.normals.empty();
  if (residuals) fit.residual_positions.resize(keys * vertices * 3);
  if (normals) fit.residual_normals.resize(keys * vertices * 3);
  double sum_squares = 0.0;
  for (std::size_t k = 0; k < keys; ++k) {
    const std::vector<Mat4d> skin = SkinMatrices(skeleton, k);
    for (std::size_t v = 0; v < vertices; ++v) {
      const Mat4d m = BlendedSkinMatrix(influences, skin, v);
      const Mat3 a = m.topLeftCorner<3, 3>();
      const Vec3 b = m.topRightCorner<3, 1>();
      const Vec3 p = Eigen::Map<const Eigen::Vector3f>(&base.positions[v * 3]).cast<double>();
      const Vec3 target = bake.positions[k * vertices + v].cast<double>();
      const Vec3 skinned = a * p + b;
      const double error = (skinned - target).norm();
      fit.max_error = std::max(fit.max_error, error);
      sum_squares += error * error;
      if (!residuals) continue;
      const bool invertible = std::abs(a.determinant()) >= 1e-9;
      const Mat3 a_inverse = invertible ? Mat3(a.inverse()) : Mat3::Identity();
      const Eigen::Vector3f r = (a_inverse * (target - skinned)).cast<float>();
      std::copy(r.data(), r.data() + 3, &fit.residual_positions[(k * vertices + v) * 3]);
      const Vec3 corrected = a * (p + r.cast<double>()) + b;
      fit.residual_max_error = std::max(fit.residual_max_error, (corrected - target).norm());
      if (normals) {
        const Vec3 n = Eigen::Map<const Eigen::Vector3f>(&base.normals[v * 3]).cast<double>();
        const Eigen::Vector3f dn =
            (a_inverse * bake.normals[k * vertices + v].cast<double>() - n).cast<float>();
        std::copy(dn.data(), dn.data() + 3, &fit.residual_normals[(k * vertices + v) * 3]);
      }
    }
  }
  fit.rms_error = std::sqrt(sum_squares / static_cast<double>(keys * vertices));
  return fit;
}

}  // namespace wirerig::gltf
