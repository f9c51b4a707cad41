// SceneViewer: the viewer application on a scene (`wirerig view SCENE`). It plays the scene's
// clip on the timeline (keys shown), draws the deformed mesh with its profile wires (blue) and
// spine wires (pink) and the load arrows, and lets the user:
//  * turn the selected part's joint: drag a ring of the rotation gizmo drawn on the joint
//    (joint_gizmo.h; X red, Y green, Z blue; a hinge has its X ring only), or use the joint
//    sliders; the skin follows through the joint's bridge;
//  * drag a wire: a live point force at the grabbed place (spine: the cantilever stiffness
//    3 EI / a^3 that puts the grabbed point under the mouse; profile: 192 EI / L^3 of a clamped
//    loop), re-evaluated in closed form every frame;
//  * edit each part's spine material (E, nu) and tube section and its boundary condition, with
//    undo; save the edited scene; export the clip to .glb (morph mode);
//  * switch to another sample with a picker.
// OnShutdown prints one summary line for scripted runs:
//   "view: picks=N force=yes|no wire_moved=yes|no mesh_moved=yes|no ... gizmo_drags=N
//    joint=PART:X,Y,Z frames=N"
// (wire_moved: the grabbed point of the wire moved over 1 cm while dragged; joint: the
// selected part's interactive joint angles in degrees).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "wirerig/anim/playback.h"
#include "wirerig/anim/scene.h"
#include "wirerig/viewer/application.h"
#include "wirerig/viewer/joint_gizmo.h"
#include "wirerig/viewer/scene_frame.h"

namespace wirerig {

struct SceneViewerSample {
  std::string name;
  std::filesystem::path scene;
};

struct SceneViewerOptions {
  std::filesystem::path scene;
  std::string clip;                        // empty: the scene's first clip
  std::vector<SceneViewerSample> samples;  // the picker's list (may be empty)
  // When set, every scene's mesh and motion files are imported in a child process
  // (isolated_process.h): a file that crashes Assimp cannot take the viewer down.
  std::optional<ImportIsolation> import_isolation;
};

class SceneViewer : public Application {
 public:
  explicit SceneViewer(SceneViewerOptions options);
  ~SceneViewer() override;

  // The open scene's playback (after Run has initialised it, until the viewer is destroyed).
  const Playback& playback() const { return *playback_; }
  int selected_part() const { return selected_part_; }

 protected:
  Result<bool> OnInitialize() override;
  std::string Failure() const override { return failure_; }
  void OnDisplay(RenderFrame& frame) override;
  void OnGui() override;
  void OnShutdown() override;
  void OnWireGrab(const WirePick& pick) override;
  void OnWireDrag(const WirePick& grab, const Vec3f& target) override;
  void OnWireRelease() override;
  bool OnHandlePress(const Vec2f& pixel) override;
  void OnHandleDrag(const Vec2f& pixel) override;
  void OnHandleRelease() override;
  bool GizmoPixel(int axis, float t, Vec2f* pixel) const override;

 private:
  // Builds the scene and everything made from it; the error names the file and field.
  Result<bool> Open(const SceneDescription& description);
  // An edit of the open scene (apply, undo): in place when it keeps the mesh and rig (EditScene:
  // nothing imported or rigged again; true), else built anew (false).
  Result<bool> OpenEdited(const SceneDescription& edited);
  // Shows a built scene: its playback and picture replace the current ones at once.
  Result<bool> Show(std::unique_ptr<BuiltScene> scene);
  // LoadScene, with the options' import isolation for its mesh and motion files.
  Result<SceneDescription> Load(const std::filesystem::path& scene) const;
  void DrawEditor();
  void DrawJointSliders(const PartModel& part);
  // The rotation gizmo of the selected part's joint, as the last evaluation posed it, seen by
  // the current camera (not visible: no joint that turns, or hidden).
  JointGizmo CurrentGizmo() const;
  void DrawGizmo();
  void Apply(SceneDescription edited);

  SceneViewerOptions options_;
  std::unique_ptr<BuiltScene> scene_;
  std::unique_ptr<Playback> playback_;
  std::unique_ptr<SceneFrame> picture_;
  Clip rest_clip_;  // played when the scene has no clips
  const Clip* clip_ = nullptr;
  std::vector<Vec3> positions_, normals_;
  std::vector<PartWarnings> part_warnings_;  // per part, at the displayed time
  bool deflection_warned_ = false;           // a deflection beyond a part's length was reported
  std::vector<SceneDescription> undo_;
  std::string status_;   // the last message shown in the editor
  std::string failure_;  // the first evaluation failure of the open scene (Failure())
  std::string caption_;
  // The drag in progress.
  bool dragging_ = false;
  InteractiveLoad drag_;
  double drag_stiffness_ = 0.0;  // N/m
  // For the summary line.
  int picks_ = 0;
  double peak_force_ = 0.0;
  double max_mesh_motion_ = 0.0;
  Vec3 grab_point_ = Vec3::Zero();  // where the grabbed wire was when grabbed
  double max_wire_motion_ = 0.0;    // how far the grabbed point moved while dragged
  int selected_part_ = 0;
  // The rotation gizmo: every part's joint as the last evaluation posed it, and the ring drag
  // in progress (on the gizmo as it stood when the drag began).
  bool show_gizmo_ = true;
  bool evaluated_ = false;  // posed_joints_ belong to the open scene's last evaluation
  std::vector<PosedJoint> posed_joints_;
  JointGizmo drag_gizmo_;
  JointGizmoDrag gizmo_drag_;
  std::uint32_t gizmo_part_ = 0;
  int gizmo_drags_ = 0;
  // The editor's fields for the selected part of the open scene, reloaded when either changes.
  struct EditorFields {
    int part = -1;
    const BuiltScene* scene = nullptr;
    float youngs = 0.0f, poisson = 0.0f, radius = 0.0f, wall = 0.0f;
  };
  EditorFields editor_;
};

}  // namespace wirerig
