// Mapping files (`"format": "wirerig.motion_mapping"`, version 1): how a motion capture's
// joints drive a rig's parts (docs/motion-import.md). Checked-in example:
// samples/mocap/human_from_cmu.mapping.json.
//
//   {"format": "wirerig.motion_mapping", "version": 1,
//    "source": {"up_axis": "y", "unit_scale": 0.056444},
//    "channels": "rotation",
//    "limits": "pass_to_parents",
//    "root_scale": "leg_length",
//    "joints": {"Hips": "pelvis", "LeftUpLeg": "thigh_l",
//               "LeftHand": {"part": "hand_l", "tip": "LFingers"}, ...}}
//
// LoadMotionMapping checks the file on its own (format, fields, types, values; unknown fields
// are refused); whether its joints and parts exist is checked against the motion and the rig
// when retargeting (motion_import.h). Errors read "<file>: <json pointer>: <reason>".
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "wirerig/io/result.h"
#include "wirerig/rig/mesh_import.h"

namespace wirerig {

// What the retargeted clip's tracks are.
enum class RetargetChannels : int {
  // `rotation` per part: each part's turn after RetargetLimits (the runtime does not clamp
  // rotation tracks).
  kRotation = 0,
  // `joint_angles` per child part (X, Y, Z about its joint axes, clamped to the joint's type
  // and limits when sampled); the root keeps `rotation`.
  kJointAngles = 1,
};

// What the retarget does where a part's turn leaves its joint's limits (joint.h: per axis, in
// degrees, and the joint's type).
enum class RetargetLimits : int {
  // Clamp the turn to the limits and hand what they refuse to the parent chain, each ancestor
  // within its own limits (motion_limits.h), so the part's world rotation is kept as well as the
  // chain's limits allow. The default.
  kPassToParents = 0,
  // Clamp each turn to its own limits; the parents do not take the rest.
  kClamp = 1,
  // The capture exactly, beyond the limits (rotation tracks; joint_angles are still clamped
  // when sampled).
  kIgnore = 2,
};

// How the root's translation is scaled from file units to metres.
enum class RootScale : int {
  kLegLength = 0,  // by the rig's leg length over the capture's (docs/motion-import.md)
  kUnit = 1,       // by source.unit_scale alone
};

// Where the retargeted body may go against the floor (the rest mesh's lowest point: the soles of
// a figure standing at rest).
enum class RetargetFloor : int {
  // Where a frame would put any point of the skin below the floor (the rig's proportions differ
  // from the subject's), the root is lifted by as much: no point sinks; nothing is pulled down.
  // The default.
  kAbove = 0,
  kFree = 1,  // the capture's root height, scaled, whatever the skin does
};

struct JointMapping {
  std::string joint;  // the capture's joint
  std::string part;   // the rig's part it drives
  std::string tip;    // optional: the capture's joint where the part's bone ends
};

struct MotionMapping {
  static constexpr int kFormatVersion = 1;

  std::string source_file;      // the mapping file, for messages
  UpAxis up_axis = UpAxis::kY;  // the capture's up axis
  double unit_scale = 1.0;      // metres per capture unit
  RetargetChannels channels = RetargetChannels::kRotation;
  RetargetLimits limits = RetargetLimits::kPassToParents;
  RootScale root_scale = RootScale::kLegLength;
  RetargetFloor floor = RetargetFloor::kAbove;
  std::vector<JointMapping> joints;  // in the file's key order (sorted by joint name)
};

// Reads a parsed document; errors read "<json pointer>: <reason>".
Result<MotionMapping> ParseMotionMapping(const nlohmann::json& document);
// Reads the file; errors start with its path.
Result<MotionMapping> LoadMotionMapping(const std::filesystem::path& path);

}  // namespace wirerig
