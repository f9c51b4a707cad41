#include "wirerig/viewer/renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <stb_easy_font.h>

#include "color_maps.h"
#include "gl.h"
#include "gl_objects.h"
#include "shaders.h"

namespace wirerig {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr int kArrowSegments = 16;

std::string Concat(const char* head, const char* common, const char* main) {
  std::string s(head);
  s.append(common).append(main);
  return s;
}

GLint Loc(GLuint program, const char* name) { return glGetUniformLocation(program, name); }
void SetVec3(GLuint program, const char* name, const Vec3f& v) {
  glUniform3f(Loc(program, name), v.x(), v.y(), v.z());
}
void SetMat4(GLuint program, const char* name, const Mat4f& m) {
  glUniformMatrix4fv(Loc(program, name), 1, GL_FALSE, m.data());
}

Mat4f LookAt(const Vec3f& eye, const Vec3f& center, const Vec3f& up_hint) {
  const Vec3f f = (center - eye).normalized();
  const Vec3f r = f.cross(up_hint).normalized();
  const Vec3f u = r.cross(f);
  Mat4f m = Mat4f::Identity();
  m.block<1, 3>(0, 0) = r.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -r.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Mat4f Ortho(float half, float near_plane, float far_plane) {
  Mat4f m = Mat4f::Identity();
  m(0, 0) = 1.0f / half;
  m(1, 1) = 1.0f / half;
  m(2, 2) = -2.0f / (far_plane - near_plane);
  m(2, 3) = -(far_plane + near_plane) / (far_plane - near_plane);
  return m;
}

Eigen::Vector4f Rgba(const Vec3f& c, float alpha) {
  return Eigen::Vector4f(c.x(), c.y(), c.z(), alpha);
}

Vec3f DirectionFromAngles(float yaw, float elevation) {
  const float c = std::cos(elevation);
  return Vec3f(c * std::sin(yaw), std::sin(elevation), c * std::cos(yaw));
}

Vec3f WireColor(WireKind kind) {
  switch (kind) {
    case WireKind::kProfile:
      return {0.02f, 0.16f, 0.85f};  // blue
    case WireKind::kSpine:
      return {0.97f, 0.22f, 0.52f};  // pink
    case WireKind::kOther:
      break;
  }
  return {0.08f, 0.08f, 0.08f};
}

struct MeshSlot {
  gl::VertexArray vao = gl::VertexArray::Make();
  gl::DynamicBuffer positions{GL_ARRAY_BUFFER};
  gl::DynamicBuffer normals{GL_ARRAY_BUFFER};
  gl::DynamicBuffer scalars{GL_ARRAY_BUFFER};
  gl::DynamicBuffer indices{GL_ELEMENT_ARRAY_BUFFER};

  MeshSlot() {
    glBindVertexArray(vao.get());
    positions.Upload(nullptr, 0);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3f), nullptr);
    normals.Upload(nullptr, 0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3f), nullptr);
    scalars.Upload(nullptr, 0);
    glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, sizeof(float), nullptr);
    indices.Upload(nullptr, 0);  // element buffer binding is part of the VAO
    glBindVertexArray(0);
  }
};

}  // namespace

struct Renderer::Impl {
  gl::Program mesh, depth, background, ground, wire, join, overlay;
  gl::VertexArray empty_vao = gl::VertexArray::Make();

  std::vector<MeshSlot> mesh_slots;

  gl::VertexArray arrow_vao = gl::VertexArray::Make();
  gl::DynamicBuffer arrow_buffer{GL_ARRAY_BUFFER};
  std::vector<float> arrow_vertices;  // position, normal
  std::vector<GLint> arrow_first;
  std::vector<GLsizei> arrow_count;

  gl::VertexArray wire_vao = gl::VertexArray::Make();
  gl::DynamicBuffer wire_buffer{GL_ARRAY_BUFFER};
  std::vector<float> wire_vertices;  // position, colour, width
  std::vector<GLint> wire_first;
  std::vector<GLsizei> wire_count;

  gl::VertexArray overlay_vao = gl::VertexArray::Make();
  gl::DynamicBuffer overlay_buffer{GL_ARRAY_BUFFER};
  std::vector<float> overlay_vertices;  // pixel x, y, linear rgba
  std::vector<char> font_scratch = std::vector<char>(1 << 16);
  std::string text_scratch;

  gl::Texture shadow_texture;
  gl::Framebuffer shadow_fbo;
  int shadow_size = 0;

  void EnsureShadowMap(int size);
  void BuildArrows(const RenderFrame& frame, float scene_diagonal);
  void BuildWires(const RenderFrame& frame, float width_scale);
  void AddQuad(float x0, float y0, float x1, float y1, const Eigen::Vector4f& c0,
               const Eigen::Vector4f& c1);
  void AddText(std::string_view text, Vec2f pixel, float scale, const Eigen::Vector4f& color);
  // Width of `text` in stb_easy_font pixels (scale 1).
  float TextWidth(std::string_view text) {
    text_scratch.assign(text);
    return float(stb_easy_font_width(text_scratch.data()));
  }
  void DrawOverlay(Size viewport);
};

void Renderer::Impl::EnsureShadowMap(int size) {
  if (shadow_size == size && shadow_texture) return;
  shadow_texture = gl::Texture::Make();
  glBindTexture(GL_TEXTURE_2D, shadow_texture.get());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, size, size, 0, GL_DEPTH_COMPONENT,
               GL_UNSIGNED_INT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  shadow_fbo = gl::Framebuffer::Make();
  glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbo.get());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadow_texture.get(),
                         0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  shadow_size = size;
}

void Renderer::Impl::BuildArrows(const RenderFrame& frame, float scene_diagonal) {
  arrow_vertices.clear();
  arrow_first.clear();
  arrow_count.clear();
  float per_newton = frame.arrow_length_per_newton;
  if (!(per_newton > 0.0f)) {
    float largest = 0.0f;
    for (const RenderArrow& a : frame.arrows) largest = std::max(largest, a.force.norm());
    per_newton = largest > 0.0f ? 0.25f * scene_diagonal / largest : 0.0f;
  }
  const float shaft_radius = 0.008f * scene_diagonal;
  auto push = [this](const Vec3f& p, const Vec3f& n) {
    arrow_vertices.insert(arrow_vertices.end(), {p.x(), p.y(), p.z(), n.x(), n.y(), n.z()});
  };
  for (const RenderArrow& a : frame.arrows) {
    const float length = a.force.norm() * per_newton;
    const GLint first = static_cast<GLint>(arrow_vertices.size() / 6);
    if (!(length > 1e-6f) || !a.origin.allFinite()) {
      arrow_first.push_back(first);
      arrow_count.push_back(0);
      continue;
    }
    const Vec3f dir = a.force.normalized();
    const Vec3f u =
        (std::abs(dir.y()) < 0.9f ? Vec3f::UnitY() : Vec3f::UnitX()).cross(dir).normalized();
    const Vec3f w = dir.cross(u);
    const float head_length = std::min(0.4f * length, 6.0f * shaft_radius);
    const float head_radius = 2.4f * shaft_radius;
    const Vec3f base = a.origin;
    const Vec3f neck = a.origin + (length - head_length) * dir;
    const Vec3f tip = a.origin + length * dir;
    const float slope = head_radius / head_length;
    for (int i = 0; i < kArrowSegments; ++i) {
      const float t0 = 2.0f * kPi * float(i) / kArrowSegments;
      const float t1 = 2.0f * kPi * float(i + 1) / kArrowSegments;
      const Vec3f r0 = std::cos(t0) * u + std::sin(t0) * w;
      const Vec3f r1 = std::cos(t1) * u + std::sin(t1) * w;
      // Shaft side.
      push(base + shaft_radius * r0, r0);
      push(neck + shaft_radius * r0, r0);
      push(neck + shaft_radius * r1, r1);
      push(base + shaft_radius * r0, r0);
      push(neck + shaft_radius * r1, r1);
      push(base + shaft_radius * r1, r1);
      // Cone side.
      const Vec3f n0 = (r0 + slope * dir).normalized();
      const Vec3f n1 = (r1 + slope * dir).normalized();
      push(neck + head_radius * r0, n0);
      push(tip, (n0 + n1).normalized());
      push(neck + head_radius * r1, n1);
      // Cone base and shaft cap.
      push(neck + head_radius * r1, -dir);
      push(neck, -dir);
      push(neck + head_radius * r0, -dir);
      push(base + shaft_radius * r1, -dir);
      push(base, -dir);
      push(base + shaft_radius * r0, -dir);
    }
    arrow_first.push_back(first);
    arrow_count.push_back(static_cast<GLsizei>(arrow_vertices.size() / 6) - first);
  }
  arrow_buffer.Upload(arrow_vertices.data(), arrow_vertices.size() * sizeof(float));
}

void Renderer::Impl::BuildWires(const RenderFrame& frame, float width_scale) {
  wire_vertices.clear();
  wire_first.clear();
  wire_count.clear();
  for (const RenderPolyline& line : frame.polylines) {
    if (line.points.size() < 2) continue;
    const Vec3f color = WireColor(line.kind);
    const float width = std::max(1.0f, line.width * width_scale);
    const GLint first = static_cast<GLint>(wire_vertices.size() / 7);
    auto push = [&](const Vec3f& p) {
      wire_vertices.insert(wire_vertices.end(),
                           {p.x(), p.y(), p.z(), color.x(), color.y(), color.z(), width});
    };
    for (const Vec3f& p : line.points) push(p);
    if (line.closed) push(line.points.front());
    wire_first.push_back(first);
    wire_count.push_back(static_cast<GLsizei>(wire_vertices.size() / 7) - first);
  }
  wire_buffer.Upload(wire_vertices.data(), wire_vertices.size() * sizeof(float));
}

void Renderer::Impl::AddQuad(float x0, float y0, float x1, float y1, const Eigen::Vector4f& c0,
                             const Eigen::Vector4f& c1) {
  // c0 on the left edge, c1 on the right edge.
  auto v = [this](float x, float y, const Eigen::Vector4f& c) {
    overlay_vertices.insert(overlay_vertices.end(), {x, y, c.x(), c.y(), c.z(), c.w()});
  };
  v(x0, y0, c0);
  v(x1, y0, c1);
  v(x1, y1, c1);
  v(x0, y0, c0);
  v(x1, y1, c1);
  v(x0, y1, c0);
}

void Renderer::Impl::AddText(std::string_view text, Vec2f pixel, float scale,
                             const Eigen::Vector4f& color) {
  text_scratch.assign(text);
  unsigned char rgba[4] = {255, 255, 255, 255};
  const int quads = stb_easy_font_print(0.0f, 0.0f, text_scratch.data(), rgba, font_scratch.data(),
                                        static_cast<int>(font_scratch.size()));
  for (int q = 0; q < quads; ++q) {
    float corners[4][2];
    for (int k = 0; k < 4; ++k) {
      float xyz[3];
      std::memcpy(xyz, font_scratch.data() + (q * 4 + k) * 16, sizeof(xyz));
      corners[k][0] = pixel.x() + scale * xyz[0];
      corners[k][1] = pixel.y() + scale * xyz[1];
    }
    AddQuad(corners[0][0], corners[0][1], corners[2][0], corners[2][1], color, color);
  }
}

void Renderer::Impl::DrawOverlay(Size viewport) {
  if (overlay_vertices.empty()) return;
  overlay_buffer.Upload(overlay_vertices.data(), overlay_vertices.size() * sizeof(float));
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glUseProgram(overlay.get());
  glUniform2f(Loc(overlay.get(), "u_viewport"), float(viewport.width), float(viewport.height));
  glBindVertexArray(overlay_vao.get());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(overlay_vertices.size() / 6));
  glBindVertexArray(0);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  overlay_vertices.clear();
}

Result<std::unique_ptr<Renderer>> Renderer::Create() {
  auto impl = std::make_unique<Impl>();
  using shaders::kCommon;
  struct Spec {
    gl::Program* target;
    const char* name;
    std::string vertex;
    std::string geometry;
    std::string fragment;
  };
  Spec specs[] = {
      {&impl->mesh, "mesh", shaders::kMeshVertex, "",
       Concat(shaders::kMeshFragmentHead, kCommon, shaders::kMeshFragmentMain)},
      {&impl->depth, "shadow depth", shaders::kDepthVertex, "", shaders::kDepthFragment},
      {&impl->background, "background", shaders::kBackgroundVertex, "",
       Concat(shaders::kBackgroundFragmentHead, kCommon, shaders::kBackgroundFragmentMain)},
      {&impl->ground, "ground", shaders::kGroundVertex, "",
       Concat(shaders::kGroundFragmentHead, kCommon, shaders::kGroundFragmentMain)},
      {&impl->wire, "wire", shaders::kWireVertex, shaders::kWireGeometry,
       Concat(shaders::kWireFragmentHead, kCommon, shaders::kWireFragmentMain)},
      {&impl->join, "wire join", shaders::kJoinVertex, "",
       Concat(shaders::kJoinFragmentHead, kCommon, shaders::kJoinFragmentMain)},
      {&impl->overlay, "overlay", shaders::kOverlayVertex, "",
       Concat(shaders::kOverlayFragmentHead, kCommon, shaders::kOverlayFragmentMain)},
  };
  for (Spec& spec : specs) {
    Result<gl::Program> program =
        gl::BuildProgram(spec.name, spec.vertex, spec.geometry, spec.fragment);
    if (!program) return Error{program.error()};
    *spec.target = std::move(program).value();
  }

  glBindVertexArray(impl->arrow_vao.get());
  impl->arrow_buffer.Upload(nullptr, 0);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                        reinterpret_cast<const void*>(3 * sizeof(float)));
  glVertexAttrib1f(2, 0.0f);

  glBindVertexArray(impl->wire_vao.get());
  impl->wire_buffer.Upload(nullptr, 0);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 7 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 7 * sizeof(float),
                        reinterpret_cast<const void*>(3 * sizeof(float)));

  glBindVertexArray(impl->overlay_vao.get());
  impl->overlay_buffer.Upload(nullptr, 0);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                        reinterpret_cast<const void*>(2 * sizeof(float)));
  glBindVertexArray(0);

  if (std::string e = gl::TakeGlError(); !e.empty()) {
    return Error{"renderer: OpenGL error while creating resources: " + e};
  }
  return std::unique_ptr<Renderer>(new Renderer(std::move(impl)));
}

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::~Renderer() = default;

void Renderer::Render(const RenderFrame& frame, const Camera& camera, Size viewport,
                      const RenderOptions& options) {
  Impl& m = *impl_;
  stats_ = RenderStats{};
  GLint target_fbo = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target_fbo);

  FrameBounds bounds = ComputeFrameBounds(frame);
  if (bounds.empty) {
    bounds.min = Vec3f::Constant(-0.5f);
    bounds.max = Vec3f::Constant(0.5f);
    bounds.empty = false;
  }
  const Vec3f center = bounds.Center();
  const float radius = std::max(bounds.Radius(), 1e-3f);
  const float ground_y = frame.ground_at_lowest_point ? bounds.min.y() : frame.ground_height;

  // Uploads.
  const auto upload_start = std::chrono::steady_clock::now();
  if (m.mesh_slots.size() < frame.meshes.size()) m.mesh_slots.resize(frame.meshes.size());
  for (std::size_t i = 0; i < frame.meshes.size(); ++i) {
    const RenderMesh& mesh = frame.meshes[i];
    MeshSlot& slot = m.mesh_slots[i];
    glBindVertexArray(slot.vao.get());
    slot.positions.Upload(mesh.positions.data(), mesh.positions.size_bytes());
    slot.normals.Upload(mesh.normals.data(), mesh.normals.size_bytes());
    const bool has_scalars = !mesh.scalars.empty() && mesh.scalars.size() == mesh.positions.size();
    if (has_scalars) {
      slot.scalars.Upload(mesh.scalars.data(), mesh.scalars.size_bytes());
      glEnableVertexAttribArray(2);
    } else {
      glDisableVertexAttribArray(2);
    }
    slot.indices.Upload(mesh.triangles.data(), mesh.triangles.size_bytes());
    stats_.meshes += 1;
    stats_.vertices += static_cast<int>(mesh.positions.size());
    stats_.triangles += static_cast<int>(mesh.triangles.size());
  }
  glBindVertexArray(0);
  const float width_scale = float(viewport.height) / 720.0f;
  if (options.show_arrows) m.BuildArrows(frame, 2.0f * radius);
  if (options.show_wires) m.BuildWires(frame, width_scale);
  stats_.polylines = static_cast<int>(m.wire_first.size());
  stats_.polyline_points = static_cast<int>(m.wire_vertices.size() / 7);
  stats_.arrows = options.show_arrows ? static_cast<int>(frame.arrows.size()) : 0;
  stats_.upload_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - upload_start)
          .count();

  // Lights follow the camera: the key from above-left of the eye, the fill low from the right,
  // the rim from behind.
  const Vec3f key_dir = DirectionFromAngles(camera.yaw - 0.6f, 1.2f);
  const Vec3f fill_dir = DirectionFromAngles(camera.yaw + 1.3f, 0.25f);
  const Vec3f rim_dir = DirectionFromAngles(camera.yaw + kPi, 0.6f);

  // Shadow pass.
  const float shadow_reach = radius * 1.05f;
  const Vec3f light_eye = center + key_dir * 3.0f * radius;
  const Mat4f light_view_proj =
      Ortho(shadow_reach, 0.5f * radius, 8.0f * radius) *
      LookAt(light_eye, center, std::abs(key_dir.y()) > 0.99f ? Vec3f::UnitZ() : Vec3f::UnitY());
  const bool shadows = options.shadows && (!frame.meshes.empty() || !m.arrow_first.empty());
  if (shadows) {
    m.EnsureShadowMap(std::max(options.shadow_map_size, 64));
    glBindFramebuffer(GL_FRAMEBUFFER, m.shadow_fbo.get());
    glViewport(0, 0, m.shadow_size, m.shadow_size);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.5f, 2.0f);
    glUseProgram(m.depth.get());
    SetMat4(m.depth.get(), "u_view_proj", light_view_proj);
    for (std::size_t i = 0; i < frame.meshes.size(); ++i) {
      glBindVertexArray(m.mesh_slots[i].vao.get());
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * frame.meshes[i].triangles.size()),
                     GL_UNSIGNED_INT, nullptr);
    }
    if (!m.arrow_vertices.empty()) {
      glBindVertexArray(m.arrow_vao.get());
      glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(m.arrow_vertices.size() / 6));
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
  }

  // Main pass.
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target_fbo));
  glViewport(0, 0, viewport.width, viewport.height);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  const Mat4f view = camera.ViewMatrix();
  const Mat4f proj = camera.ProjectionMatrix(viewport.Aspect());
  const Mat4f view_proj = proj * view;

  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LEQUAL);

  auto set_lights = [&](GLuint p) {
    SetVec3(p, "u_eye", camera.Eye());
    SetVec3(p, "u_key_dir", key_dir);
    SetVec3(p, "u_key_color", Vec3f(1.0f, 0.95f, 0.88f) * 1.45f);
    SetVec3(p, "u_fill_dir", fill_dir);
    SetVec3(p, "u_fill_color", Vec3f(0.75f, 0.85f, 1.0f) * 0.35f);
    SetVec3(p, "u_rim_dir", rim_dir);
    SetVec3(p, "u_rim_color", Vec3f(1.0f, 1.0f, 1.0f) * 0.25f);
    SetVec3(p, "u_sky_color", Vec3f(0.50f, 0.56f, 0.66f) * 0.4f);
    SetVec3(p, "u_ground_color", Vec3f(0.30f, 0.27f, 0.24f) * 0.35f);
    SetMat4(p, "u_light_view_proj", light_view_proj);
    glUniform1i(Loc(p, "u_shadows"), shadows ? 1 : 0);
    glUniform1f(Loc(p, "u_shadow_texel"), 1.0f / float(std::max(m.shadow_size, 1)));
    glUniform1f(Loc(p, "u_shadow_normal_offset"),
                1.5f * 2.0f * shadow_reach / float(std::max(m.shadow_size, 1)));
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, shadows ? m.shadow_texture.get() : 0);
    glUniform1i(Loc(p, "u_shadow_map"), 0);
  };

  // Meshes.
  const GLuint mp = m.mesh.get();
  glUseProgram(mp);
  set_lights(mp);
  SetMat4(mp, "u_view_proj", view_proj);
  glUniform2f(Loc(mp, "u_scalar_range"), frame.legend.min,
              frame.legend.max > frame.legend.min ? frame.legend.max : frame.legend.min + 1.0f);
  const auto& stops = ColorMapStops(frame.legend.map);
  glUniform3fv(Loc(mp, "u_color_stops"), kColorMapStops, stops[0].data());
  if (options.wireframe) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
  }
  bool any_scalars = false;
  for (std::size_t i = 0; i < frame.meshes.size(); ++i) {
    const RenderMesh& mesh = frame.meshes[i];
    const bool has_scalars = !mesh.scalars.empty() && mesh.scalars.size() == mesh.positions.size();
    any_scalars = any_scalars || has_scalars;
    glUniform1i(Loc(mp, "u_mode"), has_scalars ? 1 : 0);
    SetVec3(mp, "u_base_color", mesh.base_color);
    glBindVertexArray(m.mesh_slots[i].vao.get());
    if (mesh.cull_back_faces) {
      glEnable(GL_CULL_FACE);
      glCullFace(GL_BACK);
      glFrontFace(GL_CCW);
    }
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * mesh.triangles.size()), GL_UNSIGNED_INT,
                   nullptr);
    glDisable(GL_CULL_FACE);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  if (options.wireframe && !frame.meshes.empty()) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glUniform1i(Loc(mp, "u_mode"), 2);
    glUniform4f(Loc(mp, "u_flat_color"), 0.02f, 0.02f, 0.03f, 0.45f);
    for (std::size_t i = 0; i < frame.meshes.size(); ++i) {
      glBindVertexArray(m.mesh_slots[i].vao.get());
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * frame.meshes[i].triangles.size()),
                     GL_UNSIGNED_INT, nullptr);
    }
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
  }

  // Arrows.
  if (options.show_arrows && !m.arrow_vertices.empty()) {
    glUniform1i(Loc(mp, "u_mode"), 0);
    glBindVertexArray(m.arrow_vao.get());
    for (std::size_t i = 0; i < m.arrow_first.size(); ++i) {
      if (m.arrow_count[i] == 0) continue;
      SetVec3(mp, "u_base_color", frame.arrows[i].color);
      glDrawArrays(GL_TRIANGLES, m.arrow_first[i], m.arrow_count[i]);
    }
  }

  // Opaque things front to back where it helps llvmpipe's early depth test: the model and arrows
  // first, then the ground (only where the model does not cover it), then the background.
  // Ground: seen from above only (an eye below it, as a follow camera can be, would see its
  // underside hide the model).
  if (frame.ground && camera.Eye().y() > ground_y) {
    const GLuint p = m.ground.get();
    glUseProgram(p);
    set_lights(p);
    SetMat4(p, "u_view_proj", view_proj);
    const float half = 4.0f * radius;
    glUniform4f(Loc(p, "u_ground"), center.x(), ground_y, center.z(), half);
    SetVec3(p, "u_ground_albedo", Vec3f(0.50f, 0.50f, 0.48f));
    const float spacing = std::pow(10.0f, std::floor(std::log10(0.5f * radius)));
    glUniform1f(Loc(p, "u_grid_spacing"), spacing);
    glUniform4f(Loc(p, "u_footprint"), center.x(), center.z(),
                0.5f * (bounds.max.x() - bounds.min.x()), 0.5f * (bounds.max.z() - bounds.min.z()));
    glUniform1f(Loc(p, "u_footprint_lift"), std::max(bounds.min.y() - ground_y, 0.0f));
    glUniform1f(Loc(p, "u_model_radius"), radius);
    SetVec3(p, "u_top", options.background_top);
    SetVec3(p, "u_bottom", options.background_bottom);
    glUniform1f(Loc(p, "u_viewport_height"), float(std::max(viewport.height, 1)));
    glBindVertexArray(m.empty_vao.get());
    glDrawArrays(GL_TRIANGLES, 0, 6);
  }

  // Background: at the far plane, so only pixels nothing else covered are shaded.
  glUseProgram(m.background.get());
  SetVec3(m.background.get(), "u_top", options.background_top);
  SetVec3(m.background.get(), "u_bottom", options.background_bottom);
  glBindVertexArray(m.empty_vao.get());
  glDepthMask(GL_FALSE);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);

  // Wires: the hidden parts faded, then the visible parts.
  if (options.show_wires && !m.wire_first.empty()) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glDepthMask(GL_FALSE);
    glBindVertexArray(m.wire_vao.get());
    const GLsizei count = static_cast<GLsizei>(m.wire_first.size());
    for (int pass = 0; pass < 2; ++pass) {
      glDepthFunc(pass == 0 ? GL_GREATER : GL_LEQUAL);
      const float alpha = pass == 0 ? 0.55f : 1.0f;
      for (GLuint p : {m.wire.get(), m.join.get()}) {
        glUseProgram(p);
        SetMat4(p, "u_view", view);
        SetMat4(p, "u_proj", proj);
        glUniform1f(Loc(p, "u_depth_pull"), 0.004f * radius);
        glUniform2f(Loc(p, "u_viewport"), float(viewport.width), float(viewport.height));
        glUniform1f(Loc(p, "u_alpha"), alpha);
        glMultiDrawArrays(p == m.wire.get() ? GL_LINE_STRIP : GL_POINTS, m.wire_first.data(),
                          m.wire_count.data(), count);
      }
    }
    glDisable(GL_PROGRAM_POINT_SIZE);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LEQUAL);
    glDisable(GL_BLEND);
  }
  glBindVertexArray(0);

  // Overlay: legend and caption.
  if (options.show_overlay) {
    const float s = std::max(1.0f, 2.0f * float(viewport.height) / 720.0f);
    const float margin = 12.0f * s;
    const Eigen::Vector4f ink(0.02f, 0.02f, 0.025f, 1.0f);
    // Top-right corner: the caption, then the legend under it (windows keep their HUD at the
    // top-left and their timeline along the bottom).
    const float right = float(viewport.width) - margin;
    const float text_h = 8.0f * s;
    float y = margin;
    if (!frame.caption.empty()) {
      m.AddText(frame.caption, Vec2f(right - m.TextWidth(frame.caption) * s, y), s, ink);
      y += text_h + 6.0f * s;
    }
    if (any_scalars && frame.legend.show) {
      const float bar_w = std::max(110.0f * s, m.TextWidth(frame.legend.label) * s);
      const float bar_h = 7.0f * s;
      const float x0 = right - bar_w;
      const float label_y = y + 4.0f * s;
      const float bar_y0 = label_y + text_h + 3.0f * s;
      const float bar_y1 = bar_y0 + bar_h;
      const float numbers_y = bar_y1 + 3.0f * s;
      m.AddQuad(x0 - 4.0f * s, y, right + 4.0f * s, numbers_y + text_h + 2.0f * s,
                Eigen::Vector4f(1, 1, 1, 0.55f), Eigen::Vector4f(1, 1, 1, 0.55f));
      constexpr int kBarSteps = 32;
      for (int k = 0; k < kBarSteps; ++k) {
        const float t0 = float(k) / kBarSteps;
        const float t1 = float(k + 1) / kBarSteps;
        m.AddQuad(x0 + t0 * bar_w, bar_y0, x0 + t1 * bar_w, bar_y1,
                  Rgba(EvaluateColorMap(frame.legend.map, t0), 1.0f),
                  Rgba(EvaluateColorMap(frame.legend.map, t1), 1.0f));
      }
      char number[32];
      std::snprintf(number, sizeof(number), "%.3g", double(frame.legend.min));
      m.AddText(number, Vec2f(x0, numbers_y), s, ink);
      std::snprintf(number, sizeof(number), "%.3g", double(frame.legend.max));
      m.AddText(number, Vec2f(right - m.TextWidth(number) * s, numbers_y), s, ink);
      if (!frame.legend.label.empty()) m.AddText(frame.legend.label, Vec2f(x0, label_y), s, ink);
    }
    m.DrawOverlay(viewport);
  }
  glUseProgram(0);
}

void Renderer::DrawText(std::string_view text, Vec2f pixel, float scale, const Vec3f& color,
                        Size viewport) {
  impl_->AddText(text, pixel, scale, Rgba(color, 1.0f));
  impl_->DrawOverlay(viewport);
  glUseProgram(0);
}

}  // namespace wirerig
