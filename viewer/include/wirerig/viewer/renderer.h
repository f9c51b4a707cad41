// Renderer: draws a RenderFrame through a Camera with OpenGL 3.3 core into the framebuffer
// that is bound when Render() is called. Works on software rasterisers (Mesa llvmpipe): one
// shadow map, no compute, no extensions.
//
// Look: a key light (warm, casts the shadow), a fill light (cool) and a rim light, a hemisphere
// ambient term, tone mapping and sRGB output; a ground plane with a soft grid under the model;
// wires as screen-space ribbons with round joins (faded where the mesh hides them); force
// arrows; an optional colour-map legend and caption drawn with stb_easy_font.
//
// Threading and context: a Renderer belongs to the GL context that was current when it was
// created; create, use and destroy it with that context current. Render() allocates nothing
// in the steady state: its GPU buffers grow geometrically and are reused, and its CPU scratch
// vectors keep their capacity.
#pragma once

#include <memory>
#include <string_view>

#include "wirerig/io/result.h"
#include "wirerig/viewer/camera.h"
#include "wirerig/viewer/render_frame.h"

namespace wirerig {

struct RenderOptions {
  bool wireframe = false;                        // dark triangle edges over the shaded mesh
  bool shadows = true;                           // key-light shadow map on the ground and the model
  bool show_wires = true;                        // polylines
  bool show_arrows = true;                       // force arrows
  bool show_overlay = true;                      // legend and caption
  Vec3f background_top{0.60f, 0.66f, 0.74f};     // linear RGB, vertical gradient
  Vec3f background_bottom{0.93f, 0.93f, 0.92f};  // linear RGB
  int shadow_map_size = 2048;                    // texels per side
};

// Counts of the last Render(), for HUDs and tests.
struct RenderStats {
  int meshes = 0;
  int vertices = 0;
  int triangles = 0;
  int polylines = 0;
  int polyline_points = 0;
  int arrows = 0;
  // CPU time of the uploads (mesh buffers, wire ribbons, arrows) of the last Render(), ms.
  double upload_ms = 0.0;
};

class Renderer {
 public:
  // Compiles the shaders and makes the static resources. Needs a current OpenGL 3.3 core
  // context; the error says which shader failed and why.
  static Result<std::unique_ptr<Renderer>> Create();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Draws `frame` through `camera` into the bound framebuffer, whose size is `viewport`
  // (pixels). Clears it first. Leaves depth test on and blending off.
  void Render(const RenderFrame& frame, const Camera& camera, Size viewport,
              const RenderOptions& options = {});

  // Draws `text` in pixels (origin top-left) with stb_easy_font at `scale` times its 8-pixel
  // line height over whatever is in the framebuffer; colour is linear RGB. For labels.
  void DrawText(std::string_view text, Vec2f pixel, float scale, const Vec3f& color, Size viewport);

  const RenderStats& stats() const { return stats_; }

 private:
  struct Impl;
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  RenderStats stats_;
};

}  // namespace wirerig
