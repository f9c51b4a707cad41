// SceneViewer: the viewer application on a scene (`wirerig view SCENE`). It plays the scene's
// clip on the timeline (keys shown), draws the deformed mesh with its profile wires (blue) and
// spine wires (pink) and the load arrows, and lets the user:
//  * drag a wire: a live point force at the grabbed place (spine: the cantilever stiffness
//    3 EI / a^3 that puts the grabbed point under the mouse; profile: 192 EI / L^3 of a clamped
//    loop), re-evaluated in closed form every frame;
//  * edit each part's spine material (E, nu) and tube section and its boundary condition, with
//    undo; save the edited scene; export the clip to .glb (morph mode);
//  * switch to another sample with a picker.
// OnShutdown prints one summary line for scripted runs:
//   "view: picks=N force=yes|no wire_moved=yes|no mesh_moved=yes|no ... frames=N"
// (wire_moved: the grabbed point of the wire moved over 1 cm while dragged).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "wirerig/anim/playback.h"
#include "wirerig/anim/scene.h"
#include "wirerig/viewer/application.h"
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
};

class SceneViewer : public Application {
 public:
  explicit SceneViewer(SceneViewerOptions options);
  ~SceneViewer() override;

 protected:
  bool OnInitialize() override;
  void OnDisplay(RenderFrame& frame) override;
  void OnGui() override;
  void OnShutdown() override;
  void OnWireGrab(const WirePick& pick) override;
  void OnWireDrag(const WirePick& grab, const Vec3f& target) override;
  void OnWireRelease() override;

 private:
  // Loads (or rebuilds after an edit) the scene and everything made from it; the error names
  // the file and field.
  Result<bool> Open(const SceneDescription& description);
  void DrawEditor();
  void DrawJointSliders(const PartModel& part);
  void Apply(SceneDescription edited);

  SceneViewerOptions options_;
  std::unique_ptr<BuiltScene> scene_;
  std::unique_ptr<Playback> playback_;
  std::unique_ptr<SceneFrame> picture_;
  Clip rest_clip_;  // played when the scene has no clips
  const Clip* clip_ = nullptr;
  std::vector<Vec3> positions_, normals_;
  std::vector<SceneDescription> undo_;
  std::string status_;  // the last message shown in the editor
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
  // The editor's fields for the selected part of the open scene, reloaded when either changes.
  struct EditorFields {
    int part = -1;
    const BuiltScene* scene = nullptr;
    float youngs = 0.0f, poisson = 0.0f, radius = 0.0f, wall = 0.0f;
  };
  EditorFields editor_;
};

}  // namespace wirerig
