// Application: the viewer's small framework. A subclass fills hooks; Run() owns the window
// (GLFW, OpenGL 3.3 core, Dear ImGui) or, with --no-window, a headless EGL context, and runs
// the loop:
//
//   OnInitialize()                  once, with the GL context current; an error aborts (exit 1)
//   per displayed frame:
//     input (mouse, keys, or the replayed --input script)
//     OnUpdate(dt)                  zero or more times, at the fixed step dt (simulation time;
//                                   the timeline advances by the same steps while playing)
//     OnDisplay(frame)              fill a RenderFrame over the application's own buffers; they
//                                   must stay valid until the next OnDisplay (picking reads them)
//     render, then OnGui()          ImGui widgets (windowed mode only)
//   OnShutdown()                    once, context still current
//
// Mouse: a left press the application takes for a handle of its own (OnHandlePress, e.g. a
// gizmo) drags that handle (OnHandleDrag every move, OnHandleRelease); else left-drag on a
// pickable wire grabs it (OnWireGrab, OnWireDrag every move, OnWireRelease); left-drag
// elsewhere orbits; right- or middle-drag (or shift+left) pans;
// the wheel zooms. Keys: F frames the model, W/A/S/D/Q/E fly the orbit target, Z toggles the
// wireframe, space plays/pauses the timeline, escape quits.
//
// Command line (ParseApplicationOptions): --frames N (stop after N frames; frames then advance
// exactly one fixed step each, so runs are reproducible), --input SCRIPT (input_script.h),
// --screenshot PNG (the last frame), --size WxH, --no-window (headless EGL, no ImGui).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "wirerig/io/result.h"
#include "wirerig/viewer/camera.h"
#include "wirerig/viewer/input_script.h"
#include "wirerig/viewer/picking.h"
#include "wirerig/viewer/render_frame.h"
#include "wirerig/viewer/renderer.h"
#include "wirerig/viewer/timeline.h"

namespace wirerig {

struct ApplicationOptions {
  std::string title = "wirerig";
  Size size{1280, 720};
  int frames = 0;  // 0: until the window closes (or escape)
  std::filesystem::path input_script;
  std::filesystem::path screenshot;
  bool no_window = false;
  double fixed_step = 1.0 / 60.0;  // s
};

// Parses the options above from argv[1..] over `defaults`; an unknown argument or a bad value
// is an error naming it.
Result<ApplicationOptions> ParseApplicationOptions(int argc, const char* const* argv,
                                                   ApplicationOptions defaults = {});

// Timings and counts of the last frame, for the HUD and for tests.
struct FrameStatistics {
  int frame = 0;               // frames displayed so far
  double frame_ms = 0.0;       // wall time between frames, smoothed
  double evaluation_ms = 0.0;  // OnUpdate + OnDisplay of the last frame
  double render_ms = 0.0;      // Renderer::Render of the last frame (CPU side)
  RenderStats render;          // vertices, triangles, wires, arrows drawn
  int picks = 0;               // wire grabs so far
};

class Application {
 public:
  Application();
  virtual ~Application();
  Application(const Application&) = delete;
  Application& operator=(const Application&) = delete;

  // Runs with options parsed from the command line; prints errors to stderr. Returns the
  // process exit code: 0, or 1 after a clean error (bad arguments, unreadable script, no
  // display, OnInitialize refused).
  int Run(int argc, const char* const* argv);
  // Runs with explicit options; the error says what failed.
  Result<bool> Run(const ApplicationOptions& options);

 protected:
  // An error is printed once, after the program name (it should name the file at fault).
  virtual Result<bool> OnInitialize() { return true; }
  virtual void OnUpdate(double dt) { (void)dt; }
  virtual void OnDisplay(RenderFrame& frame) = 0;
  virtual void OnGui() {}
  virtual void OnShutdown() {}
  // A failure the run ends with (exit 1) after its frames, e.g. a scene whose evaluation
  // failed at some frame (drawn as the last good one); empty: none.
  virtual std::string Failure() const { return {}; }
  // A left press landed on a pickable wire.
  virtual void OnWireGrab(const WirePick& pick) { (void)pick; }
  // The grabbed wire is dragged: `target` is where the grabbed point should go (on the plane
  // through the grabbed point facing the camera).
  virtual void OnWireDrag(const WirePick& grab, const Vec3f& target) {
    (void)grab;
    (void)target;
  }
  virtual void OnWireRelease() {}
  // A left press (without shift) at `pixel`, asked before wire picking: return true to take
  // the drag for a handle of the application's own (a gizmo); then OnHandleDrag gets every
  // move and OnHandleRelease the release, and neither a wire grab nor an orbit starts.
  virtual bool OnHandlePress(const Vec2f& pixel) {
    (void)pixel;
    return false;
  }
  virtual void OnHandleDrag(const Vec2f& pixel) { (void)pixel; }
  virtual void OnHandleRelease() {}
  // Where an input script's `move-to-gizmo AXIS T` puts the cursor: the pixel at fraction T
  // around the ring of axis AXIS (0 X, 1 Y, 2 Z) of the application's gizmo. False: none.
  virtual bool GizmoPixel(int axis, float t, Vec2f* pixel) const {
    (void)axis;
    (void)t;
    (void)pixel;
    return false;
  }

  Camera& camera() { return camera_; }
  const Camera& camera() const { return camera_; }
  Timeline& timeline() { return timeline_; }
  RenderOptions& render_options() { return render_options_; }
  const FrameStatistics& statistics() const { return statistics_; }
  const ApplicationOptions& options() const { return options_; }
  // The current display size in pixels.
  Size display_size() const { return size_; }
  // The cursor in pixels of the display (top-left origin).
  Vec2f mouse() const { return mouse_; }
  // Frames the camera on the bounds of the last displayed frame.
  void FrameModel();

 private:
  struct Platform;
  friend struct Platform;

  void HandleEvent(const InputEvent& event);
  void MouseMove(const Vec2f& pixel);
  void MouseButtonEvent(MouseButton button, bool pressed, bool shift);
  void Scroll(float steps);
  void Key(int key);
  void Fly(double dt);
  void DrawHud();

  ApplicationOptions options_;
  Camera camera_;
  Timeline timeline_;
  RenderOptions render_options_;
  FrameStatistics statistics_;
  Size size_;
  RenderFrame frame_;
  std::unique_ptr<Renderer> renderer_;

  Vec2f mouse_ = Vec2f::Zero();
  bool buttons_[3] = {false, false, false};
  bool panning_ = false;
  bool orbiting_ = false;
  bool grabbing_ = false;
  bool handling_ = false;  // a handle (OnHandlePress) is being dragged
  WirePick grab_;
  bool keys_held_[6] = {};  // W A S D Q E
  bool quit_ = false;
  bool camera_framed_ = false;
};

}  // namespace wirerig
