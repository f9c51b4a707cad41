#include "wirerig/viewer/headless.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "gl.h"
#include "gl_objects.h"
#include "sanitizer_support.h"

namespace wirerig {
namespace {

constexpr int kSheetGutter = 2;  // white pixels around and between a contact sheet's tiles

std::string EglErrorText() {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "EGL error 0x%04X", static_cast<unsigned>(eglGetError()));
  return buffer;
}

bool HasExtension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  }
  return false;
}

}  // namespace

Result<std::unique_ptr<HeadlessContext>> HeadlessContext::Create() {
  std::unique_ptr<HeadlessContext> ctx(new HeadlessContext());
  EGLDisplay display = EGL_NO_DISPLAY;
  const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  EGLint major = 0, minor = 0;
  // Mesa's surfaceless platform needs neither X nor a GPU device node.
  if (HasExtension(client_extensions, "EGL_MESA_platform_surfaceless")) {
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display != nullptr) {
      display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      if (display != EGL_NO_DISPLAY && eglInitialize(display, &major, &minor) == EGL_TRUE) {
        ctx->platform_ = "surfaceless";
      } else {
        display = EGL_NO_DISPLAY;
      }
    }
  }
  if (display == EGL_NO_DISPLAY) {
    display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (display == EGL_NO_DISPLAY || eglInitialize(display, &major, &minor) != EGL_TRUE) {
      return Error{
          "headless OpenGL: no EGL display (neither Mesa's surfaceless platform nor the "
          "default display initialise: " +
          EglErrorText() + ")"};
    }
    ctx->platform_ = "default";
  }
  ctx->display_ = display;
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
    return Error{"headless OpenGL: EGL cannot bind the desktop OpenGL API (" + EglErrorText() +
                 ")"};
  }
  const char* display_extensions = eglQueryString(display, EGL_EXTENSIONS);
  const bool surfaceless = HasExtension(display_extensions, "EGL_KHR_surfaceless_context");
  const EGLint config_attributes[] = {EGL_SURFACE_TYPE,
                                      surfaceless ? 0 : EGL_PBUFFER_BIT,
                                      EGL_RENDERABLE_TYPE,
                                      EGL_OPENGL_BIT,
                                      EGL_RED_SIZE,
                                      8,
                                      EGL_GREEN_SIZE,
                                      8,
                                      EGL_BLUE_SIZE,
                                      8,
                                      EGL_NONE};
  EGLConfig config = nullptr;
  EGLint config_count = 0;
  if (eglChooseConfig(display, config_attributes, &config, 1, &config_count) != EGL_TRUE ||
      config_count < 1) {
    return Error{"headless OpenGL: no EGL configuration renders desktop OpenGL (" + EglErrorText() +
                 ")"};
  }
  const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                       3,
                                       EGL_CONTEXT_MINOR_VERSION,
                                       3,
                                       EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                       EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                       EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
  if (context == EGL_NO_CONTEXT) {
    return Error{"headless OpenGL: EGL cannot create an OpenGL 3.3 core context (" +
                 EglErrorText() + ")"};
  }
  ctx->context_ = context;
  if (!surfaceless) {
    const EGLint pbuffer_attributes[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
    EGLSurface surface = eglCreatePbufferSurface(display, config, pbuffer_attributes);
    if (surface == EGL_NO_SURFACE) {
      return Error{"headless OpenGL: EGL has neither surfaceless contexts nor pbuffers (" +
                   EglErrorText() + ")"};
    }
    ctx->surface_ = surface;
  }
  if (!ctx->MakeCurrent()) {
    return Error{"headless OpenGL: cannot make the context current (" + EglErrorText() + ")"};
  }
  PinLoadedLibrariesForLeakChecks();
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  ctx->gl_renderer_ = renderer != nullptr ? renderer : "unknown";
  return ctx;
}

bool HeadlessContext::MakeCurrent() {
  auto surface = static_cast<EGLSurface>(surface_ != nullptr ? surface_ : EGL_NO_SURFACE);
  return eglMakeCurrent(static_cast<EGLDisplay>(display_), surface, surface,
                        static_cast<EGLContext>(context_)) == EGL_TRUE;
}

HeadlessContext::~HeadlessContext() {
  if (display_ == nullptr) return;
  auto display = static_cast<EGLDisplay>(display_);
  eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (surface_ != nullptr) eglDestroySurface(display, static_cast<EGLSurface>(surface_));
  if (context_ != nullptr) eglDestroyContext(display, static_cast<EGLContext>(context_));
  eglTerminate(display);
}

// ---------------------------------------------------------------------------------------------

struct HeadlessRenderer::Impl {
  std::unique_ptr<HeadlessContext> context;
  std::unique_ptr<Renderer> renderer;  // destroyed before the context (declared after it)
  int samples = 4;
  Size size;
  gl::Framebuffer draw_fbo;  // multisampled colour + depth
  gl::Renderbuffer draw_color, draw_depth;
  gl::Framebuffer resolve_fbo;  // single-sampled colour, read back
  gl::Renderbuffer resolve_color;
  std::vector<std::uint8_t> row;  // scratch for the vertical flip

  ~Impl() {
    if (context) context->MakeCurrent();
    draw_fbo.Reset();
    draw_color.Reset();
    draw_depth.Reset();
    resolve_fbo.Reset();
    resolve_color.Reset();
    renderer.reset();
  }
};

HeadlessRenderer::HeadlessRenderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
HeadlessRenderer::~HeadlessRenderer() = default;

Result<std::unique_ptr<HeadlessRenderer>> HeadlessRenderer::Create(int samples) {
  auto impl = std::make_unique<Impl>();
  Result<std::unique_ptr<HeadlessContext>> context = HeadlessContext::Create();
  if (!context) return Error{context.error()};
  impl->context = std::move(context).value();
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  impl->samples = std::clamp(samples, 1, std::max(1, int(max_samples)));
  Result<std::unique_ptr<Renderer>> renderer = Renderer::Create();
  if (!renderer) return Error{"headless OpenGL: " + renderer.error()};
  impl->renderer = std::move(renderer).value();
  return std::unique_ptr<HeadlessRenderer>(new HeadlessRenderer(std::move(impl)));
}

Renderer& HeadlessRenderer::renderer() { return *impl_->renderer; }
HeadlessContext& HeadlessRenderer::context() { return *impl_->context; }

void HeadlessRenderer::BindTarget(Size size) {
  Impl& m = *impl_;
  if (m.size.width != size.width || m.size.height != size.height || !m.draw_fbo) {
    m.draw_fbo = gl::Framebuffer::Make();
    m.draw_color = gl::Renderbuffer::Make();
    m.draw_depth = gl::Renderbuffer::Make();
    m.resolve_fbo = gl::Framebuffer::Make();
    m.resolve_color = gl::Renderbuffer::Make();
    glBindRenderbuffer(GL_RENDERBUFFER, m.draw_color.get());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, m.samples, GL_RGBA8, size.width, size.height);
    glBindRenderbuffer(GL_RENDERBUFFER, m.draw_depth.get());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, m.samples, GL_DEPTH_COMPONENT24, size.width,
                                     size.height);
    glBindFramebuffer(GL_FRAMEBUFFER, m.draw_fbo.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              m.draw_color.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                              m.draw_depth.get());
    glBindRenderbuffer(GL_RENDERBUFFER, m.resolve_color.get());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, size.width, size.height);
    glBindFramebuffer(GL_FRAMEBUFFER, m.resolve_fbo.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              m.resolve_color.get());
    m.size = size;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, m.draw_fbo.get());
}

void HeadlessRenderer::RenderAndFinish(const RenderFrame& frame, const Camera& camera, Size size,
                                       const RenderOptions& options) {
  BindTarget(size);
  impl_->renderer->Render(frame, camera, size, options);
  glFinish();
}

Result<bool> HeadlessRenderer::RenderToImage(const RenderFrame& frame, const Camera& camera,
                                             Size size, Image* image,
                                             const RenderOptions& options) {
  if (size.width <= 0 || size.height <= 0 || size.width > 16384 || size.height > 16384) {
    return Error{"headless rendering: image size " + std::to_string(size.width) + "x" +
                 std::to_string(size.height) + " must be in 1..16384 per side"};
  }
  Impl& m = *impl_;
  BindTarget(size);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    return Error{"headless rendering: the offscreen framebuffer is incomplete at " +
                 std::to_string(size.width) + "x" + std::to_string(size.height)};
  }
  m.renderer->Render(frame, camera, size, options);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, m.draw_fbo.get());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m.resolve_fbo.get());
  glBlitFramebuffer(0, 0, size.width, size.height, 0, 0, size.width, size.height,
                    GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, m.resolve_fbo.get());
  image->width = size.width;
  image->height = size.height;
  const std::size_t stride = std::size_t(size.width) * 4;
  image->rgba.resize(stride * std::size_t(size.height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, size.width, size.height, GL_RGBA, GL_UNSIGNED_BYTE, image->rgba.data());
  glBindFramebuffer(GL_FRAMEBUFFER, m.draw_fbo.get());
  if (std::string e = gl::TakeGlError(); !e.empty()) {
    return Error{"headless rendering: OpenGL reported " + e};
  }
  // OpenGL's rows start at the bottom; images start at the top.
  m.row.resize(stride);
  for (int y = 0; y < size.height / 2; ++y) {
    std::uint8_t* a = image->rgba.data() + std::size_t(y) * stride;
    std::uint8_t* b = image->rgba.data() + std::size_t(size.height - 1 - y) * stride;
    std::memcpy(m.row.data(), a, stride);
    std::memcpy(a, b, stride);
    std::memcpy(b, m.row.data(), stride);
  }
  return true;
}

Result<std::filesystem::path> RenderToPng(const RenderFrame& frame, const Camera& camera, Size size,
                                          const std::filesystem::path& path,
                                          const RenderOptions& options) {
  Result<std::unique_ptr<HeadlessRenderer>> headless = HeadlessRenderer::Create();
  if (!headless) return Error{path.string() + ": " + headless.error()};
  Image image;
  Result<bool> rendered = headless.value()->RenderToImage(frame, camera, size, &image, options);
  if (!rendered) return Error{path.string() + ": " + rendered.error()};
  return SavePng(image, path);
}

SheetSize ContactSheetSize(int count, Size tile_size, int columns) {
  columns = std::max(1, std::min(columns, count));
  const std::int64_t rows = (std::int64_t(count) + columns - 1) / columns;
  return {columns * std::int64_t(tile_size.width) + (columns + 1) * std::int64_t(kSheetGutter),
          rows * std::int64_t(tile_size.height) + (rows + 1) * std::int64_t(kSheetGutter)};
}

Result<std::filesystem::path> RenderContactSheet(std::span<const ContactSheetTile> tiles,
                                                 Size tile_size, int columns,
                                                 const std::filesystem::path& path,
                                                 const RenderOptions& options) {
  if (tiles.empty()) return Error{path.string() + ": a contact sheet needs at least one tile"};
  if (columns < 1) return Error{path.string() + ": a contact sheet needs at least one column"};
  const int count = static_cast<int>(tiles.size());
  const SheetSize size = ContactSheetSize(count, tile_size, columns);
  if (size.width * size.height > kMaxPngPixels) {
    return Error{path.string() + ": a contact sheet of " + std::to_string(count) + " tiles of " +
                 std::to_string(tile_size.width) + "x" + std::to_string(tile_size.height) +
                 " would be " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                 " pixels, more than the " + std::to_string(kMaxPngPixels) +
                 " a PNG is written with"};
  }
  Result<std::unique_ptr<HeadlessRenderer>> headless = HeadlessRenderer::Create();
  if (!headless) return Error{path.string() + ": " + headless.error()};
  HeadlessRenderer& renderer = *headless.value();
  columns = std::min(columns, count);
  Image sheet;
  sheet.width = static_cast<int>(size.width);
  sheet.height = static_cast<int>(size.height);
  sheet.rgba.assign(std::size_t(sheet.width) * std::size_t(sheet.height) * 4, 255);
  Image tile_image;
  for (int i = 0; i < count; ++i) {
    const ContactSheetTile& tile = tiles[std::size_t(i)];
    // The label is the tile's caption, drawn by the renderer's overlay.
    RenderFrame frame = tile.frame;
    if (!tile.label.empty()) frame.caption = tile.label;
    Result<bool> rendered =
        renderer.RenderToImage(frame, tile.camera, tile_size, &tile_image, options);
    if (!rendered) {
      return Error{path.string() + ": tile " + std::to_string(i) + ": " + rendered.error()};
    }
    const int col = i % columns;
    const int row = i / columns;
    const int x0 = kSheetGutter + col * (tile_size.width + kSheetGutter);
    const int y0 = kSheetGutter + row * (tile_size.height + kSheetGutter);
    for (int y = 0; y < tile_size.height; ++y) {
      std::memcpy(sheet.rgba.data() +
                      (std::size_t(y0 + y) * std::size_t(sheet.width) + std::size_t(x0)) * 4,
                  tile_image.rgba.data() + std::size_t(y) * std::size_t(tile_size.width) * 4,
                  std::size_t(tile_size.width) * 4);
    }
  }
  return SavePng(sheet, path);
}

}  // namespace wirerig
