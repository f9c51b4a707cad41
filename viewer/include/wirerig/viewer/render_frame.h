// RenderFrame: what the renderer draws, as plain data that knows nothing of scenes, rigs or
// clips. Every array is a span over the caller's memory, read during Render() only, so a frame
// can be refilled every tick without allocating. Units and axes follow the runtime's
// conventions (metres, +Y up, counter-clockwise triangles facing outwards); colours are
// linear RGB in [0, 1] (the renderer converts to sRGB on output).
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include <Eigen/Core>

#include "wirerig/runtime/conventions.h"

namespace wirerig {

using Vec3f = Eigen::Vector3f;

// How a per-vertex scalar (bending moment, strain, ...) becomes a colour.
enum class ColorMap : int {
  kCoolWarm = 0,  // diverging blue-white-red: signed quantities such as bending moment
  kViridis = 1,   // sequential: magnitudes
};

// Linear RGB of colour map `map` at t in [0, 1] (clamped): piecewise linear through five
// stops; the shaders use the same stops.
Vec3f EvaluateColorMap(ColorMap map, float t);

// The range a scalar is mapped over, and the legend drawn for it.
struct ScalarLegend {
  float min = 0.0f;  // maps to the left end of the colour map
  float max = 1.0f;  // maps to the right end; min < max
  ColorMap map = ColorMap::kCoolWarm;
  std::string_view label;  // e.g. "bending moment (N m)"; printed above the colour bar
  bool show = true;        // draws the colour bar when some mesh has scalars
};

// A triangle mesh: #V positions and #V normals, #F triangles indexing them.
struct RenderMesh {
  std::span<const Vec3f> positions;       // #V, m
  std::span<const Vec3f> normals;         // #V unit normals (see ComputeVertexNormals)
  std::span<const Triangle> triangles;    // #F, indices < #V
  Vec3f base_color{0.80f, 0.30f, 0.10f};  // linear RGB (an sRGB orange)
  // Optional #V scalars coloured through RenderFrame::legend; empty for base_color.
  std::span<const float> scalars;
  // Skip triangles facing away from the eye. Only for closed, outward-oriented meshes (such as
  // the procedural ones); open or inconsistently wound meshes need both sides drawn. Saves
  // rasterising the hidden back half on software rasterisers.
  bool cull_back_faces = false;
};

// Which wire a polyline shows; picks its default colour (the paper's figures: profile wires
// blue, spine wires pink).
enum class WireKind : int { kProfile = 0, kSpine = 1, kOther = 2 };

// A polyline of #P >= 2 points drawn as a screen-space ribbon `width` pixels wide. Wires are
// drawn on top of the mesh: the parts behind it are faded rather than hidden, so spines inside
// a body stay visible.
struct RenderPolyline {
  std::span<const Vec3f> points;  // #P, m
  WireKind kind = WireKind::kProfile;
  bool closed = false;   // joins the last point to the first (profile loops)
  float width = 3.0f;    // pixels at the reference height of 720 pixels
  bool pickable = true;  // PickPolyline considers it
  std::uint32_t id = 0;  // returned by picking; the caller's wire number
};

// A force drawn as an arrow from `origin` along `force`, `length_per_newton` metres long per
// newton (RenderFrame::arrow_length_per_newton).
struct RenderArrow {
  Vec3f origin = Vec3f::Zero();      // m
  Vec3f force = Vec3f::Zero();       // N
  Vec3f color{0.90f, 0.10f, 0.02f};  // linear RGB
};

struct RenderFrame {
  std::span<const RenderMesh> meshes;
  std::span<const RenderPolyline> polylines;
  std::span<const RenderArrow> arrows;
  ScalarLegend legend;
  // Arrow length per newton, m/N; 0 picks one so that the largest arrow is a quarter of the
  // frame's bounding-box diagonal.
  float arrow_length_per_newton = 0.0f;
  // The ground plane sits at this height (m) under the model and receives its shadow.
  bool ground = true;
  bool ground_at_lowest_point = true;  // true: at the lowest mesh/wire point, not ground_height
  float ground_height = 0.0f;
  // Optional caption drawn in the top-left corner (e.g. "t = 1.25 s").
  std::string_view caption;
};

// Axis-aligned bounds of everything in a frame (meshes, polylines, arrow tips). `empty` when
// the frame holds no point.
struct FrameBounds {
  Vec3f min = Vec3f::Zero();
  Vec3f max = Vec3f::Zero();
  bool empty = true;
  Vec3f Center() const { return 0.5f * (min + max); }
  float Radius() const { return 0.5f * (max - min).norm(); }
};
FrameBounds ComputeFrameBounds(const RenderFrame& frame);

// Area-weighted smooth vertex normals of a triangle mesh, written to `normals` (#V, sized by
// the caller). Vertices no triangle touches get +Y. Allocation-free: meant for every frame.
void ComputeVertexNormals(std::span<const Vec3f> positions, std::span<const Triangle> triangles,
                          std::span<Vec3f> normals);

}  // namespace wirerig
