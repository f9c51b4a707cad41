// Motion capture in BVH (Biovision Hierarchy) files: a joint hierarchy with rest offsets and
// channels, then one line of channel values per frame (docs/motion-import.md).
//
// Read by wirerig's own parser rather than Assimp's BVH importer: Assimp reads the motion as
// one stream of numbers, so a frame line with a value missing or extra shifts every later frame
// instead of being refused, and its errors name neither the line nor the joint. Here every frame
// line must hold exactly the hierarchy's channel count, the frame count must match "Frames:",
// values must be finite, and every error reads "<file>: line N: <what is wrong>".
//
// Conventions (those of the BVH files in use, e.g. the CMU conversions):
//   * a joint's rotation channels, in the order listed, compose intrinsically: CHANNELS 3
//     Zrotation Yrotation Xrotation gives R = Rz(z) Ry(y) Rx(x); degrees in the file;
//   * a joint's position channels (usually the root's) replace the matching components of its
//     OFFSET: they are the joint's translation in its parent's frame (the root's: in the world);
//   * world: rotation W_j = W_parent R_j, position p_j = p_parent + W_parent t_j;
//   * at rest (every channel zero, positions at their OFFSETs) every joint's frame is the
//     world's: bones point along their children's OFFSETs.
// Units and axes are the file's (its up axis and unit are stated by a mapping file,
// motion_mapping.h); frame f is at time f x frame_time.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "wirerig/io/result.h"
#include "wirerig/runtime/conventions.h"

namespace wirerig {

enum class BvhChannel : int {
  kXPosition = 0,
  kYPosition = 1,
  kZPosition = 2,
  kXRotation = 3,
  kYRotation = 4,
  kZRotation = 5,
};
// Names used in files: "Xposition", ..., "Zrotation".
std::string_view ToString(BvhChannel channel);

struct BvhJoint {
  std::string name;
  int parent = -1;                   // parents come first; -1 for the root
  Vec3 offset = Vec3::Zero();        // from the parent's joint, file units
  std::vector<BvhChannel> channels;  // in the file's order
  std::size_t first_channel = 0;     // where its values start in a frame
  std::optional<Vec3> end_site;      // the End Site's offset from this joint, if it has one
  int line = 0;                      // line of its ROOT or JOINT keyword (1-based)
};

struct MotionCapture {
  std::string source;  // the file, for messages
  std::vector<BvhJoint> joints;
  std::size_t channel_count = 0;  // values per frame: the sum of the joints' channels
  std::size_t frame_count = 0;    // >= 1
  double frame_time = 0.0;        // s, > 0
  std::vector<double> values;     // frame_count x channel_count, finite

  std::span<const double> Frame(std::size_t frame) const {
    return std::span<const double>(values).subspan(frame * channel_count, channel_count);
  }
  // The joint's index, or -1.
  int FindJoint(std::string_view name) const;
  // Time of the last frame, s.
  double Duration() const { return double(frame_count - 1) * frame_time; }
};

// A joint's world frame in one frame of the motion: file axes and units.
struct BvhPose {
  Mat3 rotation = Mat3::Identity();
  Vec3 position = Vec3::Zero();
};

// Forward kinematics of one frame (frame < frame_count), per joint; `out` is resized.
void PoseBvhFrame(const MotionCapture& motion, std::size_t frame, std::vector<BvhPose>& out);
// The rest pose: rotations identity, positions the sums of OFFSETs.
std::vector<Vec3> BvhRestPositions(const MotionCapture& motion);

// Parses BVH text; `source` names it in errors. Refused, naming the line: a missing
// HIERARCHY, ROOT, MOTION, "Frames:" or "Frame Time:"; unknown keywords, channel names or
// channel counts that do not match the names given; a second ROOT; unbalanced braces; duplicate
// joint names; a frame count below 1 or a frame time that is not a positive finite number; a
// frame line whose count of values is not the hierarchy's channel count; fewer or more frame
// lines than "Frames:" says; values that are not finite numbers; more than 10^8 values.
Result<MotionCapture> ParseBvh(std::string_view text, const std::string& source);
// Reads the file, then ParseBvh; errors start with the path.
Result<MotionCapture> LoadBvh(const std::filesystem::path& path);

}  // namespace wirerig
