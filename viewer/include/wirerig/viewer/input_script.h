// Input scripts: mouse and key events replayed at given frames, so the viewer can be driven
// without a person (CI runs it under xvfb-run, or with --no-window).
//
// One event per line, `#` starts a comment:
//   <frame> move <x> <y>           cursor to a fraction of the window (0..1 from the top-left)
//   <frame> move-by <dx> <dy>      cursor moved by fractions of the window
//   <frame> move-to-wire <id> <v>  cursor onto wire `id` (RenderPolyline::id) at parameter v
//   <frame> move-to-gizmo <x|y|z> <t>  cursor onto the joint gizmo's ring of that axis, at
//                                  fraction t in [0, 1] around it from its point nearest the
//                                  eye, in the direction of a positive turn (joint_gizmo.h)
//   <frame> press <left|right|middle>
//   <frame> release <left|right|middle>
//   <frame> scroll <dy>            wheel steps (positive zooms in)
//   <frame> key <name>             a key tap: a letter (F, W, ...), space, tab, escape
// Frames count from 0 and must not decrease from one line to the next.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "wirerig/io/result.h"

namespace wirerig {

enum class InputEventType : int {
  kMove = 0,
  kMoveBy = 1,
  kMoveToWire = 2,
  kPress = 3,
  kRelease = 4,
  kScroll = 5,
  kKey = 6,
  kMoveToGizmo = 7,
};

enum class MouseButton : int { kLeft = 0, kRight = 1, kMiddle = 2 };

struct InputEvent {
  int frame = 0;
  InputEventType type = InputEventType::kMove;
  float x = 0.0f;     // move, move-by: fractions; move-to-wire: v; move-to-gizmo: t; scroll: 0
  float y = 0.0f;     // move, move-by: fractions; scroll: steps
  unsigned wire = 0;  // move-to-wire
  int axis = 0;       // move-to-gizmo: 0 X, 1 Y, 2 Z (x holds t)
  MouseButton button = MouseButton::kLeft;  // press, release
  int key = 0;  // key: an upper-case letter or digit, ' ', '\t', 27 (escape)
};

// Parses a script; errors read "<source_name>:<line>: <what is wrong>".
Result<std::vector<InputEvent>> ParseInputScript(std::string_view text,
                                                 std::string_view source_name);
// Reads and parses a script file; the error names the file.
Result<std::vector<InputEvent>> LoadInputScript(const std::filesystem::path& path);

}  // namespace wirerig
