// GLSL 3.30 core sources of the renderer's programs.
#pragma once

namespace wirerig::shaders {

// Shared by the lit programs: sRGB encoding, tone mapping, lights, shadow lookup.
inline constexpr const char* kCommon = R"glsl(
vec3 EncodeSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  vec3 lo = 12.92 * c;
  vec3 hi = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
  return mix(lo, hi, step(vec3(0.0031308), c));
}
// Narkowicz's fit of the ACES filmic curve, scaled so that mid-grey stays near mid-grey.
vec3 ToneMap(vec3 x) {
  x *= 0.8;
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
uniform vec3 u_eye;
uniform vec3 u_key_dir;    // towards the light, unit
uniform vec3 u_key_color;
uniform vec3 u_fill_dir;
uniform vec3 u_fill_color;
uniform vec3 u_rim_dir;
uniform vec3 u_rim_color;
uniform vec3 u_sky_color;
uniform vec3 u_ground_color;
uniform sampler2DShadow u_shadow_map;
uniform mat4 u_light_view_proj;
uniform int u_shadows;
uniform float u_shadow_texel;          // one shadow-map texel, in texture coordinates
uniform float u_shadow_normal_offset;  // world offset along the normal against acne, m

// Fraction of the key light reaching world point p (1 = lit): four bilinear-PCF taps one texel
// apart (a 4x4-texel footprint), cheap enough for llvmpipe.
float KeyVisibility(vec3 p, vec3 n) {
  if (u_shadows == 0) return 1.0;
  vec4 c = u_light_view_proj * vec4(p + n * u_shadow_normal_offset, 1.0);
  vec3 s = c.xyz / c.w * 0.5 + 0.5;
  if (s.x <= 0.0 || s.x >= 1.0 || s.y <= 0.0 || s.y >= 1.0 || s.z >= 1.0) return 1.0;
  float d = u_shadow_texel;
  float z = s.z - 0.0015;
  return 0.25 * (texture(u_shadow_map, vec3(s.xy + vec2(-d, -d), z)) +
                 texture(u_shadow_map, vec3(s.xy + vec2(d, -d), z)) +
                 texture(u_shadow_map, vec3(s.xy + vec2(-d, d), z)) +
                 texture(u_shadow_map, vec3(s.xy + vec2(d, d), z)));
}

vec3 Shade(vec3 albedo, vec3 p, vec3 n, float visibility) {
  vec3 v = normalize(u_eye - p);
  float nk = max(dot(n, u_key_dir), 0.0);
  vec3 h = normalize(u_key_dir + v);
  float spec = pow(max(dot(n, h), 0.0), 40.0) * 0.18 * step(0.0, dot(n, u_key_dir));
  vec3 c = (albedo * nk + vec3(spec)) * u_key_color * visibility;
  c += albedo * u_fill_color * max(dot(n, u_fill_dir), 0.0);
  c += albedo * mix(u_ground_color, u_sky_color, 0.5 + 0.5 * n.y);
  float rim = pow(1.0 - max(dot(n, v), 0.0), 3.0);
  c += u_rim_color * rim * (0.35 + 0.65 * max(dot(n, u_rim_dir), 0.0));
  return c;
}
)glsl";

inline constexpr const char* kMeshVertex = R"glsl(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_scalar;
uniform mat4 u_view_proj;
out vec3 v_position;
out vec3 v_normal;
out float v_scalar;
void main() {
  v_position = a_position;
  v_normal = a_normal;
  v_scalar = a_scalar;
  gl_Position = u_view_proj * vec4(a_position, 1.0);
}
)glsl";

inline constexpr const char* kMeshFragmentHead = R"glsl(#version 330 core
in vec3 v_position;
in vec3 v_normal;
in float v_scalar;
out vec4 o_color;
uniform int u_mode;  // 0 base colour, 1 colour map, 2 flat colour (wireframe edges)
uniform vec3 u_base_color;
uniform vec4 u_flat_color;
uniform vec2 u_scalar_range;
uniform vec3 u_color_stops[5];
)glsl";

inline constexpr const char* kMeshFragmentMain = R"glsl(
vec3 ColorMap(float value) {
  float t = clamp((value - u_scalar_range.x) / (u_scalar_range.y - u_scalar_range.x), 0.0, 1.0);
  float x = t * 4.0;
  int i = min(int(x), 3);
  return mix(u_color_stops[i], u_color_stops[i + 1], x - float(i));
}
void main() {
  if (u_mode == 2) {
    o_color = vec4(EncodeSrgb(u_flat_color.rgb), u_flat_color.a);
    return;
  }
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 albedo = u_mode == 1 ? ColorMap(v_scalar) : u_base_color;
  vec3 c = Shade(albedo, v_position, n, KeyVisibility(v_position, n));
  o_color = vec4(EncodeSrgb(ToneMap(c)), 1.0);
}
)glsl";

inline constexpr const char* kDepthVertex = R"glsl(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_proj;
void main() { gl_Position = u_view_proj * vec4(a_position, 1.0); }
)glsl";

inline constexpr const char* kDepthFragment = R"glsl(#version 330 core
void main() {}
)glsl";

// Background: one triangle covering the screen, a vertical gradient.
inline constexpr const char* kBackgroundVertex = R"glsl(#version 330 core
out float v_t;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
  v_t = 0.5 * p.y + 0.5;
  gl_Position = vec4(p, 1.0, 1.0);
}
)glsl";

inline constexpr const char* kBackgroundFragmentHead = R"glsl(#version 330 core
in float v_t;
out vec4 o_color;
uniform vec3 u_top;
uniform vec3 u_bottom;
)glsl";

inline constexpr const char* kBackgroundFragmentMain = R"glsl(
void main() { o_color = vec4(EncodeSrgb(mix(u_bottom, u_top, v_t)), 1.0); }
)glsl";

// Ground: a square at height u_ground.y around u_ground.xz, half size u_ground.w; a soft grid,
// the key-light shadow, a contact-occlusion blob under the model, and a fade into the
// background towards the edge.
inline constexpr const char* kGroundVertex = R"glsl(#version 330 core
uniform vec4 u_ground;  // centre x, height, centre z, half size
uniform mat4 u_view_proj;
out vec3 v_position;
void main() {
  int id = gl_VertexID % 3;
  vec2 corner = vec2(float((id << 1) & 2), float(id & 2)) - 1.0;
  if (gl_VertexID >= 3) corner = -corner;
  v_position = vec3(u_ground.x + corner.x * u_ground.w, u_ground.y, u_ground.z + corner.y * u_ground.w);
  gl_Position = u_view_proj * vec4(v_position, 1.0);
}
)glsl";

inline constexpr const char* kGroundFragmentHead = R"glsl(#version 330 core
in vec3 v_position;
out vec4 o_color;
uniform vec4 u_ground;
uniform vec3 u_ground_albedo;
uniform float u_grid_spacing;
uniform vec4 u_footprint;  // centre x, centre z, half extents x, z of the model
uniform float u_footprint_lift;  // height of the model's lowest point above the ground
uniform float u_model_radius;
uniform vec3 u_top;     // the background gradient the ground fades into (linear)
uniform vec3 u_bottom;
uniform float u_viewport_height;
)glsl";

inline constexpr const char* kGroundFragmentMain = R"glsl(
float GridLine(vec2 p, float spacing, float width) {
  vec2 g = abs(fract(p / spacing - 0.5) - 0.5) / fwidth(p / spacing);
  return 1.0 - clamp(min(g.x, g.y) - width, 0.0, 1.0);
}
void main() {
  vec3 n = vec3(0.0, 1.0, 0.0);
  vec3 albedo = u_ground_albedo;
  float minor = GridLine(v_position.xz, u_grid_spacing, 0.0);
  float major = GridLine(v_position.xz, u_grid_spacing * 10.0, 0.5);
  albedo *= 1.0 - 0.10 * minor - 0.18 * major;
  // Contact occlusion: darkest right under the model's footprint, fading with the distance
  // outside it and with the model's lift above the ground.
  vec2 d = max(abs(v_position.xz - u_footprint.xy) - u_footprint.zw, 0.0);
  float reach = 0.35 * u_model_radius + u_footprint_lift;
  float occlusion = 0.6 * exp(-dot(d, d) / (reach * reach)) * reach / (reach + 2.0 * u_footprint_lift);
  vec3 c = Shade(albedo, v_position, n, KeyVisibility(v_position, n)) * (1.0 - occlusion);
  c = ToneMap(c);
  float r = length(v_position.xz - u_ground.xz) / u_ground.w;
  float fade = smoothstep(0.55, 1.0, r);
  vec3 background = mix(u_bottom, u_top, gl_FragCoord.y / u_viewport_height);
  o_color = vec4(EncodeSrgb(mix(c, background, fade)), 1.0);
}
)glsl";

// Wires: line segments widened into screen-space ribbons by a geometry shader.
inline constexpr const char* kWireVertex = R"glsl(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec4 a_color_width;  // linear rgb, width in pixels
uniform mat4 u_view;
uniform mat4 u_proj;
uniform float u_depth_pull;  // m towards the eye, so wires on a surface win the depth test
out vec4 g_color_width;
void main() {
  vec4 view = u_view * vec4(a_position, 1.0);
  view.xyz += normalize(-view.xyz) * u_depth_pull;
  g_color_width = a_color_width;
  gl_Position = u_proj * view;
  gl_PointSize = a_color_width.w;
}
)glsl";

inline constexpr const char* kWireGeometry = R"glsl(#version 330 core
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
in vec4 g_color_width[];
uniform vec2 u_viewport;
out vec3 f_color;
out float f_across;  // -1 .. 1 across the ribbon
out float f_half_width;
void main() {
  vec4 p0 = gl_in[0].gl_Position;
  vec4 p1 = gl_in[1].gl_Position;
  if (p0.w <= 1e-6 || p1.w <= 1e-6) return;
  vec2 s0 = p0.xy / p0.w * 0.5 * u_viewport;
  vec2 s1 = p1.xy / p1.w * 0.5 * u_viewport;
  vec2 d = s1 - s0;
  float len = length(d);
  d = len > 1e-4 ? d / len : vec2(1.0, 0.0);
  vec2 n = vec2(-d.y, d.x);
  for (int k = 0; k < 4; ++k) {
    int end = k / 2;
    float side = (k % 2 == 0) ? -1.0 : 1.0;
    vec4 p = end == 0 ? p0 : p1;
    float half_width = 0.5 * g_color_width[end].w + 1.0;  // +1 pixel for antialiasing
    vec2 offset = n * side * half_width / (0.5 * u_viewport);
    gl_Position = vec4(p.xy + offset * p.w, p.zw);
    f_color = g_color_width[end].rgb;
    f_across = side;
    f_half_width = half_width;
    EmitVertex();
  }
  EndPrimitive();
}
)glsl";

inline constexpr const char* kWireFragmentHead = R"glsl(#version 330 core
in vec3 f_color;
in float f_across;
in float f_half_width;
out vec4 o_color;
uniform float u_alpha;
)glsl";

inline constexpr const char* kWireFragmentMain = R"glsl(
void main() {
  float from_edge = (1.0 - abs(f_across)) * f_half_width;  // pixels
  float coverage = clamp(from_edge, 0.0, 1.0);
  float shade = mix(0.55, 1.0, smoothstep(0.0, 0.6, 1.0 - abs(f_across)));
  o_color = vec4(EncodeSrgb(f_color * shade), coverage * u_alpha);
}
)glsl";

// Round joins: the polyline's points as discs of the ribbon's width.
inline constexpr const char* kJoinVertex = kWireVertex;

inline constexpr const char* kJoinFragmentHead = R"glsl(#version 330 core
in vec4 g_color_width;
out vec4 o_color;
uniform float u_alpha;
)glsl";

inline constexpr const char* kJoinFragmentMain = R"glsl(
void main() {
  vec2 q = gl_PointCoord * 2.0 - 1.0;
  float r = length(q);
  float radius_px = 0.5 * g_color_width.w;
  float coverage = clamp((1.0 - r) * radius_px, 0.0, 1.0);
  if (coverage <= 0.0) discard;
  float shade = mix(0.55, 1.0, smoothstep(0.0, 0.6, 1.0 - r));
  o_color = vec4(EncodeSrgb(g_color_width.rgb * shade), coverage * u_alpha);
}
)glsl";

// Overlay: 2D triangles in pixels (origin top-left) with linear RGBA colours.
inline constexpr const char* kOverlayVertex = R"glsl(#version 330 core
layout(location = 0) in vec2 a_pixel;
layout(location = 1) in vec4 a_color;
uniform vec2 u_viewport;
out vec4 v_color;
void main() {
  v_color = a_color;
  gl_Position = vec4(a_pixel.x / u_viewport.x * 2.0 - 1.0, 1.0 - a_pixel.y / u_viewport.y * 2.0, 0.0, 1.0);
}
)glsl";

inline constexpr const char* kOverlayFragmentHead = R"glsl(#version 330 core
in vec4 v_color;
out vec4 o_color;
)glsl";

inline constexpr const char* kOverlayFragmentMain = R"glsl(
void main() { o_color = vec4(EncodeSrgb(v_color.rgb), v_color.a); }
)glsl";

}  // namespace wirerig::shaders
