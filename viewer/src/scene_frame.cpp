#include "wirerig/viewer/scene_frame.h"

#include <algorithm>
#include <cmath>

namespace wirerig {
namespace {

Vec3f ToFloat(const Vec3& v) { return v.cast<float>(); }

// |kappa| at sample k of a polyline: the turn between the chords around it over their mean
// length (0 at the ends).
double TurnRate(const std::vector<Vec3>& points, std::size_t k) {
  if (k == 0 || k + 1 >= points.size()) return 0.0;
  const Vec3 d0 = points[k] - points[k - 1], d1 = points[k + 1] - points[k];
  const double l0 = d0.norm(), l1 = d1.norm();
  if (!(l0 > 0.0 && l1 > 0.0)) return 0.0;
  return std::atan2(d0.cross(d1).norm(), d0.dot(d1)) / (0.5 * (l0 + l1));
}

// The deformed spine point and frame nearest v.
std::size_t NearestSample(std::size_t samples, double v) {
  return static_cast<std::size_t>(std::lround(std::clamp(v, 0.0, 1.0) * double(samples - 1)));
}

}  // namespace

SceneFrame::SceneFrame(const BuiltScene& scene) : scene_(&scene) {
  const RigModel& model = scene.model;
  positions_.resize(model.vertices.size());
  normals_.resize(model.vertices.size());
  for (std::size_t v = 0; v < positions_.size(); ++v) {
    positions_[v] = ToFloat(scene.mesh.welded_positions[v]);
    normals_[v] = Vec3f::UnitY();
  }
  ComputeVertexNormals(positions_, model.triangles, normals_);
  if (scene.description.camera)
    for (std::size_t p = 0; p < model.parts.size(); ++p)
      if (model.parts[p].name == scene.description.camera->follow) follow_part_ = int(p);
  std::size_t loads = 0;
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const PartModel& part = model.parts[p];
    first_profile_id_.push_back(polylines_.size());
    for (const ProfileModel& profile : part.profiles) {
      wire_points_.emplace_back(profile.local_points.size(), Vec3f::Zero());
      RenderPolyline line;
      line.kind = WireKind::kProfile;
      line.closed = profile.closed;
      line.width = 2.0f;
      line.id = static_cast<std::uint32_t>(polylines_.size());
      polylines_.push_back(line);
    }
    wire_points_.emplace_back(part.spine_points.size());
    for (std::size_t k = 0; k < part.spine_points.size(); ++k)
      wire_points_.back()[k] = ToFloat(part.spine_points[k]);
    RenderPolyline spine;
    spine.kind = WireKind::kSpine;
    spine.width = 3.5f;
    spine.id = static_cast<std::uint32_t>(polylines_.size());
    polylines_.push_back(spine);
  }
  for (const Clip& clip : scene.clips) {
    std::size_t clip_loads = 0;
    for (const PartChannels<Track>& part : clip.parts) clip_loads += part.point_loads.size();
    loads = std::max(loads, clip_loads);
  }
  arrows_.resize(loads);
  // Each vertex reads its part's spine at the profile it is bound to (the nearer end for caps).
  scalars_.assign(positions_.size(), 0.0f);
  for (const PartModel& part : model.parts) sample_values_.emplace_back(part.spine_points.size());
  vertex_sample_.resize(positions_.size());
  for (std::size_t v = 0; v < positions_.size(); ++v) {
    const VertexAttachment& a = model.vertices[v];
    const PartModel& part = model.parts[a.part];
    double spine_v = part.profiles[a.profile].spine_v;
    if (!a.cap && a.profile + 1 < part.profiles.size())
      spine_v = 0.5 * (spine_v + part.profiles[a.profile + 1].spine_v);
    const auto last = static_cast<double>(part.spine_points.size() - 1);
    vertex_sample_[v] = {a.part, static_cast<std::uint32_t>(std::lround(spine_v * last))};
  }
  // The buffers never grow again: the spans stay valid for the frame's life.
  for (std::size_t i = 0; i < polylines_.size(); ++i) polylines_[i].points = wire_points_[i];
  mesh_.positions = positions_;
  mesh_.normals = normals_;
  mesh_.triangles = model.triangles;
  mesh_.base_color = Vec3f(0.80f, 0.36f, 0.22f);
}

std::uint32_t SceneFrame::ProfileId(std::size_t part, std::size_t profile) const {
  return static_cast<std::uint32_t>(first_profile_id_[part] + profile);
}

std::uint32_t SceneFrame::SpineId(std::size_t part) const {
  return static_cast<std::uint32_t>(first_profile_id_[part] +
                                    scene_->model.parts[part].profiles.size());
}

void SceneFrame::Update(const Playback& playback, std::span<const Vec3> positions,
                        std::span<const Vec3> normals) {
  for (std::size_t v = 0; v < positions_.size() && v < positions.size(); ++v) {
    positions_[v] = ToFloat(positions[v]);
    if (v < normals.size()) normals_[v] = ToFloat(normals[v]);
  }
  if (normals.size() != positions_.size())
    ComputeVertexNormals(positions_, scene_->model.triangles, normals_);
  const RigWorkspace& w = playback.workspace();
  const RigModel& model = scene_->model;
  if (follow_part_ >= 0) {
    const auto p = std::size_t(follow_part_);
    follow_offset_ = ToFloat(Vec3(w.spine_points[p].front() - model.parts[p].spine_points.front()));
  }
  UpdateColors(w);
  arrow_count_ = 0;
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    for (std::size_t k = 0; k < model.parts[p].profiles.size(); ++k) {
      std::vector<Vec3f>& points = wire_points_[ProfileId(p, k)];
      const std::vector<Vec3>& deformed = w.profile_points[p][k];
      for (std::size_t i = 0; i < points.size(); ++i) points[i] = ToFloat(deformed[i]);
    }
    std::vector<Vec3f>& spine = wire_points_[SpineId(p)];
    for (std::size_t i = 0; i < spine.size(); ++i) spine[i] = ToFloat(w.spine_points[p][i]);
    // Spine point loads as arrows at their deformed place, in world axes.
    for (const PointLoad& load : playback.sample().poses[p].loads.bending_point_loads) {
      if (arrow_count_ >= arrows_.size()) break;
      const std::size_t s = NearestSample(spine.size(), load.at);
      const Frame& f = w.spine_frames[p][s];
      const Vec3 world = load.force.x() * f.normal + load.force.y() * f.binormal;
      arrows_[arrow_count_++] = {spine[s], ToFloat(world), Vec3f(0.90f, 0.10f, 0.02f)};
    }
  }
}

RenderFrame SceneFrame::frame() const {
  RenderFrame frame;
  frame.legend = legend_;
  frame.meshes = std::span<const RenderMesh>(&mesh_, 1);
  frame.polylines = polylines_;
  frame.arrows = std::span<const RenderArrow>(arrows_.data(), arrow_count_);
  frame.caption = caption_;
  const std::optional<CameraHint>& hint = scene_->description.camera;
  if (hint && hint->ground) {
    frame.ground_at_lowest_point = false;
    frame.ground_height = static_cast<float>(*hint->ground);
  }
  return frame;
}

Camera SceneFrame::InitialCamera(Size size) const {
  Camera camera;
  const std::optional<CameraHint>& hint = scene_->description.camera;
  if (hint) {
    camera.yaw = static_cast<float>(hint->yaw);
    camera.pitch = static_cast<float>(hint->pitch);
    camera.fov_y = static_cast<float>(hint->fov);
  }
  if (hint && hint->distance > 0.0) {
    camera.target = ToFloat(hint->target) + follow_offset_;
    camera.distance = static_cast<float>(hint->distance);
    return camera;
  }
  FrameCamera(camera, ComputeFrameBounds(frame()), size.Aspect());
  return camera;
}

void SceneFrame::UpdateColors(const RigWorkspace& w) {
  const RigModel& model = scene_->model;
  if (coloring_ == SceneColoring::kBaseColor) {
    mesh_.scalars = {};
    return;
  }
  float largest = 0.0f;
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const PartModel& part = model.parts[p];
    std::vector<float>& values = sample_values_[p];
    const std::vector<Vec3>& points = w.spine_points[p];
    const std::size_t n = points.size();
    for (std::size_t k = 0; k < n; ++k) {
      double value = 0.0;
      if (coloring_ == SceneColoring::kAxialStrain) {
        value = w.strain[p][k];
      } else {
        // The load's moment: EI times the change of the spine's curvature from rest.
        value = part.spine_stiffness.bending *
                std::abs(TurnRate(points, k) - TurnRate(part.spine_points, k));
      }
      values[k] = static_cast<float>(value);
      largest = std::max(largest, std::abs(values[k]));
    }
  }
  for (std::size_t v = 0; v < scalars_.size(); ++v)
    scalars_[v] = sample_values_[vertex_sample_[v].first][vertex_sample_[v].second];
  mesh_.scalars = scalars_;
  const float range = largest > 0.0f ? largest : 1.0f;
  if (coloring_ == SceneColoring::kBendingMoment) {
    legend_ = {0.0f, range, ColorMap::kViridis, "bending moment |M| (N m)", true};
  } else {
    legend_ = {-range, range, ColorMap::kCoolWarm, "axial strain N / EA", true};
  }
}

}  // namespace wirerig
