// BuildSpineSkin on a hand-made RigModel of a capped cylinder (r = 0.1 m, h = 1 m, rings every
// 1/8 m): one part whose spine runs up the axis, a profile at every ring, ring vertices bound
// between profiles and the two poles as caps. Expected weights are the tent of the header,
// evaluated here from each vertex's height. The skinning error of each spread is measured by
// exporting an analytic bend (the cylinder's axis on circular arcs, cross-sections rigid) in glTF
// skin mode.
#include "wirerig/anim/spine_skin.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "wirerig/anim/gltf_export.h"
#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_model_builder.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr double kHeight = 1.0;
constexpr int kRings = 8;

struct Cylinder {
  Mesh mesh;
  RigModel model;
};

// `samples` spine points on the axis; profile j at ring j (v = j / rings).
Cylinder MakeRiggedCylinder(int samples, int rings = kRings) {
  Cylinder c;
  c.mesh = MakeCylinder(0.1, kHeight, 16, rings);
  PartModel part;
  part.name = "body";
  for (int s = 0; s < samples; ++s) {
    part.spine_points.emplace_back(0.0, kHeight * s / (samples - 1), 0.0);
    part.spine_frames.emplace_back();
  }
  for (int j = 0; j <= rings; ++j) {
    ProfileModel profile;
    profile.spine_v = static_cast<double>(j) / rings;
    part.profiles.push_back(profile);
  }
  c.model.parts.push_back(part);
  for (const Vec3& p : c.mesh.welded_positions) {
    VertexAttachment a;
    const bool pole = std::abs(p.x()) < 1e-12 && std::abs(p.z()) < 1e-12;
    const int ring = static_cast<int>(std::lround(p.y() / kHeight * rings));
    a.cap = pole;
    a.profile = static_cast<std::uint32_t>(pole ? ring : std::min(ring, rings - 1));
    c.model.vertices.push_back(a);
  }
  return c;
}

// The tent weight of sample s for a vertex at height y (n samples, half-width spread).
double Tent(double y, int n, double spread, int s) {
  const double u = y / kHeight * (n - 1);
  return std::max(0.0, 1.0 - std::abs(u - s) / spread);
}

double WeightOf(const SpineSkin& skin, std::size_t v, std::uint32_t joint) {
  double w = 0.0;
  for (std::size_t c = 0; c < 4; ++c) {
    if (skin.joints[v][c] == joint) w += skin.weights[v][static_cast<Eigen::Index>(c)];
  }
  return w;
}

void ExpectValid(const SpineSkin& skin, std::size_t vertices, std::uint32_t joints) {
  ASSERT_EQ(skin.joints.size(), vertices);
  ASSERT_EQ(skin.weights.size(), vertices);
  for (std::size_t v = 0; v < vertices; ++v) {
    SCOPED_TRACE(v);
    EXPECT_NEAR(skin.weights[v].sum(), 1.0f, 1e-6f);
    for (int c = 0; c < 4; ++c) {
      EXPECT_GE(skin.weights[v][c], 0.0f);
      EXPECT_LT(skin.joints[v][static_cast<std::size_t>(c)], joints);
      if (c > 0) {
        EXPECT_LE(skin.weights[v][c], skin.weights[v][c - 1]);
      }
    }
  }
}

TEST(SpineSkin, RingVerticesInterpolateLinearlyBetweenTheirSamples) {
  const Cylinder c = MakeRiggedCylinder(5);  // samples every 1/4 m, rings every 1/8 m
  const Result<SpineSkin> skin = BuildSpineSkin(c.model, c.mesh);
  ASSERT_TRUE(skin.ok()) << skin.error();
  ExpectValid(skin.value(), c.mesh.positions.size(), 5);
  for (std::size_t v = 0; v < c.mesh.positions.size(); ++v) {
    if (c.model.vertices[v].cap) continue;
    SCOPED_TRACE(v);
    for (int s = 0; s < 5; ++s) {
      EXPECT_NEAR(WeightOf(skin.value(), v, static_cast<std::uint32_t>(s)),
                  Tent(c.mesh.positions[v].y(), 5, 1.0, s), 1e-6);
    }
  }
}

TEST(SpineSkin, WiderTentsReachUpToFourSamples) {
  const Cylinder c = MakeRiggedCylinder(9);
  for (double spread : {1.5, 2.0}) {
    SCOPED_TRACE(spread);
    SpineSkinOptions options;
    options.spread = spread;
    const Result<SpineSkin> skin = BuildSpineSkin(c.model, c.mesh, options);
    ASSERT_TRUE(skin.ok()) << skin.error();
    ExpectValid(skin.value(), c.mesh.positions.size(), 9);
    std::size_t four = 0;
    for (std::size_t v = 0; v < c.mesh.positions.size(); ++v) {
      if (c.model.vertices[v].cap) continue;
      const double y = c.mesh.positions[v].y();
      double sum = 0.0;
      for (int s = 0; s < 9; ++s) sum += Tent(y, 9, spread, s);
      for (int s = 0; s < 9; ++s) {
        EXPECT_NEAR(WeightOf(skin.value(), v, static_cast<std::uint32_t>(s)),
                    Tent(y, 9, spread, s) / sum, 1e-6);
      }
      if (skin.value().weights[v][3] > 0.0f) ++four;
    }
    if (spread == 2.0) {
      EXPECT_EQ(four, 0u);  // rings sit on samples: |u - s| < 2 holds for 3 samples only
    }
  }
}

TEST(SpineSkin, VerticesBetweenSamplesWithTheWidestTentUseFour) {
  const Cylinder c = MakeRiggedCylinder(5);  // rings half-way between samples
  SpineSkinOptions options;
  options.spread = 2.0;
  const Result<SpineSkin> skin = BuildSpineSkin(c.model, c.mesh, options);
  ASSERT_TRUE(skin.ok()) << skin.error();
  // Ring 3 (y = 3/8, u = 1.5): samples 0..3 at distances 1.5, 0.5, 0.5, 1.5.
  const std::size_t v = 1 + 3 * 16;
  ASSERT_NEAR(c.mesh.positions[v].y(), 0.375, 1e-12);
  EXPECT_NEAR(WeightOf(skin.value(), v, 0), 0.125, 1e-6);
  EXPECT_NEAR(WeightOf(skin.value(), v, 1), 0.375, 1e-6);
  EXPECT_NEAR(WeightOf(skin.value(), v, 2), 0.375, 1e-6);
  EXPECT_NEAR(WeightOf(skin.value(), v, 3), 0.125, 1e-6);
}

TEST(SpineSkin, CapsGoRigidlyToTheEndProfilesNearestSample) {
  Cylinder c = MakeRiggedCylinder(5);
  c.model.parts[0].profiles.front().spine_v = 0.2;  // u = 0.8: nearest sample 1
  c.model.parts[0].profiles.back().spine_v = 0.8;   // u = 3.2: nearest sample 3
  const Result<SpineSkin> skin = BuildSpineSkin(c.model, c.mesh);
  ASSERT_TRUE(skin.ok()) << skin.error();
  const std::size_t bottom = 0;
  const std::size_t top = c.mesh.positions.size() - 1;
  ASSERT_TRUE(c.model.vertices[bottom].cap);
  ASSERT_TRUE(c.model.vertices[top].cap);
  EXPECT_EQ(skin.value().joints[bottom][0], 1u);
  EXPECT_EQ(skin.value().weights[bottom][0], 1.0f);
  EXPECT_EQ(skin.value().joints[top][0], 3u);
  EXPECT_EQ(skin.value().weights[top][0], 1.0f);
}

TEST(SpineSkin, ProjectionIsLimitedToTheVertexsProfilePair) {
  Cylinder c = MakeRiggedCylinder(5);
  // Bind the ring at y = 1/8 to the pair (4, 5) (v in [0.5, 0.625]): it projects onto v = 0.5.
  const std::size_t v = 1 + 1 * 16;
  c.model.vertices[v].profile = 4;
  const Result<SpineSkin> skin = BuildSpineSkin(c.model, c.mesh);
  ASSERT_TRUE(skin.ok()) << skin.error();
  EXPECT_NEAR(WeightOf(skin.value(), v, 2), 1.0, 1e-6);
}

TEST(SpineSkin, RenderVerticesOfOneWeldedVertexShareTheirInfluences) {
  Cylinder c = MakeRiggedCylinder(5);
  const std::size_t source = 1 + 3 * 16 + 5;
  c.mesh.positions.push_back(c.mesh.positions[source]);  // a seam copy
  c.mesh.weld_map.push_back(static_cast<std::uint32_t>(source));
  const Result<SpineSkin> skin = BuildSpineSkin(c.model, c.mesh);
  ASSERT_TRUE(skin.ok()) << skin.error();
  const std::size_t copy = c.mesh.positions.size() - 1;
  EXPECT_EQ(skin.value().joints[copy], skin.value().joints[source]);
  EXPECT_EQ(skin.value().weights[copy], skin.value().weights[source]);
}

TEST(SpineSkin, JointsAreNumberedOverThePartsInOrder) {
  Cylinder c = MakeRiggedCylinder(5);
  PartModel second = c.model.parts[0];
  second.name = "second";
  second.parent = 0;
  for (int s = 0; s < 3; ++s) second.spine_points.pop_back();  // 2 samples: v = 0 and 1
  second.spine_points.back() = Vec3(0.0, kHeight, 0.0);
  c.model.parts.push_back(second);
  c.model.vertices.back().part = 1;  // the top pole, a cap at v = 1 of part 1
  const Result<SpineSkin> skin = BuildSpineSkin(c.model, c.mesh);
  ASSERT_TRUE(skin.ok()) << skin.error();
  ExpectValid(skin.value(), c.mesh.positions.size(), 7);
  EXPECT_EQ(skin.value().joints.back()[0], 5u + 1u);  // part 1's samples follow part 0's 5
}

TEST(SpineSkin, RefusesInconsistentInput) {
  const Cylinder good = MakeRiggedCylinder(5);
  struct Case {
    const char* expected;
    void (*spoil)(Cylinder&, SpineSkinOptions&);
  };
  const Case cases[] = {
      {"options.spread", [](Cylinder&, SpineSkinOptions& o) { o.spread = 2.5; }},
      {"mesh.weld_map: not one entry",
       [](Cylinder& c, SpineSkinOptions&) { c.mesh.weld_map.pop_back(); }},
      {"mesh.weld_map[3]: beyond",
       [](Cylinder& c, SpineSkinOptions&) { c.mesh.weld_map[3] = 100000; }},
      {"model.vertices: not one attachment",
       [](Cylinder& c, SpineSkinOptions&) { c.model.vertices.pop_back(); }},
      {"model.vertices[7].part",
       [](Cylinder& c, SpineSkinOptions&) { c.model.vertices[7].part = 1; }},
      {"model.vertices[7].profile",
       [](Cylinder& c, SpineSkinOptions&) { c.model.vertices[7].profile = 8; }},
      {"model.parts[0]",
       [](Cylinder& c, SpineSkinOptions&) { c.model.parts[0].spine_points.resize(1); }},
      {"mesh.welded_positions[4]: not finite",
       [](Cylinder& c, SpineSkinOptions&) {
         c.mesh.welded_positions[4].x() = std::numeric_limits<double>::quiet_NaN();
       }},
  };
  for (const Case& test : cases) {
    SCOPED_TRACE(test.expected);
    Cylinder c = good;
    SpineSkinOptions options;
    test.spoil(c, options);
    const Result<SpineSkin> skin = BuildSpineSkin(c.model, c.mesh, options);
    ASSERT_FALSE(skin.ok());
    EXPECT_NE(skin.error().find(test.expected), std::string::npos) << skin.error();
  }
}

// ---------------------------------------------------------------------------------------------
// Measured skinning error: a cylinder with rings every 1/48 m bends along circular arcs (top
// turned by up to 90 deg), a joint per spine sample following the arc's frame. Export in skin
// mode and read the report.

Quat Bend(double kappa, double y) { return Quat(Eigen::AngleAxisd(-kappa * y, Vec3::UnitZ())); }
Vec3 BendCentre(double kappa, double y) {
  if (kappa == 0.0) return {0.0, y, 0.0};
  return {(1.0 - std::cos(kappa * y)) / kappa, std::sin(kappa * y) / kappa, 0.0};
}

BakedAnimation BendBake(const Cylinder& c, const SpineSkin& skin, int keys) {
  BakedAnimation bake;
  bake.name = "bend";
  bake.vertex_count = c.mesh.positions.size();
  BakedSpine spine;
  spine.name = "body";
  const PartModel& part = c.model.parts[0];
  for (const Vec3& p : part.spine_points) {
    spine.rest_points.push_back(p);
    spine.rest_rotations.push_back(Quat::Identity());
  }
  for (int k = 0; k < keys; ++k) {
    const double kappa = std::numbers::pi / 2.0 / kHeight * k / (keys - 1);
    bake.times.push_back(k / 30.0);
    for (const Vec3& p : c.mesh.positions) {
      const Vec3 q = BendCentre(kappa, p.y()) + Bend(kappa, p.y()) * Vec3(p.x(), 0.0, p.z());
      bake.positions.push_back(q.cast<float>());
    }
    for (const Vec3& p : part.spine_points) {
      spine.points.push_back(BendCentre(kappa, p.y()));
      spine.rotations.push_back(Bend(kappa, p.y()));
    }
  }
  bake.spines.push_back(spine);
  bake.skin_joints = skin.joints;
  bake.skin_weights = skin.weights;
  return bake;
}

TEST(SpineSkin, MeasuredSkinningErrorOfEachSpread) {
  const std::filesystem::path out = std::filesystem::temp_directory_path() /
                                    ("wirerig_spine_skin_" + std::to_string(::getpid()) + ".glb");
  for (int samples : {5, 9, 17}) {
    const Cylinder c = MakeRiggedCylinder(samples, 48);
    double errors[3] = {};
    int i = 0;
    for (double spread : {1.0, 1.5, 2.0}) {
      SCOPED_TRACE(spread);
      SpineSkinOptions options;
      options.spread = spread;
      const Result<SpineSkin> skin = BuildSpineSkin(c.model, c.mesh, options);
      ASSERT_TRUE(skin.ok()) << skin.error();
      GltfExportOptions export_options;
      export_options.mode = GltfAnimationMode::kSkin;
      export_options.max_joints_per_part = 0;  // these weights, on a joint per sample
      export_options.fit_skin = false;
      export_options.max_correctives = 0;
      const Result<GltfExportReport> report =
          ExportGltf(c.mesh, BendBake(c, skin.value(), 7), export_options, out);
      ASSERT_TRUE(report.ok()) << report.error();
      const GltfExportReport& r = report.value();
      std::printf(
          "[ measured ] %2d samples, spread %.1f: skin error max %.4g m (%.3g of diag), rms %.4g m "
          "(%.3g)\n",
          samples, spread, r.skin_max_error, r.skin_max_error_relative, r.skin_rms_error,
          r.skin_rms_error_relative);
      errors[i++] = r.skin_max_error_relative;
    }
    // Linear interpolation between neighbouring samples is the most accurate for a bend of
    // constant curvature; with 17 samples the error stays below 0.1 % of the diagonal.
    EXPECT_LE(errors[0], errors[1]);
    EXPECT_LE(errors[0], errors[2]);
    if (samples == 17) {
      EXPECT_LT(errors[0], 1e-3);
    }
  }
  std::filesystem::remove(out);
}

// The whole path on a real rig: a capsule rigged by BuildRig / BuildRigModel, its cantilever
// spine bent by a growing tip force (tip deflection up to 10 % of the length), evaluated by the
// runtime at every key; skin weights from BuildSpineSkin; skin error from the glTF export.
TEST(SpineSkin, SkinsARiggedCapsuleBentByTheRuntime) {
  Mesh mesh = MakeCapsule(0.1, 1.0, 32, 16, 6);
  RigDescription description;
  description.parts.push_back({"body", {Vec3(0, 0, 0), Vec3(0, 1, 0)}, 10, 24, "", {}, {}});
  Result<BuiltRig> rig = BuildRig(mesh, description, "capsule");
  ASSERT_TRUE(rig.ok()) << rig.error();
  Result<BuiltRigModel> built = BuildRigModel(mesh, rig.value().rig);
  ASSERT_TRUE(built.ok()) << built.error();
  const RigModel& model = built.value().model;
  const PartModel& part = model.parts[0];
  ASSERT_EQ(mesh.positions.size(), mesh.welded_positions.size());  // procedural: no seams

  const Result<SpineSkin> skin = BuildSpineSkin(model, mesh);
  ASSERT_TRUE(skin.ok()) << skin.error();
  ExpectValid(skin.value(), mesh.positions.size(),
              static_cast<std::uint32_t>(part.spine_points.size()));

  auto frame_rotation = [](const Frame& f) {
    Mat3 m;
    m.col(0) = f.normal;
    m.col(1) = f.binormal;
    m.col(2) = f.tangent;
    return Quat(m);
  };
  BakedAnimation bake;
  bake.name = "tip_force";
  bake.vertex_count = mesh.positions.size();
  BakedSpine spine;
  spine.name = part.name;
  spine.rest_points = part.spine_points;
  for (const Frame& f : part.spine_frames) spine.rest_rotations.push_back(frame_rotation(f));
  RigWorkspace workspace = MakeRigWorkspace(model);
  std::vector<PartPose> poses(1);
  std::vector<Vec3> positions(model.vertices.size());
  std::vector<Vec3> normals(model.vertices.size());
  const int keys = 5;
  const double full = 0.3 * part.spine_stiffness.bending / std::pow(part.spine_length, 3);
  for (int k = 0; k < keys; ++k) {
    poses[0].loads.tip_force = Vec3(full * k / (keys - 1), 0.0, 0.0);
    EvaluateRigJob job;
    job.model = &model;
    job.poses = poses;
    job.workspace = &workspace;
    job.positions = positions;
    job.normals = normals;
    ASSERT_TRUE(job.Run().ok());
    bake.times.push_back(k / 30.0);
    for (std::size_t v = 0; v < positions.size(); ++v) {
      bake.positions.push_back(positions[v].cast<float>());
      bake.normals.push_back(normals[v].cast<float>());
    }
    spine.points.insert(spine.points.end(), workspace.spine_points[0].begin(),
                        workspace.spine_points[0].end());
    for (const Frame& f : workspace.spine_frames[0]) spine.rotations.push_back(frame_rotation(f));
  }
  bake.spines.push_back(spine);

  const std::filesystem::path out =
      std::filesystem::temp_directory_path() /
      ("wirerig_spine_skin_capsule_" + std::to_string(::getpid()) + ".glb");
  for (double spread : {1.0, 1.5, 2.0}) {
    SCOPED_TRACE(spread);
    SpineSkinOptions skin_options;
    skin_options.spread = spread;
    const Result<SpineSkin> spread_skin = BuildSpineSkin(model, mesh, skin_options);
    ASSERT_TRUE(spread_skin.ok()) << spread_skin.error();
    bake.skin_joints = spread_skin.value().joints;
    bake.skin_weights = spread_skin.value().weights;
    GltfExportOptions options;
    options.mode = GltfAnimationMode::kSkin;
    options.residual_morph_targets = true;
    const Result<GltfExportReport> report = ExportGltf(mesh, bake, options, out);
    std::filesystem::remove(out);
    ASSERT_TRUE(report.ok()) << report.error();
    const GltfExportReport& r = report.value();
    std::printf(
        "[ measured ] capsule (V=%zu, %zu spine samples, %zu profiles, tip deflection 10 %% of "
        "L), spread %.1f: skin error max %.4g m (%.3g of diag), rms %.4g m (%.3g); with "
        "residuals max %.3g m; %ju bytes\n",
        r.vertex_count, part.spine_points.size(), part.profiles.size(), spread, r.skin_max_error,
        r.skin_max_error_relative, r.skin_rms_error, r.skin_rms_error_relative,
        r.residual_max_error, r.bytes_written);
    if (spread == 1.0) {
      EXPECT_LT(r.skin_max_error_relative, 0.01);
    }
    EXPECT_LT(r.residual_max_error, 1e-5 * r.skin_max_error / r.skin_max_error_relative);
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
