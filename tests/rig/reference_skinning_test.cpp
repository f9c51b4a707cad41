// The baselines of the joint-skin comparison (reference_skinning.h) against their textbook
// formulas evaluated here in double: linear blend skinning sum_k w_k (R_k p + t_k) with the
// normal renormalised, and dual-quaternion skinning of one bone (a rigid motion) and of two bones
// turned alike (the translations blend).
#include <gtest/gtest.h>

#include <random>

#include "wirerig/rig/reference_skinning.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

BoneMatrix ToBone(const Mat3& r, const Vec3& t) {
  BoneMatrix m{};
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) m[std::size_t(4 * row + col)] = float(r(row, col));
    m[std::size_t(4 * row + 3)] = float(t[row]);
  }
  return m;
}

struct Bone {
  Mat3 r;
  Vec3 t;
};

// n vertices with random positions, unit normals and 4 random influences over `bones`.
ReferenceSkin RandomSkin(std::size_t n, std::size_t bones, std::mt19937& random) {
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0), weight(0.0, 1.0);
  std::uniform_int_distribution<int> bone(0, int(bones) - 1);
  ReferenceSkin skin;
  for (std::size_t v = 0; v < n; ++v) {
    const Vec3 p(coordinate(random), coordinate(random), coordinate(random));
    const Vec3 normal =
        Vec3(coordinate(random), coordinate(random), coordinate(random) + 2.0).normalized();
    skin.x.push_back(float(p.x())), skin.y.push_back(float(p.y())), skin.z.push_back(float(p.z()));
    skin.nx.push_back(float(normal.x())), skin.ny.push_back(float(normal.y())),
        skin.nz.push_back(float(normal.z()));
    std::array<std::uint16_t, ReferenceSkin::kInfluences> ids{};
    std::array<float, ReferenceSkin::kInfluences> ws{};
    double sum = 0.0;
    std::array<double, ReferenceSkin::kInfluences> raw{};
    for (int k = 0; k < ReferenceSkin::kInfluences; ++k)
      sum += raw[std::size_t(k)] = weight(random);
    for (int k = 0; k < ReferenceSkin::kInfluences; ++k) {
      ids[std::size_t(k)] = std::uint16_t(bone(random));
      ws[std::size_t(k)] = float(raw[std::size_t(k)] / sum);
    }
    skin.bones.push_back(ids);
    skin.weights.push_back(ws);
  }
  skin.cx = skin.x, skin.cy = skin.y, skin.cz = skin.z;
  return skin;
}

std::vector<Bone> RandomBones(std::size_t count, std::mt19937& random) {
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  std::vector<Bone> bones;
  for (std::size_t b = 0; b < count; ++b) {
    const Vec3 axis = Vec3(coordinate(random), coordinate(random), coordinate(random)).normalized();
    bones.push_back({Eigen::AngleAxisd(1.2 * coordinate(random), axis).toRotationMatrix(),
                     Vec3(coordinate(random), coordinate(random), coordinate(random))});
  }
  return bones;
}

struct Output {
  std::vector<float> x, y, z, nx, ny, nz;
  explicit Output(std::size_t n) : x(n), y(n), z(n), nx(n), ny(n), nz(n) {}
};

Output Skin(ReferenceSkinning method, const ReferenceSkin& skin, const std::vector<Bone>& bones) {
  std::vector<BoneMatrix> matrices;
  for (const Bone& b : bones) matrices.push_back(ToBone(b.r, b.t));
  Output out(skin.x.size());
  const ReferenceSkinningJob job{method, &skin,  matrices, out.x, out.y,
                                 out.z,  out.nx, out.ny,   out.nz};
  job.Run();
  return out;
}

TEST(ReferenceSkinning, LinearBlendIsTheWeightedSumOfTheBonesMotions) {
  std::mt19937 random(7);
  const std::vector<Bone> bones = RandomBones(9, random);
  const ReferenceSkin skin = RandomSkin(1001, bones.size(), random);  // odd: no whole packs
  const Output out = Skin(ReferenceSkinning::kLinearBlend, skin, bones);
  for (std::size_t v = 0; v < skin.x.size(); ++v) {
    const Vec3 p(skin.x[v], skin.y[v], skin.z[v]), n(skin.nx[v], skin.ny[v], skin.nz[v]);
    Vec3 position = Vec3::Zero(), normal = Vec3::Zero();
    for (int k = 0; k < ReferenceSkin::kInfluences; ++k) {
      const double w = skin.weights[v][std::size_t(k)];
      const Bone& b = bones[skin.bones[v][std::size_t(k)]];
      position += w * (b.r * p + b.t);
      normal += w * (b.r * n);
    }
    normal.normalize();
    EXPECT_NEAR(out.x[v], position.x(), 2e-6) << v;
    EXPECT_NEAR(out.y[v], position.y(), 2e-6) << v;
    EXPECT_NEAR(out.z[v], position.z(), 2e-6) << v;
    EXPECT_NEAR(out.nx[v], normal.x(), 2e-5) << v;
    EXPECT_NEAR(out.ny[v], normal.y(), 2e-5) << v;
    EXPECT_NEAR(out.nz[v], normal.z(), 2e-5) << v;
  }
}

TEST(ReferenceSkinning, DualQuaternionsMoveASingleBonesSkinRigidlyAndBlendTranslations) {
  std::mt19937 random(11);
  std::vector<Bone> bones = RandomBones(2, random);
  ReferenceSkin skin = RandomSkin(64, bones.size(), random);
  // Every vertex on bone 0 alone: the bone's rigid motion.
  for (auto& w : skin.weights) w = {1.0f, 0.0f, 0.0f, 0.0f};
  for (auto& b : skin.bones) b = {0, 1, 1, 1};
  Output out = Skin(ReferenceSkinning::kDualQuaternion, skin, bones);
  for (std::size_t v = 0; v < skin.x.size(); ++v) {
    const Vec3 expected = bones[0].r * Vec3(skin.x[v], skin.y[v], skin.z[v]) + bones[0].t;
    EXPECT_NEAR(out.x[v], expected.x(), 1e-5);
    EXPECT_NEAR(out.y[v], expected.y(), 1e-5);
    EXPECT_NEAR(out.z[v], expected.z(), 1e-5);
  }
  // Two bones turned alike, translated apart, weights w and 1 - w: R p + the blended translation.
  bones[1].r = bones[0].r;
  for (std::size_t v = 0; v < skin.x.size(); ++v)
    skin.weights[v] = {float(v) / 63.0f, 1.0f - float(v) / 63.0f, 0.0f, 0.0f};
  out = Skin(ReferenceSkinning::kDualQuaternion, skin, bones);
  for (std::size_t v = 0; v < skin.x.size(); ++v) {
    const double w = skin.weights[v][0];
    const Vec3 expected = bones[0].r * Vec3(skin.x[v], skin.y[v], skin.z[v]) + w * bones[0].t +
                          (1.0 - w) * bones[1].t;
    EXPECT_NEAR(out.x[v], expected.x(), 1e-5);
    EXPECT_NEAR(out.y[v], expected.y(), 1e-5);
    EXPECT_NEAR(out.z[v], expected.z(), 1e-5);
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
