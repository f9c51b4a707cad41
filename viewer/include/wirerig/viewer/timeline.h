// Timeline: playback state of a clip in the viewer (play, pause, scrub, loop, speed, keys),
// advanced by the application's fixed step and drawn by DrawTimeline (ImGui).
#pragma once

#include <vector>

namespace wirerig {

struct Timeline {
  double time = 0.0;      // s, in [0, duration]
  double duration = 0.0;  // s; 0 hides the widget
  double speed = 1.0;     // playback rate; negative plays backwards
  bool playing = false;
  bool loop = true;          // wraps at the ends; otherwise stops there
  std::vector<double> keys;  // key times, s, shown as ticks

  // Moves time by dt * speed when playing: wraps when looping, otherwise clamps and pauses.
  void Advance(double dt);
  // Sets the time, clamped to [0, duration].
  void Seek(double t);
};

// Draws the timeline as an ImGui window along the bottom of the display: a play/pause button,
// loop and speed controls, and a scrub bar with a tick per key. Needs a current ImGui frame.
// Returns true when the user moved the time.
bool DrawTimeline(Timeline& timeline);

}  // namespace wirerig
