#include "wirerig/viewer/scene_viewer.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "wirerig/anim/bake.h"
#include "wirerig/anim/gltf_export.h"

namespace wirerig {
namespace {

constexpr const char* kBoundaryNames[] = {"simply_supported", "clamped", "cantilever_free",
                                          "cantilever_guided"};

}  // namespace

Result<SceneDescription> SceneViewer::Load(const std::filesystem::path& scene) const {
  Result<SceneDescription> description = LoadScene(scene);
  if (description) description.value().mesh.import.isolation = options_.import_isolation;
  return description;
}

SceneViewer::SceneViewer(SceneViewerOptions options) : options_(std::move(options)) {}
SceneViewer::~SceneViewer() = default;

Result<bool> SceneViewer::Open(const SceneDescription& description) {
  Result<BuiltScene> built = BuildScene(description);
  if (!built) return Error{built.error()};
  return Show(std::make_unique<BuiltScene>(std::move(built).value()));
}

Result<bool> SceneViewer::OpenEdited(const SceneDescription& edited) {
  auto scene = std::make_unique<BuiltScene>(*scene_);
  Result<bool> in_place = EditScene(scene.get(), edited);
  if (!in_place) return in_place;
  if (Result<bool> shown = Show(std::move(scene)); !shown) return shown;
  return in_place;
}

Result<bool> SceneViewer::Show(std::unique_ptr<BuiltScene> scene) {
  const SceneDescription& description = scene->description;
  failure_.clear();
  deflection_warned_ = false;
  const Clip* clip = scene->FindClip(options_.clip);
  if (!clip && !options_.clip.empty() && !scene->clips.empty())
    return Error{scene->MissingClipMessage(options_.clip)};
  rest_clip_ = RestClip(scene->model);
  if (!clip) clip = &rest_clip_;
  Result<Playback> playback = Playback::Make(scene->model, *clip, description.playback);
  if (!playback) return Error{playback.error()};
  // Replace everything at once: the picture and playback refer to the scene.
  picture_.reset();
  playback_ = std::make_unique<Playback>(std::move(playback).value());
  scene_ = std::move(scene);
  clip_ = clip;
  picture_ = std::make_unique<SceneFrame>(*scene_);
  positions_.assign(scene_->model.vertices.size(), Vec3::Zero());
  normals_.assign(positions_.size(), Vec3::Zero());
  timeline().duration = clip_ == &rest_clip_ ? 0.0 : clip_->duration;
  timeline().keys = clip_->key_times;
  timeline().loop = clip_->loop != LoopMode::kOnce;
  timeline().Seek(timeline().time);
  timeline().playing = timeline().duration > 0.0;  // a scene's clip plays when it opens
  selected_part_ = std::min(selected_part_, int(scene_->model.parts.size()) - 1);
  dragging_ = false;
  evaluated_ = false;
  gizmo_drag_ = JointGizmoDrag{};
  return true;
}

Result<bool> SceneViewer::OnInitialize() {
  Result<SceneDescription> description = Load(options_.scene);
  if (!description) return Error{description.error()};  // it names the file
  if (Result<bool> opened = Open(description.value()); !opened)
    return Error{options_.scene.string() + ": " + opened.error()};
  camera() = picture_->InitialCamera(display_size());
  return true;
}

void SceneViewer::OnDisplay(RenderFrame& frame) {
  part_warnings_.resize(scene_->model.parts.size());
  if (Status s = playback_->Evaluate(timeline().time, positions_, normals_, part_warnings_); !s) {
    status_ = "evaluation: " + ToString(s);
    if (failure_.empty()) {  // the run fails with the first, as render and bake do
      failure_ = options_.scene.string() + ": t = " + std::to_string(timeline().time) +
                 " s: " + ToString(s);
    }
  } else {
    // Linear theory no longer holds: said once per scene, on stderr and in the status line.
    for (std::size_t p = 0; p < part_warnings_.size() && !deflection_warned_; ++p) {
      const std::string w =
          DeflectionWarning(scene_->model.parts[p], part_warnings_[p], timeline().time);
      if (w.empty()) continue;
      std::fprintf(stderr, "wirerig view: warning: %s: %s\n", options_.scene.string().c_str(),
                   w.c_str());
      status_ = "warning: " + w;
      deflection_warned_ = true;
    }
    const Vec3f followed = picture_->FollowOffset();
    picture_->Update(*playback_, positions_, normals_);
    camera().target += picture_->FollowOffset() - followed;  // the part the camera follows
    // Where each joint stands now, for the rotation gizmo.
    const RigModel& model = scene_->model;
    posed_joints_.resize(model.parts.size());
    for (std::size_t p = 0; p < model.parts.size(); ++p)
      posed_joints_[p] =
          PoseJoint(model, playback_->workspace(), p, playback_->sample().poses[p],
                    playback_->InteractiveJointAngles(static_cast<std::uint32_t>(p)));
    evaluated_ = true;
    if (dragging_) {
      // How far the grabbed point of the wire moved from where it was grabbed.
      const RigWorkspace& w = playback_->workspace();
      const std::vector<Vec3>& points =
          drag_.profile < 0 ? w.spine_points[drag_.part]
                            : w.profile_points[drag_.part][std::size_t(drag_.profile)];
      const auto k = static_cast<std::size_t>(
          std::lround(drag_.at * double(points.size() - (drag_.profile < 0 ? 1 : 0))));
      const Vec3& now = points[std::min(k, points.size() - 1)];
      max_wire_motion_ = std::max(max_wire_motion_, (now - grab_point_).norm());
    }
    for (std::size_t v = 0; v < positions_.size(); ++v)
      max_mesh_motion_ =
          std::max(max_mesh_motion_, (positions_[v] - scene_->mesh.welded_positions[v]).norm());
  }
  char text[128];
  std::snprintf(text, sizeof text, "%s  %s  t = %.2f s", scene_->description.name.c_str(),
                clip_->name.c_str(), timeline().time);
  caption_ = text;
  picture_->set_caption(caption_);
  frame = picture_->frame();
}

void SceneViewer::OnWireGrab(const WirePick& pick) {
  // Which wire: the SceneFrame numbers each part's profiles, then its spine.
  for (std::size_t p = 0; p < scene_->model.parts.size(); ++p) {
    const PartModel& part = scene_->model.parts[p];
    if (pick.id < picture_->ProfileId(p, 0) || pick.id > picture_->SpineId(p)) continue;
    drag_ = InteractiveLoad{};
    drag_.part = static_cast<std::uint32_t>(p);
    selected_part_ = int(p);  // the editor (and its joint sliders) follow the picked part
    drag_.at = std::clamp(double(pick.parameter), 0.0, 1.0);
    const bool spine = pick.id == picture_->SpineId(p);
    drag_.profile = spine ? -1 : int(pick.id - picture_->ProfileId(p, 0));
    if (spine) {
      // A cantilever's point at a = v L moves P a^3 / 3EI under a load P there.
      const double a = std::max(0.1, drag_.at) * part.spine_length;
      drag_stiffness_ = 3.0 * part.spine_stiffness.bending / (a * a * a);
    } else {
      const ProfileModel& profile = part.profiles[std::size_t(drag_.profile)];
      double length = 0.0;
      for (std::size_t k = 0; k + 1 < profile.local_points.size(); ++k)
        length += (profile.local_points[k + 1] - profile.local_points[k]).norm();
      // A clamped wire's centre moves P L^3 / 192 EI under a load P there.
      drag_stiffness_ = 192.0 * profile.stiffness.bending / (length * length * length);
    }
    dragging_ = true;
    grab_point_ = pick.point.cast<double>();
    ++picks_;
    std::printf("view: grabbed %s of part \"%s\" at v = %.3f\n",
                spine ? "the spine" : "a profile wire", part.name.c_str(), drag_.at);
    return;
  }
}

void SceneViewer::OnWireDrag(const WirePick& grab, const Vec3f& target) {
  if (!dragging_) return;
  drag_.force = drag_stiffness_ * (target - grab.point).cast<double>();
  peak_force_ = std::max(peak_force_, drag_.force.norm());
  if (Status s = playback_->SetInteractiveLoad(drag_); !s) status_ = ToString(s);
}

void SceneViewer::OnWireRelease() {
  dragging_ = false;
  (void)playback_->SetInteractiveLoad(std::nullopt);
}

JointGizmo SceneViewer::CurrentGizmo() const {
  if (!show_gizmo_ || !evaluated_ || selected_part_ < 0 ||
      std::size_t(selected_part_) >= posed_joints_.size())
    return JointGizmo{};
  const auto p = static_cast<std::uint32_t>(selected_part_);
  const PartModel& part = scene_->model.parts[p];
  if (part.parent < 0) return JointGizmo{};
  const PosedJoint& posed = posed_joints_[p];
  const Mat3 axes = JointGizmoAxes(part.joint, posed.frame, playback_->InteractiveJointAngles(p));
  return BuildJointGizmo(camera(), display_size(), posed.center, axes, part.joint.type);
}

bool SceneViewer::OnHandlePress(const Vec2f& pixel) {
  const JointGizmo gizmo = CurrentGizmo();
  const int ring = HitTestJointGizmo(gizmo, pixel);
  if (ring < 0) return false;
  gizmo_part_ = static_cast<std::uint32_t>(selected_part_);
  drag_gizmo_ = gizmo;
  gizmo_drag_ =
      BeginJointGizmoDrag(gizmo, ring, pixel, playback_->InteractiveJointAngles(gizmo_part_));
  ++gizmo_drags_;
  return true;
}

void SceneViewer::OnHandleDrag(const Vec2f& pixel) {
  if (gizmo_drag_.ring < 0 || gizmo_part_ >= scene_->model.parts.size()) return;
  const Vec3 angles = UpdateJointGizmoDrag(drag_gizmo_, scene_->model.parts[gizmo_part_].joint,
                                           pixel, &gizmo_drag_);
  const Status s = playback_->SetInteractiveJointAngles(gizmo_part_, angles);
  if (!s) status_ = ToString(s);
}

void SceneViewer::OnHandleRelease() { gizmo_drag_ = JointGizmoDrag{}; }

bool SceneViewer::GizmoPixel(int axis, float t, Vec2f* pixel) const {
  const JointGizmo gizmo = CurrentGizmo();
  for (const JointGizmoRing& ring : gizmo.rings) {
    if (ring.axis != axis || ring.pixels.empty()) continue;
    // Along the ring's polyline, between its points.
    const double x = double(std::clamp(t, 0.0f, 1.0f)) * double(ring.pixels.size());
    const auto i = static_cast<std::size_t>(std::floor(x)) % ring.pixels.size();
    const float f = float(x - std::floor(x));
    *pixel = (1.0f - f) * ring.pixels[i] + f * ring.pixels[(i + 1) % ring.pixels.size()];
    return true;
  }
  return false;
}

// The rotation gizmo on the background draw list (over the 3D view, under the panels): X red,
// Y green, Z blue, fading towards the side of each ring away from the eye, the hovered or
// dragged ring bright and thick; while dragging, a line from the joint to the cursor and the
// angle.
void SceneViewer::DrawGizmo() {
  const JointGizmo gizmo = CurrentGizmo();
  if (!gizmo.visible) return;
  const ImGuiIO& io = ImGui::GetIO();
  // Our pixels are the framebuffer's; ImGui draws in window coordinates.
  const ImVec2 scale(io.DisplayFramebufferScale.x > 0.0f ? io.DisplayFramebufferScale.x : 1.0f,
                     io.DisplayFramebufferScale.y > 0.0f ? io.DisplayFramebufferScale.y : 1.0f);
  auto to_imgui = [&](const Vec2f& p) { return ImVec2(p.x() / scale.x, p.y() / scale.y); };
  int hot = -1;  // axis
  if (gizmo_drag_.ring >= 0) {
    hot = gizmo_drag_.axis;
  } else if (!io.WantCaptureMouse) {
    const int ring = HitTestJointGizmo(gizmo, mouse());
    if (ring >= 0) hot = gizmo.rings[std::size_t(ring)].axis;
  }
  const int colours[3][3] = {{230, 60, 60}, {70, 200, 80}, {70, 120, 245}};
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  // Far sides first, then near sides, the hot ring last.
  for (int pass = 0; pass < 3; ++pass) {
    for (const JointGizmoRing& ring : gizmo.rings) {
      const bool is_hot = ring.axis == hot;
      if ((pass == 2) != is_hot) continue;
      const int* c = colours[ring.axis];
      const int lift = is_hot ? 70 : 0;
      const std::size_t n = ring.pixels.size();
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t j = (i + 1) % n;
        const float near = 0.5f * (ring.toward_eye[i] + ring.toward_eye[j]);
        if (pass < 2 && (near >= 0.0f) != (pass == 1)) continue;
        const int alpha = near >= 0.0f ? 255 : int(255.0f + 175.0f * std::max(near, -1.0f));
        const ImU32 colour = IM_COL32(std::min(c[0] + lift, 255), std::min(c[1] + lift, 255),
                                      std::min(c[2] + lift, 255), alpha);
        draw->AddLine(to_imgui(ring.pixels[i]), to_imgui(ring.pixels[j]), colour,
                      is_hot ? 4.0f : 2.0f);
      }
    }
  }
  const ImVec2 centre = to_imgui(gizmo.center_pixel);
  draw->AddCircleFilled(centre, 3.0f, IM_COL32(240, 240, 240, 220));
  if (gizmo_drag_.ring >= 0 && gizmo_part_ < scene_->model.parts.size()) {
    const ImVec2 cursor = to_imgui(mouse());
    draw->AddLine(centre, cursor, IM_COL32(240, 240, 240, 160), 1.0f);
    const Vec3 angles = playback_->InteractiveJointAngles(gizmo_part_);
    char text[48];
    std::snprintf(text, sizeof text, "%c %.1f deg", "xyz"[gizmo_drag_.axis],
                  angles[gizmo_drag_.axis]);
    draw->AddText(ImVec2(cursor.x + 14.0f, cursor.y - 6.0f), IM_COL32(255, 255, 255, 255), text);
  }
}

void SceneViewer::Apply(SceneDescription edited) {
  undo_.push_back(scene_->description);
  if (Result<bool> opened = OpenEdited(edited); !opened) {
    status_ = opened.error();
    undo_.pop_back();
    return;
  }
  status_ = "applied";
}

void SceneViewer::DrawEditor() {
  ImGui::SetNextWindowPos(ImVec2(float(display_size().width) - 330.0f, 10.0f), ImGuiCond_Once);
  ImGui::SetNextWindowSize(ImVec2(320.0f, 0.0f), ImGuiCond_Once);
  if (!ImGui::Begin("Scene")) {
    ImGui::End();
    return;
  }
  // Sample picker.
  if (!options_.samples.empty() && ImGui::BeginCombo("sample", scene_->description.name.c_str())) {
    for (const SceneViewerSample& sample : options_.samples) {
      if (ImGui::Selectable(sample.name.c_str())) {
        Result<SceneDescription> description = Load(sample.scene);
        Result<bool> opened =
            description ? Open(description.value()) : Result<bool>(Error{description.error()});
        if (opened) {
          options_.scene = sample.scene;
          undo_.clear();
          camera() = picture_->InitialCamera(display_size());
          status_ = "opened " + sample.name;
        } else {
          status_ = opened.error();
        }
      }
    }
    ImGui::EndCombo();
  }
  const RigModel& model = scene_->model;
  std::vector<const char*> names;
  for (const PartModel& part : model.parts) names.push_back(part.name.c_str());
  ImGui::Combo("part", &selected_part_, names.data(), int(names.size()));
  const PartModel& part = model.parts[std::size_t(selected_part_)];
  const RigPart& rig_part = scene_->rig.parts[std::size_t(selected_part_)];
  DrawJointSliders(part);
  ImGui::Text("spine: L = %.3f m, EI = %.3g N m^2, EA = %.3g N", part.spine_length,
              part.spine_stiffness.bending, part.spine_stiffness.axial);
  EditorFields& f = editor_;
  if (f.part != selected_part_ || f.scene != scene_.get()) {
    f.youngs = float(rig_part.spine_wire.material.youngs_modulus);
    f.poisson = float(rig_part.spine_wire.material.poisson_ratio);
    // A tube's area is 2 pi r h (mean radius r, wall h); the wall is the scene's skin thickness.
    f.wall = float(scene_->description.skin_thickness);
    f.radius = float(rig_part.spine_wire.section.area / (2.0 * 3.14159265358979 * double(f.wall)));
    f.part = selected_part_;
    f.scene = scene_.get();
  }
  float& youngs = f.youngs;
  float& poisson = f.poisson;
  float& radius = f.radius;
  float& wall = f.wall;
  ImGui::InputFloat("E (Pa)", &youngs, 0.0f, 0.0f, "%.4g");
  ImGui::SliderFloat("nu", &poisson, 0.0f, 0.49f);
  ImGui::InputFloat("tube r (m)", &radius, 0.0f, 0.0f, "%.4g");
  ImGui::InputFloat("tube h (m)", &wall, 0.0f, 0.0f, "%.4g");
  int boundary = 2;
  if (clip_ != &rest_clip_ && !clip_->parts[std::size_t(selected_part_)].boundary.empty())
    boundary = int(clip_->parts[std::size_t(selected_part_)].boundary.front().boundary);
  const bool boundary_changed = ImGui::Combo("boundary", &boundary, kBoundaryNames, 4);
  if (ImGui::Button("apply") || boundary_changed) {
    SceneDescription edited = scene_->description;
    PartSettings& settings = edited.parts[part.name];
    Material material = rig_part.spine_wire.material;
    material.youngs_modulus = double(youngs);
    material.poisson_ratio = double(poisson);
    settings.spine_material = material;
    if (ValidateTube(double(radius), double(wall)).ok())
      settings.spine_section = TubeSection(double(radius), double(wall));
    for (RawClip& clip : edited.clips) {
      if (clip.name != clip_->name) continue;
      auto it = std::find_if(clip.parts.begin(), clip.parts.end(),
                             [&](const RawPartTracks& t) { return t.part == part.name; });
      if (it == clip.parts.end()) {
        clip.parts.push_back({part.name, {}});
        it = clip.parts.end() - 1;
      }
      it->channels.boundary = {{0.0, static_cast<BoundaryCondition>(boundary)}};
    }
    Apply(std::move(edited));
  }
  ImGui::SameLine();
  if (ImGui::Button("undo") && !undo_.empty()) {
    SceneDescription previous = undo_.back();
    undo_.pop_back();
    Result<bool> opened = OpenEdited(previous);
    status_ = opened ? "undone" : opened.error();
  }
  ImGui::SameLine();
  if (ImGui::Button("save")) {
    const std::filesystem::path path =
        options_.scene.parent_path() /
        (options_.scene.stem().stem().string() + ".edited.scene.json");
    Result<std::filesystem::path> saved = SaveScene(scene_->description, path);
    status_ = saved ? "saved " + path.string() : saved.error();
  }
  ImGui::SameLine();
  if (ImGui::Button("export .glb") && clip_ != &rest_clip_) {
    const std::filesystem::path path =
        options_.scene.parent_path() / (scene_->description.name + ".glb");
    Result<BakedAnimation> bake =
        BakeClip(scene_->mesh, scene_->model, *clip_, scene_->description.playback, BakeOptions{});
    Result<GltfExportReport> exported =
        bake ? ExportGltf(scene_->mesh, bake.value(), GltfExportOptions{}, path)
             : Result<GltfExportReport>(Error{bake.error()});
    status_ = exported ? "exported " + path.string() : exported.error();
  }
  int coloring = int(picture_->coloring());
  const char* colorings[] = {"base colour", "bending moment", "axial strain"};
  if (ImGui::Combo("colour", &coloring, colorings, 3))
    picture_->set_coloring(static_cast<SceneColoring>(coloring));
  if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());
  ImGui::TextWrapped(
      "Drag a gizmo ring to turn the selected joint; drag a wire to push it (and select its "
      "part); drag elsewhere to orbit.");
  ImGui::End();
}

// The selected part's joint: one slider per angle its type allows (degrees, within its limits),
// turning the part live on top of the clip; the skin follows through the joint's bridge.
void SceneViewer::DrawJointSliders(const PartModel& part) {
  if (part.parent < 0 || part.joint.type == JointType::kFixed) return;
  const auto index = static_cast<std::uint32_t>(selected_part_);
  const Vec3 current = playback_->InteractiveJointAngles(index);
  float angles[3] = {float(current.x()), float(current.y()), float(current.z())};
  const char* labels[3] = {"joint x (deg)", "joint y (deg)", "twist z (deg)"};
  const int count = part.joint.type == JointType::kHinge ? 1 : 3;
  bool changed = false;
  for (int k = 0; k < count; ++k)
    changed |= ImGui::SliderFloat(labels[k], &angles[k], float(part.joint.min_degrees[k]),
                                  float(part.joint.max_degrees[k]), "%.0f");
  ImGui::Checkbox("rotation gizmo", &show_gizmo_);
  ImGui::SameLine();
  ImGui::TextDisabled("drag a ring to turn the joint");
  if (ImGui::Button("reset joint")) {
    angles[0] = angles[1] = angles[2] = 0.0f;
    changed = true;
  }
  if (changed) {
    const Status s = playback_->SetInteractiveJointAngles(
        index, Vec3(double(angles[0]), double(angles[1]), double(angles[2])));
    status_ = s ? std::string() : ToString(s);
  }
}

void SceneViewer::OnGui() {
  DrawGizmo();
  DrawEditor();
}

void SceneViewer::OnShutdown() {
  const auto selected = static_cast<std::uint32_t>(selected_part_);
  const Vec3 joint = playback_->InteractiveJointAngles(selected);
  std::printf(
      "view: picks=%d force=%s wire_moved=%s mesh_moved=%s max_wire_motion=%.4f m "
      "max_mesh_motion=%.4f m peak_force=%.3g N gizmo_drags=%d joint=%s:%.1f,%.1f,%.1f "
      "frames=%d\n",
      picks_, peak_force_ > 0.0 ? "yes" : "no", max_wire_motion_ > 1e-2 ? "yes" : "no",
      max_mesh_motion_ > 1e-3 ? "yes" : "no", max_wire_motion_, max_mesh_motion_, peak_force_,
      gizmo_drags_, scene_->model.parts[selected].name.c_str(), joint.x(), joint.y(), joint.z(),
      statistics().frame);
}

}  // namespace wirerig
