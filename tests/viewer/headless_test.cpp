// Headless helpers: PNG writing (atomic, errors naming the file), RenderToPng and contact
// sheets.
#include "wirerig/viewer/headless.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "test_scenes.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using testing::ScopedNoFpTraps;

std::filesystem::path OutputPath(const char* name) {
  return std::filesystem::path(WIRERIG_TEST_OUTPUT_DIR) / name;
}

TEST(Headless, ContextIsOpenGl33Core) {
  ScopedNoFpTraps no_traps;
  Result<std::unique_ptr<HeadlessContext>> context = HeadlessContext::Create();
  ASSERT_TRUE(context) << context.error();
  EXPECT_FALSE(context.value()->platform().empty());
  EXPECT_FALSE(context.value()->gl_renderer().empty());
}

TEST(Headless, RenderToPngWritesAReadablePng) {
  ScopedNoFpTraps no_traps;
  const testing::OwnedMesh torus = testing::ToOwnedMesh(MakeTorus(0.5, 0.15, 64, 24));
  const RenderMesh mesh = torus.View();
  RenderFrame frame;
  frame.meshes = {&mesh, 1};
  Camera camera;
  FrameCamera(camera, ComputeFrameBounds(frame), 320.0f / 240.0f);
  const auto path = OutputPath("torus.png");
  std::filesystem::remove(path);
  Result<std::filesystem::path> written = RenderToPng(frame, camera, {320, 240}, path);
  ASSERT_TRUE(written) << written.error();
  Result<Image> image = LoadPng(path);
  ASSERT_TRUE(image) << image.error();
  EXPECT_EQ(image.value().width, 320);
  EXPECT_EQ(image.value().height, 240);
  // No temporary file is left next to it.
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(path.parent_path())) {
    if (entry.path().filename().string().rfind("torus.png", 0) == 0) ++files;
  }
  EXPECT_EQ(files, 1);
}

TEST(Headless, UnwritablePathFailsNamingTheFile) {
  ScopedNoFpTraps no_traps;
  const std::filesystem::path path = "/nonexistent-folder/picture.png";
  Result<std::filesystem::path> written = RenderToPng(RenderFrame{}, Camera{}, {64, 64}, path);
  ASSERT_FALSE(written);
  EXPECT_NE(written.error().find("/nonexistent-folder/picture.png"), std::string::npos)
      << written.error();
}

TEST(Headless, BadSizeIsRefused) {
  ScopedNoFpTraps no_traps;
  Result<std::filesystem::path> written =
      RenderToPng(RenderFrame{}, Camera{}, {0, 64}, OutputPath("zero.png"));
  ASSERT_FALSE(written);
  EXPECT_NE(written.error().find("zero.png"), std::string::npos) << written.error();
  EXPECT_NE(written.error().find("size"), std::string::npos) << written.error();
}

TEST(Headless, SavePngRefusesAnInconsistentImage) {
  Image image;
  image.width = 4;
  image.height = 4;
  image.rgba.resize(3);
  Result<std::filesystem::path> written = SavePng(image, OutputPath("bad.png"));
  ASSERT_FALSE(written);
  EXPECT_NE(written.error().find("bad.png"), std::string::npos);
}

TEST(Headless, LoadPngOfAMissingFileNamesIt) {
  Result<Image> image = LoadPng(OutputPath("missing.png"));
  ASSERT_FALSE(image);
  EXPECT_NE(image.error().find("missing.png"), std::string::npos);
}

TEST(Headless, ContactSheetTilesFramesWithLabels) {
  ScopedNoFpTraps no_traps;
  std::vector<testing::OwnedMesh> meshes;
  for (int i = 0; i < 5; ++i) {
    meshes.push_back(testing::ToOwnedMesh(MakeCapsule(0.15, 0.8, 32, 12, 6)));
    for (Vec3f& p : meshes.back().positions) p.x() += 0.25f * float(i) * p.y() * p.y();
    meshes.back().UpdateNormals();
  }
  std::vector<RenderMesh> views;
  for (const auto& m : meshes) views.push_back(m.View());
  std::vector<ContactSheetTile> tiles(views.size());
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    tiles[i].frame.meshes = {&views[i], 1};
    FrameCamera(tiles[i].camera, ComputeFrameBounds(tiles[i].frame), 4.0f / 3.0f, 1.2f);
    tiles[i].label = "frame " + std::to_string(i);
  }
  const auto path = OutputPath("contact_sheet.png");
  Result<std::filesystem::path> written = RenderContactSheet(tiles, {200, 150}, 3, path);
  ASSERT_TRUE(written) << written.error();
  Result<Image> image = LoadPng(path);
  ASSERT_TRUE(image) << image.error();
  EXPECT_EQ(image.value().width, 3 * 200 + 4 * 2);
  EXPECT_EQ(image.value().height, 2 * 150 + 3 * 2);
  // The empty sixth slot stays white.
  const auto p = image.value().At(2 + 2 * 202 + 100, 2 + 152 + 75);
  EXPECT_EQ(p[0], 255);
  EXPECT_EQ(p[1], 255);

  Result<std::filesystem::path> none = RenderContactSheet({}, {200, 150}, 3, path);
  EXPECT_FALSE(none);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
