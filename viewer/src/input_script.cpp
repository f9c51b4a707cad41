#include "wirerig/viewer/input_script.h"

#include <cctype>
#include <charconv>
#include <sstream>

#include "wirerig/io/input_file.h"

namespace wirerig {
namespace {

bool ParseFloat(const std::string& word, float* out) {
  const char* end = word.data() + word.size();
  auto [ptr, ec] = std::from_chars(word.data(), end, *out);
  return ec == std::errc() && ptr == end;
}

bool ParseButton(const std::string& word, MouseButton* out) {
  if (word == "left")
    *out = MouseButton::kLeft;
  else if (word == "right")
    *out = MouseButton::kRight;
  else if (word == "middle")
    *out = MouseButton::kMiddle;
  else
    return false;
  return true;
}

bool ParseKey(const std::string& word, int* out) {
  if (word.size() == 1 && std::isalnum(static_cast<unsigned char>(word[0]))) {
    *out = std::toupper(static_cast<unsigned char>(word[0]));
  } else if (word == "space") {
    *out = ' ';
  } else if (word == "tab") {
    *out = '\t';
  } else if (word == "escape") {
    *out = 27;
  } else {
    return false;
  }
  return true;
}

}  // namespace

Result<std::vector<InputEvent>> ParseInputScript(std::string_view text,
                                                 std::string_view source_name) {
  std::vector<InputEvent> events;
  std::istringstream in{std::string(text)};
  std::string line;
  int line_number = 0;
  auto fail = [&](const std::string& what) {
    std::string message(source_name);
    message.append(":").append(std::to_string(line_number)).append(": ").append(what);
    return Error{message};
  };
  while (std::getline(in, line)) {
    ++line_number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    if (w.empty()) continue;
    InputEvent e;
    float frame = 0.0f;
    if (!ParseFloat(w[0], &frame) || frame < 0.0f || frame != float(int(frame))) {
      return fail("the line must start with a frame number >= 0, not '" + w[0] + "'");
    }
    e.frame = int(frame);
    if (!events.empty() && e.frame < events.back().frame) {
      return fail("frame " + w[0] + " comes before the previous line's frame");
    }
    if (w.size() < 2) return fail("an event name must follow the frame number");
    const std::string& name = w[1];
    auto need = [&](std::size_t count) { return w.size() == count + 2; };
    if (name == "move" || name == "move-by") {
      e.type = name == "move" ? InputEventType::kMove : InputEventType::kMoveBy;
      if (!need(2) || !ParseFloat(w[2], &e.x) || !ParseFloat(w[3], &e.y)) {
        return fail(name + " takes two numbers: x y (fractions of the window)");
      }
    } else if (name == "move-to-wire") {
      e.type = InputEventType::kMoveToWire;
      float id = 0.0f;
      if (!need(2) || !ParseFloat(w[2], &id) || id < 0.0f || !ParseFloat(w[3], &e.x) ||
          e.x < 0.0f || e.x > 1.0f) {
        return fail("move-to-wire takes a wire id >= 0 and a parameter v in [0, 1]");
      }
      e.wire = unsigned(id);
    } else if (name == "move-to-gizmo") {
      e.type = InputEventType::kMoveToGizmo;
      const std::string axes = "xyz";
      if (!need(2) || w[2].size() != 1 || axes.find(w[2][0]) == std::string::npos ||
          !ParseFloat(w[3], &e.x) || e.x < 0.0f || e.x > 1.0f) {
        return fail("move-to-gizmo takes a ring axis (x, y or z) and a fraction t in [0, 1]");
      }
      e.axis = int(axes.find(w[2][0]));
    } else if (name == "press" || name == "release") {
      e.type = name == "press" ? InputEventType::kPress : InputEventType::kRelease;
      if (!need(1) || !ParseButton(w[2], &e.button)) {
        return fail(name + " takes a button: left, right or middle");
      }
    } else if (name == "scroll") {
      e.type = InputEventType::kScroll;
      if (!need(1) || !ParseFloat(w[2], &e.y)) return fail("scroll takes a number of steps");
    } else if (name == "key") {
      e.type = InputEventType::kKey;
      if (!need(1) || !ParseKey(w[2], &e.key)) {
        return fail("key takes a letter, a digit, space, tab or escape");
      }
    } else {
      return fail("unknown event '" + name +
                  "' (move, move-by, move-to-wire, move-to-gizmo, press, release, scroll, key)");
    }
    events.push_back(e);
  }
  return events;
}

Result<std::vector<InputEvent>> LoadInputScript(const std::filesystem::path& path) {
  Result<std::string> text = ReadInputFile(path, "input script");
  if (!text) return Error{text.error()};
  return ParseInputScript(text.value(), path.string());
}

}  // namespace wirerig
