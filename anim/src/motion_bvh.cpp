// BVH motion capture: parsing (line-aware, every error naming its line) and forward kinematics.
#include <algorithm>
#include <cfenv>
#include <charconv>
#include <cmath>
#include <numbers>
#include <unordered_set>

#include "wirerig/anim/motion_capture.h"
#include "wirerig/io/floating_point_hold.h"
#include "wirerig/io/input_file.h"

namespace wirerig {
namespace {

constexpr double kMaxValue = 1e9;                // larger values are refused as absurd
constexpr std::size_t kMaxValues = 100'000'000;  // frames x channels
constexpr std::size_t kMaxJoints = 10'000;

struct Token {
  std::string_view text;
  int line = 0;
};

// Whitespace-separated tokens with their line numbers.
class Tokens {
 public:
  explicit Tokens(std::string_view text) : text_(text) {}

  std::optional<Token> Next() {
    SkipSpace();
    if (pos_ >= text_.size()) return std::nullopt;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !IsSpace(text_[pos_])) ++pos_;
    return Token{text_.substr(start, pos_ - start), line_};
  }
  std::optional<Token> Peek() {
    const std::size_t pos = pos_;
    const int line = line_;
    std::optional<Token> token = Next();
    pos_ = pos;
    line_ = line;
    return token;
  }
  // The rest of the text from the next line on, and that line's number.
  std::string_view RestAfterLine(int* line) {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    if (pos_ < text_.size()) {
      ++pos_;
      ++line_;
    }
    *line = line_;
    return text_.substr(pos_);
  }
  int line() const { return line_; }

 private:
  static bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  void SkipSpace() {
    while (pos_ < text_.size() && IsSpace(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

// Thrown inside the parser, caught at its boundary.
struct ParseError {
  int line = 0;
  std::string message;
};

[[noreturn]] void Fail(int line, std::string message) {
  throw ParseError{line, std::move(message)};
}

std::string Quoted(std::string_view s) {
  std::string out(1, '"');
  out.append(s).push_back('"');
  return out;
}

// A number (a leading '+' allowed); nullopt when the token is not one.
std::optional<double> ParseNumber(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error == std::errc::result_out_of_range && end == text.data() + text.size())
    return std::numeric_limits<double>::infinity();
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

double ReadValue(const Token& token, const std::string& what) {
  const std::optional<double> value = ParseNumber(token.text);
  if (!value) Fail(token.line, what + ": " + Quoted(token.text) + " is not a number");
  if (!std::isfinite(*value)) Fail(token.line, what + ": " + Quoted(token.text) + " is not finite");
  if (std::abs(*value) > kMaxValue)
    Fail(token.line, what + ": " + Quoted(token.text) + " is beyond +-1e9 (absurd)");
  return *value;
}

Token Expect(Tokens& tokens, int last_line, const std::string& what) {
  std::optional<Token> token = tokens.Next();
  if (!token) Fail(last_line, "the file ends where " + what + " should follow");
  return *token;
}

void ExpectWord(Tokens& tokens, int last_line, std::string_view word, const std::string& where) {
  const Token token = Expect(tokens, last_line, Quoted(word));
  if (token.text != word)
    Fail(token.line, "expected " + Quoted(word) + " " + where + ", found " + Quoted(token.text));
}

std::optional<BvhChannel> ParseChannel(std::string_view name) {
  static constexpr std::pair<std::string_view, BvhChannel> kNames[] = {
      {"Xposition", BvhChannel::kXPosition}, {"Yposition", BvhChannel::kYPosition},
      {"Zposition", BvhChannel::kZPosition}, {"Xrotation", BvhChannel::kXRotation},
      {"Yrotation", BvhChannel::kYRotation}, {"Zrotation", BvhChannel::kZRotation}};
  for (const auto& [text, channel] : kNames)
    if (text == name) return channel;
  return std::nullopt;
}

class Parser {
 public:
  explicit Parser(std::string_view text) : tokens_(text) {}

  MotionCapture Parse() {
    ExpectWord(tokens_, 1, "HIERARCHY", "at the start of the file");
    const Token root = Expect(tokens_, tokens_.line(), "ROOT");
    if (root.text != "ROOT")
      Fail(root.line, "expected \"ROOT\" after HIERARCHY, found " + Quoted(root.text));
    ReadJoint(root, -1);
    std::optional<Token> next = tokens_.Next();
    if (!next) Fail(tokens_.line(), "the file ends where \"MOTION\" should follow the hierarchy");
    if (next->text == "ROOT")
      Fail(next->line, "a second ROOT: only one skeleton per file is supported");
    if (next->text != "MOTION")
      Fail(next->line, "expected \"MOTION\" after the hierarchy, found " + Quoted(next->text));
    ReadMotion(next->line);
    return std::move(motion_);
  }

 private:
  // ROOT/JOINT name { OFFSET x y z CHANNELS n ... (JOINT ... | End Site { OFFSET ... })* }
  void ReadJoint(const Token& keyword, int parent) {
    if (motion_.joints.size() >= kMaxJoints) Fail(keyword.line, "more than 10000 joints");
    const Token name = Expect(tokens_, keyword.line, "the joint's name");
    if (name.text == "{") Fail(name.line, Quoted(keyword.text) + " needs a name");
    if (!names_.insert(std::string(name.text)).second)
      Fail(name.line, "a second joint named " + Quoted(name.text));
    const int index = static_cast<int>(motion_.joints.size());
    {
      BvhJoint joint;
      joint.name = std::string(name.text);
      joint.parent = parent;
      joint.line = keyword.line;
      motion_.joints.push_back(std::move(joint));
    }
    const std::string where = "in joint " + Quoted(name.text);
    ExpectWord(tokens_, name.line, "{", "after the joint's name");
    ExpectWord(tokens_, name.line, "OFFSET", where);
    motion_.joints[index].offset = ReadVector(where + "'s OFFSET");
    ExpectWord(tokens_, tokens_.line(), "CHANNELS", where);
    const Token count_token = Expect(tokens_, tokens_.line(), "the channel count");
    const std::optional<double> count = ParseNumber(count_token.text);
    if (!count || *count < 0 || *count > 6 || *count != std::floor(*count))
      Fail(count_token.line, "CHANNELS " + where + ": the count must be a whole number 0..6, not " +
                                 Quoted(count_token.text));
    std::vector<BvhChannel>& channels = motion_.joints[index].channels;
    for (int c = 0; c < static_cast<int>(*count); ++c) {
      const Token channel = Expect(tokens_, count_token.line, "a channel name");
      const std::optional<BvhChannel> parsed = ParseChannel(channel.text);
      if (!parsed) {
        if (channel.text == "JOINT" || channel.text == "End" || channel.text == "}")
          Fail(channel.line, "CHANNELS " + where + " says " + Quoted(count_token.text) +
                                 " but names only " + std::to_string(c));
        Fail(channel.line, "CHANNELS " + where + ": unknown channel " + Quoted(channel.text) +
                               " (Xposition, Yposition, Zposition, Xrotation, Yrotation, "
                               "Zrotation)");
      }
      for (BvhChannel earlier : channels)
        if (earlier == *parsed)
          Fail(channel.line, "CHANNELS " + where + " lists " + Quoted(channel.text) + " twice");
      channels.push_back(*parsed);
    }
    motion_.joints[index].first_channel = motion_.channel_count;
    motion_.channel_count += channels.size();
    for (;;) {
      const Token token =
          Expect(tokens_, tokens_.line(), "\"}\" closing joint " + Quoted(name.text));
      if (token.text == "}") return;
      if (token.text == "JOINT") {
        ReadJoint(token, index);
      } else if (token.text == "End") {
        ExpectWord(tokens_, token.line, "Site", "after \"End\"");
        if (motion_.joints[index].end_site)
          Fail(token.line, "joint " + Quoted(name.text) + " has a second End Site");
        ExpectWord(tokens_, token.line, "{", "after \"End Site\"");
        ExpectWord(tokens_, token.line, "OFFSET", "in the End Site of " + Quoted(name.text));
        motion_.joints[index].end_site = ReadVector("the End Site OFFSET of " + Quoted(name.text));
        ExpectWord(tokens_, tokens_.line(), "}", "closing the End Site of " + Quoted(name.text));
      } else if (token.text == "ROOT") {
        Fail(token.line, "a second ROOT inside joint " + Quoted(name.text));
      } else if (token.text == "MOTION") {
        Fail(token.line, "\"MOTION\" before joint " + Quoted(name.text) + " is closed with \"}\"");
      } else {
        Fail(token.line, "unexpected " + Quoted(token.text) + " " + where +
                             " (expected JOINT, End Site or \"}\")");
      }
    }
  }

  Vec3 ReadVector(const std::string& what) {
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
      const Token token = Expect(tokens_, tokens_.line(), what + " (three numbers)");
      v[i] = ReadValue(token, what);
    }
    return v;
  }

  void ReadMotion(int motion_line) {
    const Token frames_word = Expect(tokens_, motion_line, "\"Frames:\"");
    if (frames_word.text != "Frames:")
      Fail(frames_word.line,
           "expected \"Frames:\" after MOTION, found " + Quoted(frames_word.text));
    const Token frames = Expect(tokens_, frames_word.line, "the frame count");
    const std::optional<double> count = ParseNumber(frames.text);
    if (!count || !(*count >= 1.0) || *count != std::floor(*count) || *count > double(kMaxValues))
      Fail(frames.line, "Frames: must be a whole number of at least 1, not " + Quoted(frames.text));
    motion_.frame_count = static_cast<std::size_t>(*count);
    ExpectWord(tokens_, frames.line, "Frame", "after the frame count");
    ExpectWord(tokens_, frames.line, "Time:", "after \"Frame\"");
    const Token time = Expect(tokens_, frames.line, "the frame time");
    const std::optional<double> dt = ParseNumber(time.text);
    // At most 10,000 frames a second (a clip's rate, clip_asset.h): a shorter frame time
    // (1e-300) made the whole capture last less than a key and bake as one pose.
    if (!dt || !std::isfinite(*dt) || !(*dt >= 1e-4) || *dt > 1e6)
      Fail(time.line,
           "Frame Time: must be a number of seconds in [1e-4, 1e6], not " + Quoted(time.text));
    motion_.frame_time = *dt;
    if (motion_.channel_count == 0) Fail(time.line, "the hierarchy has no channels to animate");
    if (motion_.frame_count > kMaxValues / motion_.channel_count)
      Fail(frames.line, "Frames: " + std::string(frames.text) + " x " +
                            std::to_string(motion_.channel_count) +
                            " channels is more than 10^8 values");
    // One frame per non-empty line from the line after "Frame Time:" on (a value takes two
    // characters at least: a header claiming more frames than the text holds reserves no more).
    int line = 0;
    std::string_view rest = tokens_.RestAfterLine(&line);
    motion_.values.reserve(
        std::min(motion_.frame_count * motion_.channel_count, rest.size() / 2 + 1));
    std::size_t frame = 0;
    while (!rest.empty()) {
      const std::size_t end = rest.find('\n');
      const std::string_view text = rest.substr(0, end);
      rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
      Tokens values(text);
      if (values.Peek() && frame >= motion_.frame_count)
        Fail(line,
             "more frame lines than \"Frames: " + std::to_string(motion_.frame_count) + "\" says");
      std::size_t n = 0;
      for (std::optional<Token> token = values.Next(); token; token = values.Next(), ++n) {
        if (n >= motion_.channel_count) continue;  // counted, refused below
        motion_.values.push_back(ReadValue(Token{token->text, line},
                                           "frame " + std::to_string(frame) + ", value " +
                                               std::to_string(n) + " (" + ChannelName(n) + ")"));
      }
      if (n > 0) {
        if (n != motion_.channel_count)
          Fail(line, "frame " + std::to_string(frame) + " has " + std::to_string(n) +
                         " values; the hierarchy's " + std::to_string(motion_.joints.size()) +
                         " joints have " + std::to_string(motion_.channel_count) + " channels");
        ++frame;
      }
      ++line;
    }
    if (frame != motion_.frame_count)
      Fail(line - 1, "\"Frames: " + std::to_string(motion_.frame_count) + "\" but the file holds " +
                         std::to_string(frame) + " frame lines");
  }

  // "LeftArm Zrotation" for the n-th value of a frame.
  std::string ChannelName(std::size_t n) const {
    for (const BvhJoint& joint : motion_.joints)
      if (n >= joint.first_channel && n < joint.first_channel + joint.channels.size())
        return joint.name + " " + std::string(ToString(joint.channels[n - joint.first_channel]));
    return "?";
  }

  Tokens tokens_;
  MotionCapture motion_;
  std::unordered_set<std::string> names_;
};

Mat3 AxisRotation(BvhChannel channel, double degrees) {
  const double a = degrees * (std::numbers::pi / 180.0);
  const Vec3 axis = channel == BvhChannel::kXRotation   ? Vec3::UnitX()
                    : channel == BvhChannel::kYRotation ? Vec3::UnitY()
                                                        : Vec3::UnitZ();
  return Eigen::AngleAxisd(a, axis).toRotationMatrix();
}

}  // namespace

std::string_view ToString(BvhChannel channel) {
  switch (channel) {
    case BvhChannel::kXPosition:
      return "Xposition";
    case BvhChannel::kYPosition:
      return "Yposition";
    case BvhChannel::kZPosition:
      return "Zposition";
    case BvhChannel::kXRotation:
      return "Xrotation";
    case BvhChannel::kYRotation:
      return "Yrotation";
    case BvhChannel::kZRotation:
      return "Zrotation";
  }
  return "?";
}

int MotionCapture::FindJoint(std::string_view name) const {
  for (std::size_t j = 0; j < joints.size(); ++j)
    if (joints[j].name == name) return static_cast<int>(j);
  return -1;
}

void PoseBvhFrame(const MotionCapture& motion, std::size_t frame, std::vector<BvhPose>& out) {
  out.resize(motion.joints.size());
  const std::span<const double> values = motion.Frame(frame);
  for (std::size_t j = 0; j < motion.joints.size(); ++j) {
    const BvhJoint& joint = motion.joints[j];
    Vec3 translation = joint.offset;
    Mat3 rotation = Mat3::Identity();
    for (std::size_t c = 0; c < joint.channels.size(); ++c) {
      const double value = values[joint.first_channel + c];
      const BvhChannel channel = joint.channels[c];
      if (channel <= BvhChannel::kZPosition) {
        translation[static_cast<int>(channel)] = value;
      } else {
        rotation = rotation * AxisRotation(channel, value);
      }
    }
    if (joint.parent < 0) {
      out[j] = {rotation, translation};
    } else {
      const BvhPose& parent = out[std::size_t(joint.parent)];
      out[j] = {parent.rotation * rotation, parent.position + parent.rotation * translation};
    }
  }
}

std::vector<Vec3> BvhRestPositions(const MotionCapture& motion) {
  std::vector<Vec3> out(motion.joints.size());
  for (std::size_t j = 0; j < motion.joints.size(); ++j) {
    const BvhJoint& joint = motion.joints[j];
    out[j] = joint.parent < 0 ? joint.offset : out[std::size_t(joint.parent)] + joint.offset;
  }
  return out;
}

Result<MotionCapture> ParseBvh(std::string_view text, const std::string& source) {
  const ScopedFloatingPointHold hold;
  try {
    // Lines may end in LF, CRLF or a lone CR (classic Mac OS exporters): the parser counts LFs.
    std::string unified;
    if (text.find('\r') != std::string_view::npos) {
      unified.reserve(text.size());
      for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '\r')
          unified.push_back(text[i]);
        else if (i + 1 == text.size() || text[i + 1] != '\n')
          unified.push_back('\n');
      }
      text = unified;
    }
    Parser parser(text);
    MotionCapture motion = parser.Parse();
    motion.source = source;
    return motion;
  } catch (const ParseError& e) {
    return Error{source + ": line " + std::to_string(e.line) + ": " + e.message};
  } catch (const std::bad_alloc&) {
    return Error{source + ": out of memory"};
  }
}

Result<MotionCapture> LoadBvh(const std::filesystem::path& path) {
  Result<std::string> text = ReadInputFile(path, "motion file (BVH)");
  if (!text) return Error{text.error()};
  return ParseBvh(text.value(), path.string());
}

}  // namespace wirerig
