// Proves that Renderer::Render allocates nothing in the steady state: global operator new is
// replaced by one that counts. Its own binary, because it replaces operator new. After warm-up
// frames (buffers sized, llvmpipe's shader variants compiled), further frames of the same
// shape, with new vertex positions, must not allocate.
#include <atomic>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

#include <gtest/gtest.h>

#include "test_scenes.h"
#include "wirerig/viewer/headless.h"

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
// The nothrow forms too (LLVM, inside llvmpipe, uses them): every new that pairs with the
// replaced deletes below must come from malloc, or AddressSanitizer reports a mismatch.
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  ++g_allocations;
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept {
  return operator new(size, tag);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace wirerig {
namespace {

TEST(RenderAllocation, SteadyStateFramesDoNotAllocate) {
  testing::ScopedNoFpTraps no_traps;
  Result<std::unique_ptr<HeadlessRenderer>> headless = HeadlessRenderer::Create();
  ASSERT_TRUE(headless) << headless.error();
  testing::OwnedMesh capsule = testing::LyingCapsule(0.3f);
  capsule.scalars.assign(capsule.positions.size(), 1.0f);
  const RenderMesh mesh = capsule.View();
  std::vector<Vec3f> spine = {Vec3f(-0.5f, 0.3f, 0.0f), Vec3f(0.0f, 0.3f, 0.0f),
                              Vec3f(0.5f, 0.3f, 0.0f)};
  RenderPolyline line;
  line.points = spine;
  line.kind = WireKind::kSpine;
  const RenderArrow arrow{Vec3f(0.5f, 0.3f, 0.0f), Vec3f(0.0f, -10.0f, 0.0f)};
  RenderFrame frame;
  frame.meshes = {&mesh, 1};
  frame.polylines = {&line, 1};
  frame.arrows = {&arrow, 1};
  frame.caption = "t = 1.00 s";
  frame.legend.label = "strain";
  Camera camera;
  FrameCamera(camera, ComputeFrameBounds(frame), 4.0f / 3.0f);
  RenderOptions options;
  options.wireframe = true;
  const Size size{320, 240};
  for (int i = 0; i < 3; ++i) headless.value()->RenderAndFinish(frame, camera, size, options);

  const long before = g_allocations;
  for (int i = 0; i < 5; ++i) {
    for (Vec3f& p : capsule.positions) p.y() += 0.001f;
    capsule.UpdateNormals();
    headless.value()->RenderAndFinish(frame, camera, size, options);
  }
  EXPECT_EQ(g_allocations - before, 0);
}

}  // namespace
}  // namespace wirerig
