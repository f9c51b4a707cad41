// ExportGltf read back by an independent reader: three.js (pinned by
// scripts/gltf_validator/package-lock.json, installed by scripts/setup.sh) loads each exported
// file with its GLTFLoader under node, plays it with an AnimationMixer and computes every vertex
// the way its morph and skinning shaders do (scripts/three_skinned_positions.mjs). Its positions
// are compared with wirerig's own evaluation: the bake at the keys, and the glTF playback of the
// bake (gltf_playback_reference.h, in double from the BakedAnimation) at keys and between them.
//
// Scenes: samples/beam (one spine, one primitive) and samples/octopus (a rigid mantle with eight
// tentacle spines hanging from it, several primitives), each in morph, skin and skin + residual
// mode; the beam also quantized (KHR_mesh_quantization) and as a textured .gltf + .bin.
// Tolerances: 1e-4 of the rest mesh's bounding-box diagonal (float rounding), except plain skin
// mode against the bake at the keys, where linear blend skinning is off by the export report's
// skin_max_error. Node or three.js missing fails these tests (run scripts/setup.sh).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gltf_playback_reference.h"
#include "support/shuffled_vertices.h"
#include "three_reader.h"
#include "wirerig/anim/bake.h"
#include "wirerig/anim/gltf_export.h"
#include "wirerig/anim/scene.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;
using testing::GltfPlayback;

constexpr double kFloatTolerance = 1e-4;  // of the diagonal: float rounding in the file

// A fresh folder per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "wirerig_three_";
    name.append(info->name()).append("_").append(std::to_string(::getpid()));
    path_ = fs::temp_directory_path() / name;
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// A sample's scene and its first clip baked with the skin (for every mode).
struct Baked {
  BuiltScene scene;
  BakedAnimation bake;
  double diagonal = 0.0;
};

Baked BakeSample(const std::string& scene_file, double fps) {
  Baked out;
  Result<BuiltScene> built = LoadAndBuildScene(fs::path(WIRERIG_SAMPLES_DIR) / scene_file);
  EXPECT_TRUE(built.ok()) << built.error();
  if (!built.ok()) return out;
  out.scene = std::move(built).value();
  BakeOptions options;
  options.fps = fps;
  options.skin = true;
  Result<BakedAnimation> bake = BakeClip(out.scene.mesh, out.scene.model, out.scene.clips.at(0),
                                         out.scene.description.playback, options);
  EXPECT_TRUE(bake.ok()) << bake.error();
  if (bake.ok()) out.bake = std::move(bake).value();
  out.diagonal = ComputeBounds(out.scene.mesh).Diagonal();
  return out;
}

// The export variants of a scene.
struct Variant {
  const char* name;
  GltfPlayback playback;
  bool quantize = false;
  bool textured_gltf = false;  // a .gltf + .bin whose material references a PNG
  // Skin mode's default: joints and weights fitted to the bake, corrective shapes. The glTF
  // playback reference models a joint per spine sample on the baked frames, so a fitted skin
  // is compared with the bake at the keys only.
  bool fitted = false;
  bool compressed = false;  // EXT_meshopt_compression (fitted skins only)
  bool reordered = false;   // the file stores the vertices in another order (vertex_order)
};

GltfExportOptions ExportOptions(const Variant& variant) {
  GltfExportOptions options;
  options.mode = variant.playback == GltfPlayback::kMorph ? GltfAnimationMode::kMorph
                                                          : GltfAnimationMode::kSkin;
  options.residual_morph_targets = variant.playback == GltfPlayback::kSkinResidual;
  options.quantize = variant.quantize;
  options.compress = variant.compressed;
  if (!variant.fitted) {  // what the reference models: a joint per sample, the baked frames
    options.max_joints = 65535;
    options.max_joints_per_part = 0;
    options.fit_skin = false;
    options.max_correctives = 0;
  }
  return options;
}

// `mesh` with UVs around the X axis and a material whose base colour texture is a real PNG under
// <dir>/src; returns that texture folder.
fs::path AddTexture(Mesh* mesh, const fs::path& dir) {
  const fs::path png =
      fs::path(WIRERIG_ASSET_DIR) / "assimp" / "glTF2" / "textureTransform" / "UV.png";
  EXPECT_TRUE(fs::exists(png)) << png << " missing: run scripts/setup.sh";
  fs::create_directories(dir / "src" / "textures");
  fs::copy_file(png, dir / "src" / "textures" / "logo.png", fs::copy_options::overwrite_existing);
  mesh->uvs.clear();
  for (const Vec3& p : mesh->positions) {
    mesh->uvs.emplace_back(p.x(), 0.5 + std::atan2(p.z(), p.y()) / (2.0 * std::numbers::pi));
  }
  mesh->materials = {MeshMaterial{"skin", Vec4(0.8, 0.4, 0.3, 1.0), "textures/logo.png", {}}};
  for (MeshPart& part : mesh->parts) part.material = 0;
  return dir / "src";
}

// Times to play: keys 0, #K / 2 and the last, half-way between keys #K / 3 and #K / 3 + 1, and a
// quarter of the way from key 2 #K / 3 to the next. Key times are exactly the file's floats.
struct PlayTime {
  std::size_t key;  // at this key (u = 0), or between it and the next
  double u;
  double t;
  double key_t;  // the key's time
};

std::vector<PlayTime> PlayTimes(const BakedAnimation& bake) {
  const std::vector<double> keys = testing::FloatKeyTimes(bake);
  const std::size_t n = keys.size();
  std::vector<PlayTime> out;
  for (const auto& [key, u] : {std::pair<std::size_t, double>{0, 0.0},
                               {n / 2, 0.0},
                               {n - 1, 0.0},
                               {n / 3, 0.5},
                               {2 * n / 3, 0.25}}) {
    const double t = u == 0.0 ? keys[key] : (1.0 - u) * keys[key] + u * keys[key + 1];
    out.push_back({key, u, t, keys[key]});
  }
  return out;
}

double MaxDistance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double d = 0.0;
  for (std::size_t v = 0; v < a.size(); ++v) d = std::max(d, (a[v] - b[v]).norm());
  return d;
}

std::vector<Vec3> BakedKey(const BakedAnimation& bake, std::size_t key) {
  std::vector<Vec3> out;
  for (std::size_t v = 0; v < bake.vertex_count; ++v) {
    out.push_back(bake.positions[key * bake.vertex_count + v].cast<double>());
  }
  return out;
}

// Exports `baked` as `variant`, plays it with three.js and compares.
void CheckVariant(const Baked& baked, const Variant& variant, const fs::path& dir) {
  SCOPED_TRACE(variant.name);
  const BakedAnimation& bake = baked.bake;
  GltfExportOptions options = ExportOptions(variant);
  options.node_name = baked.scene.description.name;
  Mesh mesh = baked.scene.mesh;
  if (variant.textured_gltf) options.texture_dir = AddTexture(&mesh, dir);
  const fs::path file =
      dir / (std::string(variant.name) + (variant.textured_gltf ? ".gltf" : ".glb"));
  Result<GltfExportReport> report = ExportGltf(mesh, bake, options, file);
  ASSERT_TRUE(report.ok()) << report.error();
  if (variant.textured_gltf) {
    ASSERT_EQ(report.value().texture_count, 1u);
  }
  if (variant.quantize) {
    ASSERT_GT(report.value().quantized_position_targets, 0u);
  }
  if (variant.reordered) {
    ASSERT_EQ(report.value().vertex_order.size(), bake.vertex_count);
  }

  const std::vector<PlayTime> times = PlayTimes(bake);
  std::vector<double> seconds;
  for (const PlayTime& time : times) seconds.push_back(time.t);
  const testing::ThreePlayback three = testing::PlayWithThree(file, seconds);
  ASSERT_EQ(three.error, "");
  ASSERT_EQ(three.meshes.size(), 1u);
  const testing::ThreeMesh& drawn = three.meshes[0];
  EXPECT_EQ(three.animation, bake.name);
  ASSERT_EQ(drawn.positions.at(0).size(), bake.vertex_count);
  EXPECT_EQ(drawn.skinned, variant.playback != GltfPlayback::kMorph);
  EXPECT_EQ(drawn.morph_targets, variant.playback == GltfPlayback::kSkin
                                     ? report.value().corrective_count
                                     : bake.KeyCount());
  EXPECT_EQ(drawn.primitives, report.value().primitive_count);
  EXPECT_EQ(drawn.primitive_spread, 0.0);

  const double float_tolerance = kFloatTolerance * baked.diagonal;
  // Plain skin at the keys: the linear blend's own error (with its correctives), plus rounding.
  const double skin_tolerance = report.value().corrected_max_error + 1e-5 * baked.diagonal;
  double worst_keys = 0.0;      // three against the bake, at keys
  double worst_playback = 0.0;  // three against the glTF playback of the bake, every time
  double least_step = 1e300;    // between keys: how far three's mesh is from the previous key
  for (std::size_t i = 0; i < times.size(); ++i) {
    SCOPED_TRACE("t = " + std::to_string(times[i].t) + " s");
    // Back in the mesh's vertex order (compressed files may store another: vertex_order).
    std::vector<Vec3> positions = drawn.positions[i];
    const std::vector<std::uint32_t>& order = report.value().vertex_order;
    for (std::size_t v = 0; v < order.size(); ++v) positions[order[v]] = drawn.positions[i][v];
    if (variant.fitted) {
      if (times[i].u != 0.0) continue;
      const double keyed = MaxDistance(positions, BakedKey(bake, times[i].key));
      EXPECT_LE(keyed, skin_tolerance);
      worst_keys = std::max(worst_keys, keyed);
      continue;
    }
    const double playback = MaxDistance(
        positions, testing::GltfPositionsAt(baked.scene.mesh, bake, variant.playback, times[i].t));
    EXPECT_LE(playback, float_tolerance);
    worst_playback = std::max(worst_playback, playback);
    if (times[i].u == 0.0) {
      const double keyed = MaxDistance(positions, BakedKey(bake, times[i].key));
      EXPECT_LE(keyed, variant.playback == GltfPlayback::kSkin ? skin_tolerance : float_tolerance);
      worst_keys = std::max(worst_keys, keyed);
    } else {
      // The times between keys must tell interpolation from holding the previous key.
      const double step = MaxDistance(
          positions,
          testing::GltfPositionsAt(baked.scene.mesh, bake, variant.playback, times[i].key_t));
      EXPECT_GT(step, 5.0 * float_tolerance) << "key " << times[i].key;
      least_step = std::min(least_step, step);
    }
  }
  if (variant.fitted) {
    std::printf(
        "three.js r%s, %s %s (%zu vertices, %zu keys, %zu joints, %zu correctives): at keys "
        "%.3g m from the bake (report: skin %.3g m, corrected %.3g m)\n",
        three.revision.c_str(), baked.scene.description.name.c_str(), variant.name,
        bake.vertex_count, bake.KeyCount(), report.value().joint_count,
        report.value().corrective_count, worst_keys, report.value().skin_max_error,
        report.value().corrected_max_error);
    return;
  }
  std::printf(
      "three.js r%s, %s %s (%zu vertices, %zu keys, diagonal %.3g m): at keys %.3g m from the "
      "bake (%.3g of the diagonal; report skin_max_error %.3g m), %.3g m from the glTF playback "
      "at all times (%.3g); between keys %.3g m from the previous key\n",
      three.revision.c_str(), baked.scene.description.name.c_str(), variant.name, bake.vertex_count,
      bake.KeyCount(), baked.diagonal, worst_keys, worst_keys / baked.diagonal,
      report.value().skin_max_error, worst_playback, worst_playback / baked.diagonal, least_step);
}

TEST(GltfExportThree, BeamPlaysInThreeAsWirerigBakedIt) {
  const Baked baked = BakeSample("beam/beam.scene.json", 30.0);
  ASSERT_GT(baked.bake.KeyCount(), 10u);
  TempDir dir;
  const Variant variants[] = {
      {"morph", GltfPlayback::kMorph},
      {"skin", GltfPlayback::kSkin},
      {"skin_residual", GltfPlayback::kSkinResidual},
      {"morph_quantized", GltfPlayback::kMorph, true},
      {"skin_residual_quantized", GltfPlayback::kSkinResidual, true},
      {"skin_residual_textured", GltfPlayback::kSkinResidual, false, true},
      {"skin_fitted", GltfPlayback::kSkin, false, false, true},
  };
  for (const Variant& variant : variants) CheckVariant(baked, variant, dir.path());
  // Vertices in a random order: the compressed file stores them in another, mapped back.
  Baked shuffled = baked;
  testing::ShuffleVertices(&shuffled.scene.mesh, &shuffled.bake, 11);
  CheckVariant(
      shuffled,
      {"skin_fitted_compressed_shuffled", GltfPlayback::kSkin, false, false, true, true, true},
      dir.path());
}

TEST(GltfExportThree, OctopusPlaysInThreeAsWirerigBakedIt) {
  const Baked baked = BakeSample("octopus/octopus.scene.json", 10.0);
  ASSERT_GT(baked.bake.KeyCount(), 10u);
  TempDir dir;
  const Variant variants[] = {
      {"morph", GltfPlayback::kMorph},
      {"skin", GltfPlayback::kSkin},
      {"skin_residual", GltfPlayback::kSkinResidual},
      {"skin_fitted", GltfPlayback::kSkin, false, false, true},
      // Corrective shapes as normalized bytes (KHR_mesh_quantization), plain and compressed.
      {"skin_fitted_quantized", GltfPlayback::kSkin, true, false, true},
      {"skin_fitted_compressed", GltfPlayback::kSkin, false, false, true, true},
  };
  for (const Variant& variant : variants) CheckVariant(baked, variant, dir.path());
}

// The reader's own failures are reported, not read as positions.
TEST(GltfExportThree, TheReaderRefusesAMissingFileAndAMissingThree) {
  TempDir dir;
  const testing::ThreePlayback missing = testing::PlayWithThree(dir.path() / "none.glb", {0.0});
  EXPECT_NE(missing.error.find("none.glb: ENOENT"), std::string::npos) << missing.error;
  ::setenv("WIRERIG_THREE", dir.path().c_str(), 1);
  const testing::ThreePlayback no_three = testing::PlayWithThree(dir.path() / "none.glb", {0.0});
  ::unsetenv("WIRERIG_THREE");
  EXPECT_NE(no_three.error.find("cannot load three.js"), std::string::npos) << no_three.error;
  EXPECT_NE(no_three.error.find("run scripts/setup.sh"), std::string::npos) << no_three.error;
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
