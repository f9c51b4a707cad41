// Headless rendering: an OpenGL 3.3 core context without a window (EGL, Mesa's surfaceless
// platform first, the default display as a fallback), an offscreen multisampled framebuffer,
// and the one-call helpers RenderToPng and RenderContactSheet.
//
// Floating-point traps: Mesa (EGL initialisation, llvmpipe's LLVM shader compiler) raises
// division-by-zero and invalid-operation flags internally. A process that enables traps
// (feenableexcept, as wirerig's test main does) must disable them around these calls; the
// viewer tests do so with a scoped guard.
#pragma once

#include <filesystem>
#include <memory>
#include <span>
#include <string>

#include "wirerig/io/result.h"
#include "wirerig/viewer/camera.h"
#include "wirerig/viewer/image.h"
#include "wirerig/viewer/render_frame.h"
#include "wirerig/viewer/renderer.h"

namespace wirerig {

// An EGL display and OpenGL 3.3 core context, current on the creating thread after Create().
class HeadlessContext {
 public:
  // The error says which EGL step failed (no display, no 3.3 core context, ...).
  static Result<std::unique_ptr<HeadlessContext>> Create();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  // Makes the context current on the calling thread.
  bool MakeCurrent();
  // "surfaceless" or "default", and GL_RENDERER (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
  const std::string& platform() const { return platform_; }
  const std::string& gl_renderer() const { return gl_renderer_; }

 private:
  HeadlessContext() = default;
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  void* surface_ = nullptr;  // EGLSurface, only when surfaceless contexts are unsupported
  std::string platform_;
  std::string gl_renderer_;
};

// A headless context, an offscreen framebuffer (resized on demand) and a Renderer: render many
// frames to images without re-creating anything.
class HeadlessRenderer {
 public:
  // samples: MSAA samples of the offscreen colour buffer (1 = none; 4 looks good).
  static Result<std::unique_ptr<HeadlessRenderer>> Create(int samples = 4);
  ~HeadlessRenderer();
  HeadlessRenderer(const HeadlessRenderer&) = delete;
  HeadlessRenderer& operator=(const HeadlessRenderer&) = delete;

  // Renders `frame` at `size` and reads it back into `image` (resized; its storage is reused
  // across calls of the same size). Waits for the GPU. The error names the GL failure.
  Result<bool> RenderToImage(const RenderFrame& frame, const Camera& camera, Size size,
                             Image* image, const RenderOptions& options = {});
  // Renders without reading back, then glFinish(): for benchmarks of upload + draw.
  void RenderAndFinish(const RenderFrame& frame, const Camera& camera, Size size,
                       const RenderOptions& options = {});

  Renderer& renderer();
  HeadlessContext& context();

 private:
  struct Impl;
  explicit HeadlessRenderer(std::unique_ptr<Impl> impl);
  void BindTarget(Size size);
  std::unique_ptr<Impl> impl_;
};

// Renders one frame at `size` into a PNG at `path` (written atomically). Returns the path, or
// an error naming the file or the failed rendering step.
Result<std::filesystem::path> RenderToPng(const RenderFrame& frame, const Camera& camera, Size size,
                                          const std::filesystem::path& path,
                                          const RenderOptions& options = {});

// One tile of a contact sheet: a frame, its camera and a label printed in the tile's top-left
// corner (it replaces the frame's caption).
struct ContactSheetTile {
  RenderFrame frame;
  Camera camera;
  std::string label;
};

// The size of a contact sheet of `count` tiles of `tile_size`, `columns` wide (at most `count`;
// rows as needed), with a 2-pixel white gutter; in 64 bits (a sheet may exceed int).
struct SheetSize {
  std::int64_t width = 0, height = 0;
};
SheetSize ContactSheetSize(int count, Size tile_size, int columns);

// Renders every tile at `tile_size` and tiles them `columns` wide (rows as needed) into one PNG
// with a 2-pixel white gutter. Returns the path, or an error naming the file; a sheet of more
// than kMaxPngPixels (image.h) is refused before anything is drawn.
Result<std::filesystem::path> RenderContactSheet(std::span<const ContactSheetTile> tiles,
                                                 Size tile_size, int columns,
                                                 const std::filesystem::path& path,
                                                 const RenderOptions& options = {});

}  // namespace wirerig
