// The skin mode's decomposition (few joints fitted to the bake, weights solved, corrective
// shapes) against animations whose answer is known: a two-bone elbow made by linear blend
// skinning with known weights (the decomposition must find the blend the bake's own weights do
// not have), a bending tube (a deformable part gets a chain of joints within its budget) and a
// bulge no joint can make (the corrective shapes carry it, as many as its rank).
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/SVD>

#include "support/test_folder.h"
#include "wirerig/anim/gltf_export.h"
#include "wirerig/procedural/shapes.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;

constexpr double kLength = 1.0;  // the tube along +y, two parts of half the length each
constexpr int kKeys = 11;

Quat Bend(double angle) { return Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ())); }

// An elbow: the lower part still, the upper part turned about the joint at y = L/2 by up to
// 90 degrees; each vertex moves by the blend (1 - b) lower + b upper, b = smoothstep over
// [0.35, 0.65] L. The bake's own weights bind each vertex to its own part only (as a rig's
// spine skin does), so only a fit of the weights finds the blend.
struct Elbow {
  Mesh mesh;
  BakedAnimation bake;
};

double Blend(double y) {
  const double t = std::clamp((y - 0.35) / 0.3, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// `bulge`: a swelling of the middle, in the rest pose (before the joints move it), growing
// and shrinking with the keys: rank one over the keys. `true_weights`: the bake carries the
// blend itself instead of the own-part weights. `swept`: each vertex turns about the joint by
// the blended angle b * angle (a bend that keeps the elbow's section, as a wire bridge does)
// instead of moving by the blended positions, which linear blend skinning of the two sides
// cannot do (halfway through a 90 degree bend their blend shrinks the section to 71 %).
Elbow MakeElbow(double bulge = 0.0, bool true_weights = false, bool swept = false) {
  Elbow e;
  e.mesh = MakeCylinder(0.08, kLength, 16, 20);
  const Vec3 joint(0.0, kLength / 2.0, 0.0);
  BakedAnimation& bake = e.bake;
  bake.name = "elbow";
  bake.vertex_count = e.mesh.positions.size();
  for (int k = 0; k < kKeys; ++k) {
    const double s = double(k) / (kKeys - 1);
    const Quat turn = Bend(s * std::numbers::pi / 2.0);
    bake.times.push_back(k / 10.0);
    for (const Vec3& rest : e.mesh.positions) {
      const Vec3 radial(rest.x(), 0.0, rest.z());
      const Vec3 p = rest + bulge * std::sin(std::numbers::pi * s * 3.0) *
                                std::exp(-std::pow((rest.y() - 0.5) / 0.1, 2)) * radial;
      const double b = Blend(rest.y());
      const Vec3 moved = swept ? Vec3(joint + Bend(b * s * std::numbers::pi / 2.0) * (p - joint))
                               : Vec3((1.0 - b) * p + b * (joint + turn * (p - joint)));
      bake.positions.push_back(moved.cast<float>());
    }
  }
  for (int i = 0; i < 2; ++i) {
    BakedSpine spine;
    spine.name = i == 0 ? "lower" : "upper";
    spine.parent = i - 1;
    spine.parent_joint = i == 0 ? 0 : 2;
    for (int s = 0; s < 3; ++s) {
      spine.rest_points.emplace_back(0.0, kLength / 2.0 * (i + s / 2.0), 0.0);
      spine.rest_rotations.push_back(Quat::Identity());
    }
    for (int k = 0; k < kKeys; ++k) {
      const Quat turn =
          i == 0 ? Quat::Identity() : Bend(double(k) / (kKeys - 1) * std::numbers::pi / 2.0);
      for (const Vec3& rest : spine.rest_points) {
        spine.points.push_back(i == 0 ? rest : Vec3(joint + turn * (rest - joint)));
        spine.rotations.push_back(turn);
      }
    }
    bake.spines.push_back(std::move(spine));
  }
  for (const Vec3& p : e.mesh.positions) {
    const std::uint32_t own = p.y() < kLength / 2.0 ? 0u : 3u;
    const float b = float(Blend(p.y()));
    bake.skin_joints.push_back(true_weights ? std::array<std::uint32_t, 4>{0, 3, 0, 0}
                                            : std::array<std::uint32_t, 4>{own, 0, 0, 0});
    bake.skin_weights.push_back(true_weights ? Vec4f(1.0f - b, b, 0.0f, 0.0f)
                                             : Vec4f(1.0f, 0.0f, 0.0f, 0.0f));
  }
  return e;
}

// What storing the skin costs a 1 m elbow: rotation keys as normalized shorts (each component
// within 0.5 / 32767, so the angle within 6.1e-5 rad, times a reach of at most 0.5 m: 3.1e-5 m)
// and weights as normalized unsigned shorts (within 0.5 / 65535, times the at most 0.7 m the two
// joints move a vertex apart: 5.3e-6 m).
constexpr double kStoredRounding = 3.7e-5;  // m

GltfExportReport Export(const Elbow& e, const GltfExportOptions& options, const char* name) {
  testing::TestFolder dir;
  const Result<GltfExportReport> report = ExportGltf(e.mesh, e.bake, options, dir.path() / name);
  EXPECT_TRUE(report.ok()) << report.error();
  return report.ok() ? report.value() : GltfExportReport{};
}

// The bones alone (no flesh joints: FleshJointsCarryJigglingRings tests those).
GltfExportOptions SkinOptions() {
  GltfExportOptions options;
  options.mode = GltfAnimationMode::kSkin;
  options.max_correctives = 0;
  options.flesh_joints = false;
  return options;
}

// Two rigid parts: a joint each, and a bridge joint at the elbow. The bake's weights (own part
// only) leave the elbow's skin 6 cm off; the decomposition recovers the known blend to the
// rounding of the stored skin.
TEST(SkinDecomposition, RecoversAnElbowMadeByLinearBlendSkinning) {
  const Elbow elbow = MakeElbow();
  GltfExportOptions options = SkinOptions();
  options.fit_skin = false;
  const GltfExportReport unfitted = Export(elbow, options, "unfitted.glb");
  options.fit_skin = true;
  const GltfExportReport fitted = Export(elbow, options, "fitted.glb");
  EXPECT_EQ(unfitted.joint_count, 3u);
  EXPECT_EQ(fitted.joint_count, 3u);
  EXPECT_GT(unfitted.skin_max_error, 0.03);
  EXPECT_LT(fitted.skin_max_error, kStoredRounding);
  std::printf("[ measured ] elbow skin error: bake's weights %.3g m, fitted %.3g m\n",
              unfitted.skin_max_error, fitted.skin_max_error);
}

// A swept elbow: the bridge joint, starting at half the turn, carries the bend the two sides'
// blend cannot: the fitted skin's error drops by more than half.
TEST(SkinDecomposition, ABridgeJointCarriesASweptElbow) {
  const Elbow elbow = MakeElbow(0.0, false, /*swept=*/true);
  GltfExportOptions options = SkinOptions();
  options.bridge_joints = false;
  const GltfExportReport sides = Export(elbow, options, "sides.glb");
  options.bridge_joints = true;
  const GltfExportReport bridged = Export(elbow, options, "bridged.glb");
  EXPECT_EQ(sides.joint_count, 2u);
  EXPECT_EQ(bridged.joint_count, 3u);
  EXPECT_LT(bridged.skin_max_error, 0.5 * sides.skin_max_error);
  std::printf("[ measured ] swept elbow skin error: two joints %.3g m, with the bridge %.3g m\n",
              sides.skin_max_error, bridged.skin_max_error);
}

// A bend along the whole tube: both parts deform (no rigid part), so each gets a chain of
// joints, at most max_joints_per_part, and the whole skin at most max_joints; more joints fit
// the bend better.
TEST(SkinDecomposition, ADeformablePartGetsAChainWithinItsBudget) {
  Elbow e = MakeElbow();
  // Replace the motion by a uniform bend of curvature kappa: each spine sample on the arc.
  const double max_kappa = std::numbers::pi / 2.0 / kLength;
  for (BakedSpine& spine : e.bake.spines) {
    spine.rest_points.clear();
    spine.rest_rotations.clear();
    spine.points.clear();
    spine.rotations.clear();
  }
  e.bake.positions.clear();
  auto on_arc = [](double kappa, double y) {
    if (kappa == 0.0) return Vec3(0.0, y, 0.0);
    return Vec3((1.0 - std::cos(kappa * y)) / kappa, std::sin(kappa * y) / kappa, 0.0);
  };
  constexpr int kSamples = 9;
  for (int i = 0; i < 2; ++i) {
    for (int s = 0; s < kSamples; ++s) {
      const double y = kLength / 2.0 * (i + double(s) / (kSamples - 1));
      e.bake.spines[std::size_t(i)].rest_points.push_back(on_arc(0.0, y));
      e.bake.spines[std::size_t(i)].rest_rotations.push_back(Quat::Identity());
    }
    e.bake.spines[std::size_t(i)].parent_joint = i == 0 ? 0 : kSamples - 1;
  }
  e.bake.skin_joints.clear();
  e.bake.skin_weights.clear();
  for (const Vec3& p : e.mesh.positions) {
    const double u = std::clamp(p.y() / (kLength / 2.0), 0.0, 2.0) * (kSamples - 1);
    const auto spine = std::uint32_t(u >= kSamples - 1 ? 1 : 0);
    const double local = std::min(u - spine * (kSamples - 1), double(kSamples - 1) - 1e-9);
    const auto s = std::uint32_t(std::floor(local));
    const float f = float(local - s);
    const std::uint32_t first = spine * kSamples + s;
    e.bake.skin_joints.push_back(
        {first, std::min(first + 1, spine * kSamples + kSamples - 1), 0, 0});
    e.bake.skin_weights.emplace_back(1.0f - f, f, 0.0f, 0.0f);
  }
  for (int k = 0; k < kKeys; ++k) {
    const double kappa = max_kappa * k / (kKeys - 1);
    for (int i = 0; i < 2; ++i) {
      for (int s = 0; s < kSamples; ++s) {
        const double y = kLength / 2.0 * (i + double(s) / (kSamples - 1));
        e.bake.spines[std::size_t(i)].points.push_back(on_arc(kappa, y));
        e.bake.spines[std::size_t(i)].rotations.push_back(Bend(-kappa * y));
      }
    }
    for (const Vec3& p : e.mesh.positions) {
      const double y = std::clamp(p.y(), 0.0, kLength);
      const Vec3 moved = on_arc(kappa, y) + Bend(-kappa * y) * Vec3(p.x(), 0.0, p.z());
      e.bake.positions.push_back(moved.cast<float>());
    }
  }
  double previous = 1e9;
  for (std::size_t per_part : {2u, 3u, 5u, 9u}) {
    SCOPED_TRACE(per_part);
    GltfExportOptions options = SkinOptions();
    options.max_joints_per_part = per_part;
    const GltfExportReport report = Export(e, options, "chain.glb");
    EXPECT_EQ(report.joint_count, 2 * per_part + 1);  // and the bridge joint between the parts
    EXPECT_LT(report.skin_max_error, previous);
    previous = report.skin_max_error;
  }
  EXPECT_LT(previous, 2e-3);  // a joint at every sample
  // The budget: 6 joints for two parts, 3 each (no room left for the bridge); fewer joints than
  // parts is refused.
  GltfExportOptions options = SkinOptions();
  options.max_joints = 6;
  EXPECT_EQ(Export(e, options, "budget.glb").joint_count, 6u);
  options.max_joints = 1;
  testing::TestFolder dir;
  const Result<GltfExportReport> refused =
      ExportGltf(e.mesh, e.bake, options, dir.path() / "x.glb");
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().find("the rig's 2 parts need a joint each, more than max_joints (1)"),
            std::string::npos)
      << refused.error();
  EXPECT_FALSE(fs::exists(dir.path() / "x.glb"));
}

// Two rings of skin jiggling on the elbow (its exact blend, the upper part turning): a ring
// round the lower part at y = 0.25 swings 2 cm along x at 1.3 Hz, one round the upper part at
// y = 0.8 swings 1.5 cm along its part's z at 2.1 Hz, each falling off along the tube as a
// Gaussian. No bone moves that way, and each ring is exactly a joint that translates its
// vertices with weights of that falloff: the flesh joints find them, and the skin's RMS error
// falls tenfold (its worst by half at least: the fit alternates weights and transforms, and
// keeps its best round by squared error); with no joint left in the budget, none is added.
TEST(SkinDecomposition, FleshJointsCarryJigglingRings) {
  Elbow elbow = MakeElbow(0.0, /*true_weights=*/true);
  const std::size_t vertices = elbow.mesh.positions.size();
  const Vec3 joint(0.0, kLength / 2.0, 0.0);
  for (int k = 0; k < kKeys; ++k) {
    const double t = elbow.bake.times[std::size_t(k)];
    const Quat turn = Bend(double(k) / (kKeys - 1) * std::numbers::pi / 2.0);
    const Vec3 lower_swing = 0.02 * std::sin(2.0 * std::numbers::pi * 1.3 * t) * Vec3::UnitX();
    const Vec3 upper_swing =
        0.015 * std::sin(2.0 * std::numbers::pi * 2.1 * t + 1.0) * Vec3::UnitZ();
    for (std::size_t v = 0; v < vertices; ++v) {
      const double y = elbow.mesh.positions[v].y();
      const Vec3 lower = std::exp(-std::pow((y - 0.25) / 0.06, 2)) * lower_swing;
      const Vec3 upper = turn * (std::exp(-std::pow((y - 0.8) / 0.06, 2)) * upper_swing);
      elbow.bake.positions[std::size_t(k) * vertices + v] += (lower + upper).cast<float>();
    }
  }
  GltfExportOptions options = SkinOptions();
  const GltfExportReport bones = Export(elbow, options, "bones.glb");
  options.flesh_joints = true;
  const GltfExportReport flesh = Export(elbow, options, "flesh.glb");
  options.max_joints = 3;
  const GltfExportReport full = Export(elbow, options, "full.glb");
  EXPECT_EQ(bones.joint_count, 3u);
  EXPECT_GT(bones.skin_max_error, 0.01);
  // A joint per ring at least (and a few for the bones' share of the swing, which the first fit
  // gave them and the refit takes back).
  EXPECT_GE(flesh.joint_count, 5u);
  EXPECT_LE(flesh.joint_count, 12u);
  EXPECT_LT(flesh.skin_rms_error, 0.1 * bones.skin_rms_error);
  EXPECT_LT(flesh.skin_max_error, 0.5 * bones.skin_max_error);
  EXPECT_EQ(full.joint_count, 3u);
  EXPECT_NEAR(full.skin_max_error, bones.skin_max_error, 1e-9);
  std::printf(
      "[ measured ] jiggling rings: bones max %.3g m, RMS %.3g m (%zu joints); with flesh "
      "joints max %.3g m, RMS %.3g m (%zu joints)\n",
      bones.skin_max_error, bones.skin_rms_error, bones.joint_count, flesh.skin_max_error,
      flesh.skin_rms_error, flesh.joint_count);
}

// Key thinning: the elbow turns at a constant rate about one axis, which the reader's slerp
// reproduces between any two keys (so does its bridge joint, at half the rate), and the lower
// part does not move: each track keeps its first and last key, within the tolerance. Without
// thinning every key is stored.
TEST(SkinDecomposition, AJointTurningAtAConstantRateKeepsTwoKeys) {
  const Elbow elbow = MakeElbow(0.0, /*true_weights=*/true);
  GltfExportOptions options = SkinOptions();
  options.fit_skin = false;
  const GltfExportReport every_key = Export(elbow, options, "every.glb");
  options.key_tolerance = 1e-4;
  const GltfExportReport thinned = Export(elbow, options, "thinned.glb");
  EXPECT_EQ(every_key.joint_count, 3u);  // the two parts' joints and the elbow's bridge joint
  EXPECT_EQ(every_key.joint_keys, 3u * kKeys);
  EXPECT_EQ(thinned.joint_keys, 6u);  // the bridge turns at half the rate: two keys too
  EXPECT_LT(thinned.skin_max_error, kStoredRounding + 1e-4);
  std::printf("[ measured ] elbow skin error: every key %.3g m, thinned to 4 keys %.3g m\n",
              every_key.skin_max_error, thinned.skin_max_error);
}

// A swelling no joint makes, of rank one over the keys (a fixed shape times a weight per key),
// on the elbow's exact skin (its true weights and frames, nothing fitted): one corrective
// shape carries it to the rounding of the stored skin; without correctives the skin misses it.
TEST(SkinDecomposition, ACorrectiveShapeCarriesWhatTheJointsCannot) {
  const Elbow elbow = MakeElbow(/*bulge=*/0.5, /*true_weights=*/true);
  GltfExportOptions options = SkinOptions();
  options.fit_skin = false;
  const GltfExportReport skin_only = Export(elbow, options, "skin.glb");
  options.max_correctives = 16;
  options.corrective_error = kStoredRounding;
  const GltfExportReport corrected = Export(elbow, options, "corrected.glb");
  EXPECT_GT(skin_only.skin_max_error, 5e-3);
  EXPECT_EQ(corrected.corrective_count, 1u);
  EXPECT_EQ(corrected.morph_target_count, 1u);
  EXPECT_LT(corrected.corrected_max_error, kStoredRounding);
  // A cap on the shapes is kept, and no shape is added where the skin already meets the bound.
  options.corrective_error = 1.0;
  EXPECT_EQ(Export(elbow, options, "loose.glb").corrective_count, 0u);
}

// An error one key holds (a pose the joints miss once: 8 mm at one vertex of key 7) beside a
// swelling over every key (5 mm at its peak, far more energy): PCA ranks the swelling first, so
// with one shape allowed it leaves the 8 mm; the worst key's own residual as the shape leaves
// only the swelling's other keys (5 mm). With two shapes PCA carries both and is kept.
TEST(SkinDecomposition, ACorrectiveShapeCarriesAnErrorOneKeyHolds) {
  Elbow elbow = MakeElbow(/*bulge=*/0.0625, /*true_weights=*/true);
  std::size_t spike = 0;  // a vertex of the lower part, away from the swelling
  for (std::size_t v = 0; v < elbow.mesh.positions.size(); ++v)
    if (std::abs(elbow.mesh.positions[v].y() - 0.2) <
        std::abs(elbow.mesh.positions[spike].y() - 0.2))
      spike = v;
  const std::size_t vertices = elbow.mesh.positions.size();
  elbow.bake.positions[7 * vertices + spike] += Vec3f(0.008f, 0.0f, 0.0f);
  GltfExportOptions options = SkinOptions();
  options.fit_skin = false;
  options.corrective_error = 1e-4;
  options.max_correctives = 2;
  const GltfExportReport two = Export(elbow, options, "two.glb");
  EXPECT_EQ(two.corrective_count, 2u);
  EXPECT_LT(two.corrected_max_error, 1e-4);
  options.max_correctives = 1;
  const GltfExportReport one = Export(elbow, options, "one.glb");
  EXPECT_EQ(one.corrective_count, 1u);
  EXPECT_LT(one.corrected_max_error, 6e-3);  // PCA's first shape alone leaves the 8 mm
  EXPECT_GT(one.corrected_max_error, 3e-3);  // the swelling's other keys stay
}

// Residual fields that PCA ranks by their energy, summed over the vertices: a broad swelling
// and three narrow bumps of larger amplitude at other places, each with its own rhythm over the
// keys. With two shapes, the best fit in the squared sense (the truncated SVD, computed here on
// the residual as built) carries the swelling and leaves a bump; the shapes the export chooses
// aim at the worst vertex instead (the target is the bound), so they leave less.
TEST(SkinDecomposition, CorrectiveShapesAimAtTheWorstVertex) {
  Elbow elbow = MakeElbow(0.0, /*true_weights=*/true);
  const std::size_t vertices = elbow.mesh.positions.size();
  // Rest-space offsets per key, added before the elbow's own motion (so the skin's bind-space
  // residual is exactly these).
  auto field = [&](std::size_t v, int k) {
    const Vec3& rest = elbow.mesh.positions[v];
    const Vec3 radial = Vec3(rest.x(), 0.0, rest.z()).normalized();
    const double s = double(k) / (kKeys - 1);
    auto bump = [&](double centre, double width) {
      return std::exp(-std::pow((rest.y() - centre) / width, 2));
    };
    const double swelling = 0.002 * bump(0.5, 0.3) * std::sin(std::numbers::pi * s);
    const double a = 0.003 * bump(0.15, 0.04) * std::sin(2.0 * std::numbers::pi * s + 0.3);
    const double b = 0.0028 * bump(0.85, 0.04) * std::cos(3.0 * std::numbers::pi * s);
    const double c = 0.0026 * bump(0.5, 0.03) * std::sin(5.0 * std::numbers::pi * s + 1.0);
    return Vec3((swelling + a + b + c) * radial);
  };
  Eigen::MatrixXd residual(kKeys, 3 * vertices);
  const Vec3 joint(0.0, kLength / 2.0, 0.0);
  for (int k = 0; k < kKeys; ++k) {
    const Quat turn = Bend(double(k) / (kKeys - 1) * std::numbers::pi / 2.0);
    for (std::size_t v = 0; v < vertices; ++v) {
      const Vec3 offset = field(v, k);
      residual.block<1, 3>(k, 3 * v) = offset.transpose();
      const Vec3 p = elbow.mesh.positions[v] + offset;
      const double w = Blend(elbow.mesh.positions[v].y());
      elbow.bake.positions[k * vertices + v] =
          ((1.0 - w) * p + w * (joint + turn * (p - joint))).cast<float>();
    }
  }
  constexpr int kShapes = 2;
  // The truncated SVD's worst vertex: the least squared error any two shapes leave.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(residual, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::MatrixXd best_squares = svd.matrixU().leftCols(kShapes) *
                                       svd.singularValues().head(kShapes).asDiagonal() *
                                       svd.matrixV().leftCols(kShapes).transpose();
  const Eigen::MatrixXd left = residual - best_squares;
  double svd_worst = 0.0;
  for (std::size_t v = 0; v < vertices; ++v)
    svd_worst = std::max(svd_worst, left.middleCols<3>(3 * v).rowwise().norm().maxCoeff());
  GltfExportOptions options = SkinOptions();
  options.fit_skin = false;
  options.max_correctives = kShapes;
  options.corrective_error = 0.8 * svd_worst;
  const GltfExportReport report = Export(elbow, options, "worst.glb");
  EXPECT_EQ(report.corrective_count, std::size_t(kShapes));
  EXPECT_LT(report.corrected_max_error, 0.8 * svd_worst);
  std::printf("[ measured ] two shapes' worst vertex: truncated SVD %.3g m, exported %.3g m\n",
              svd_worst, report.corrected_max_error);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
