// Renders procedural meshes headless and checks the pictures pixel by pixel: the model is where
// its projected bounds say, the background is elsewhere, the ground is darker under the model,
// and different poses give different pictures. The PNGs stay in the test output folder.
#include "wirerig/viewer/renderer.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include <gtest/gtest.h>

#include "test_scenes.h"
#include "wirerig/viewer/headless.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using testing::LyingCapsule;
using testing::OwnedMesh;
using testing::ScopedNoFpTraps;

std::filesystem::path OutputPath(const char* name) {
  return std::filesystem::path(WIRERIG_TEST_OUTPUT_DIR) / name;
}

float Luminance(const std::array<std::uint8_t, 4>& p) {
  return 0.2126f * float(p[0]) + 0.7152f * float(p[1]) + 0.0722f * float(p[2]);
}

// Mean luminance of the (2r+1)^2 pixels around (x, y): averages grid lines away.
float MeanLuminance(const Image& image, int x, int y, int r) {
  float sum = 0.0f;
  int n = 0;
  for (int j = std::max(0, y - r); j <= std::min(image.height - 1, y + r); ++j) {
    for (int i = std::max(0, x - r); i <= std::min(image.width - 1, x + r); ++i) {
      sum += Luminance(image.At(i, j));
      ++n;
    }
  }
  return n > 0 ? sum / float(n) : 0.0f;
}

int CountDifferentPixels(const Image& a, const Image& b, int threshold) {
  int count = 0;
  for (std::size_t i = 0; i + 3 < a.rgba.size(); i += 4) {
    int d = 0;
    for (std::size_t c = 0; c < 3; ++c)
      d = std::max(d, std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c])));
    if (d > threshold) ++count;
  }
  return count;
}

class RendererTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Result<std::unique_ptr<HeadlessRenderer>> headless = HeadlessRenderer::Create();
    ASSERT_TRUE(headless) << headless.error();
    headless_ = std::move(headless).value();
  }
  void TearDown() override { headless_.reset(); }

  Image Render(const RenderFrame& frame, const Camera& camera, const char* png_name,
               const RenderOptions& options = {}) {
    Image image;
    Result<bool> ok = headless_->RenderToImage(frame, camera, size_, &image, options);
    EXPECT_TRUE(ok) << ok.error();
    Result<std::filesystem::path> saved = SavePng(image, OutputPath(png_name));
    EXPECT_TRUE(saved) << saved.error();
    return image;
  }

  ScopedNoFpTraps no_traps_;
  std::unique_ptr<HeadlessRenderer> headless_;
  Size size_{640, 400};
};

// `mesh` alone over a ground at y = 0.
RenderFrame OnGround(const RenderMesh& mesh) {
  RenderFrame frame;
  frame.meshes = {&mesh, 1};
  frame.ground_at_lowest_point = false;
  frame.ground_height = 0.0f;
  return frame;
}

// The model's colour (orange: red over green over blue) where `point` projects.
void ExpectOrangeAt(const Image& image, const Camera& camera, Size size, const Vec3f& point) {
  Vec2f pixel;
  ASSERT_TRUE(ProjectToPixel(camera, size, point, &pixel));
  const auto c = image.At(int(pixel.x()), int(pixel.y()));
  EXPECT_GT(c[0], c[1] + 20) << int(c[0]) << " " << int(c[1]) << " " << int(c[2]);
  EXPECT_GT(c[1], c[2]);
}

TEST_F(RendererTest, CapsuleIsLitWhereItsBoundsProjectAndBackgroundElsewhere) {
  const OwnedMesh capsule = LyingCapsule(0.5f);
  const RenderMesh mesh = capsule.View();
  const RenderFrame frame = OnGround(mesh);
  Camera camera;
  FrameCamera(camera, ComputeFrameBounds(frame), size_.Aspect(), 1.6f);
  const Image image = Render(frame, camera, "capsule.png");
  ASSERT_EQ(image.width, size_.width);

  // Not blank: the luminance varies.
  float lo = 255.0f, hi = 0.0f;
  for (int y = 0; y < image.height; y += 4) {
    for (int x = 0; x < image.width; x += 4) {
      lo = std::min(lo, Luminance(image.At(x, y)));
      hi = std::max(hi, Luminance(image.At(x, y)));
    }
  }
  EXPECT_GT(hi - lo, 60.0f);

  // The model's colour at the projected centre of its box, and lit (not black).
  ExpectOrangeAt(image, camera, size_, ComputeFrameBounds(frame).Center());
  Vec2f centre;
  ASSERT_TRUE(ProjectToPixel(camera, size_, ComputeFrameBounds(frame).Center(), &centre));
  EXPECT_GT(Luminance(image.At(int(centre.x()), int(centre.y()))), 60.0f);

  // Outside the projected box, above the model: the background gradient (bluish grey).
  Vec2f lo_px, hi_px;
  ASSERT_TRUE(ProjectBounds(camera, size_, ComputeFrameBounds(frame), &lo_px, &hi_px));
  ASSERT_GT(lo_px.y(), 12.0f);
  const auto sky = image.At(int(centre.x()), int(lo_px.y() * 0.3f));
  EXPECT_GE(sky[2], sky[0]);
  EXPECT_LT(std::abs(int(sky[0]) - int(sky[1])), 30);
  // Every pixel inside the model's silhouette sits inside the projected box: scan a row
  // through the centre and check the orange run lies within it.
  const int row = int(centre.y());
  for (int x = 0; x < image.width; ++x) {
    const auto p = image.At(x, row);
    const bool orange = p[0] > p[2] + 60;
    if (orange) {
      EXPECT_GE(float(x), lo_px.x() - 2.0f);
      EXPECT_LE(float(x), hi_px.x() + 2.0f);
    }
  }
}

TEST_F(RendererTest, GroundIsDarkerUnderTheModel) {
  const OwnedMesh capsule = LyingCapsule(0.45f);
  const RenderMesh mesh = capsule.View();
  const RenderFrame frame = OnGround(mesh);
  Camera camera;
  camera.pitch = 0.6f;
  const FrameBounds bounds = ComputeFrameBounds(frame);
  FrameCamera(camera, bounds, size_.Aspect(), 1.8f);
  const Image image = Render(frame, camera, "capsule_shadow.png");
  Vec2f under, aside;
  ASSERT_TRUE(ProjectToPixel(camera, size_, Vec3f(0.0f, 0.0f, 0.0f), &under));
  ASSERT_TRUE(ProjectToPixel(camera, size_, Vec3f(bounds.max.x() + 0.6f, 0.0f, 0.0f), &aside));
  const float l_under = MeanLuminance(image, int(under.x()), int(under.y()), 3);
  const float l_aside = MeanLuminance(image, int(aside.x()), int(aside.y()), 3);
  EXPECT_LT(l_under, 0.8f * l_aside) << l_under << " vs " << l_aside;

  // Without shadows the difference shrinks (only the contact occlusion remains).
  RenderOptions no_shadows;
  no_shadows.shadows = false;
  const Image flat = Render(frame, camera, "capsule_no_shadow.png", no_shadows);
  EXPECT_GT(MeanLuminance(flat, int(under.x()), int(under.y()), 3), l_under);
}

TEST_F(RendererTest, AnEyeBelowTheGroundStillSeesTheModel) {
  const OwnedMesh capsule = LyingCapsule(0.5f);  // above the ground: its centre is at y 0.5
  const RenderMesh mesh = capsule.View();
  const RenderFrame frame = OnGround(mesh);
  Camera camera;
  camera.pitch = -0.5f;  // looking up from below
  FrameCamera(camera, ComputeFrameBounds(frame), size_.Aspect(), 1.6f);
  ASSERT_LT(camera.Eye().y(), 0.0f);
  const Image image = Render(frame, camera, "capsule_from_below.png");
  ExpectOrangeAt(image, camera, size_, ComputeFrameBounds(frame).Center());
}

TEST_F(RendererTest, DifferentPosesGiveDifferentImages) {
  OwnedMesh capsule = LyingCapsule(0.3f);
  RenderMesh mesh = capsule.View();
  RenderFrame frame;
  frame.meshes = {&mesh, 1};
  Camera camera;
  FrameCamera(camera, ComputeFrameBounds(frame), size_.Aspect(), 1.5f);
  const Image straight = Render(frame, camera, "pose_straight.png");
  // Bend: lift the ends, a parabola along the axis.
  for (Vec3f& p : capsule.positions) p.y() += 0.35f * p.x() * p.x();
  capsule.UpdateNormals();
  mesh = capsule.View();
  const Image bent = Render(frame, camera, "pose_bent.png");
  EXPECT_GT(CountDifferentPixels(straight, bent, 24), 2000);
  // The same pose twice renders identically.
  const Image bent_again = Render(frame, camera, "pose_bent_again.png");
  EXPECT_EQ(CountDifferentPixels(bent, bent_again, 0), 0);
}

TEST_F(RendererTest, WiresArrowsScalarsAndWireframe) {
  OwnedMesh capsule = LyingCapsule(0.3f);
  capsule.scalars.resize(capsule.positions.size());
  for (std::size_t i = 0; i < capsule.positions.size(); ++i) {
    capsule.scalars[i] = 100.0f * capsule.positions[i].x();  // a "bending moment", N m
  }
  const RenderMesh mesh = capsule.View();
  // Spine along the axis (pink) and three profile rings (blue).
  std::vector<Vec3f> spine;
  for (int i = 0; i <= 20; ++i) spine.emplace_back(-0.7f + 1.4f * float(i) / 20.0f, 0.3f, 0.0f);
  std::vector<std::vector<Vec3f>> rings(3);
  for (int r = 0; r < 3; ++r) {
    const float x = -0.4f + 0.4f * float(r);
    for (int k = 0; k < 32; ++k) {
      const float a = 2.0f * 3.14159265f * float(k) / 32.0f;
      rings[r].emplace_back(x, 0.3f + 0.2f * std::cos(a), 0.2f * std::sin(a));
    }
  }
  std::vector<RenderPolyline> lines(4);
  lines[0].points = spine;
  lines[0].kind = WireKind::kSpine;
  for (int r = 0; r < 3; ++r) {
    lines[r + 1].points = rings[r];
    lines[r + 1].closed = true;
  }
  const RenderArrow arrow{Vec3f(0.7f, 0.3f, 0.0f), Vec3f(0.0f, -50.0f, 0.0f)};
  RenderFrame frame;
  frame.meshes = {&mesh, 1};
  frame.polylines = lines;
  frame.arrows = {&arrow, 1};
  frame.legend.min = -70.0f;
  frame.legend.max = 70.0f;
  frame.legend.label = "bending moment (N m)";
  frame.caption = "t = 0.50 s";
  Camera camera;
  FrameCamera(camera, ComputeFrameBounds(frame), size_.Aspect(), 1.3f);
  RenderOptions options;
  options.wireframe = true;
  const Image image = Render(frame, camera, "wires_arrows_scalars.png", options);
  EXPECT_EQ(headless_->renderer().stats().polylines, 4);
  EXPECT_EQ(headless_->renderer().stats().arrows, 1);

  // The spine is pink where it projects, even though it runs inside the mesh (faded).
  Vec2f mid;
  ASSERT_TRUE(ProjectToPixel(camera, size_, Vec3f(-0.2f, 0.3f, 0.0f), &mid));
  const auto p = image.At(int(mid.x()), int(mid.y()));
  EXPECT_GT(int(p[0]), int(p[1]) + 10) << int(p[0]) << " " << int(p[1]) << " " << int(p[2]);
  // A profile ring's front point is blue.
  Vec2f front;
  ASSERT_TRUE(ProjectToPixel(camera, size_, Vec3f(0.0f, 0.3f, 0.2f), &front));
  const auto q = image.At(int(front.x()), int(front.y()));
  EXPECT_GT(int(q[2]), int(q[0]) + 60) << int(q[0]) << " " << int(q[1]) << " " << int(q[2]);
}

TEST_F(RendererTest, BackFaceCullingLeavesAClosedMeshUnchanged) {
  const OwnedMesh capsule = LyingCapsule(0.3f);
  RenderMesh mesh = capsule.View();
  RenderFrame frame;
  frame.meshes = {&mesh, 1};
  Camera camera;
  FrameCamera(camera, ComputeFrameBounds(frame), size_.Aspect(), 1.5f);
  const Image both = Render(frame, camera, "cull_off.png");
  mesh.cull_back_faces = true;
  const Image culled = Render(frame, camera, "cull_on.png");
  EXPECT_LT(CountDifferentPixels(both, culled, 8), 20);
}

TEST_F(RendererTest, EmptyFrameRendersBackgroundAndGround) {
  const Image image = Render(RenderFrame{}, Camera{}, "empty.png");
  EXPECT_GT(Luminance(image.At(5, 5)), 100.0f);
  EXPECT_EQ(headless_->renderer().stats().vertices, 0);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
