// JointDescription: how a part turns on its parent, as rig descriptions and rig files state it
// (JSON object "joint" of a part):
//   "type":   "ball" (default), "hinge" or "fixed"
//   "axis":   [x, y, z], rest world axes: the hinge axis (required for a hinge) or a ball's
//             first bend axis; made perpendicular to the bone. Default: the bone's rest normal.
//   "limits": {"x": [min, max], "y": [min, max], "z": [min, max]} in degrees about the joint's
//             X (hinge / first bend), Y and Z (along the bone) axes; each optional, default
//             [-180, 180]; min <= max.
//   "blend":  half-length of the skin bridge across the joint, m, >= 0 (0: none); default
//             automatic (rig_model_builder.h).
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "wirerig/runtime/joint.h"

namespace wirerig {

class JsonObject;

struct JointDescription {
  JointType type = JointType::kBall;
  std::optional<Vec3> axis;
  Vec3 min_degrees = Vec3::Constant(-180.0);
  Vec3 max_degrees = Vec3::Constant(180.0);
  std::optional<double> blend_length;  // m; absent: automatic
};

// Names used in files: "ball", "hinge", "fixed".
const char* ToString(JointType type);

// Reads the optional "joint" member of `part` (throws FieldError naming the field).
JointDescription ReadJointDescription(const JsonObject& part);
nlohmann::json WriteJointDescription(const JointDescription& joint);

// Empty when valid, else "<field>: <reason>" relative to the joint object ("limits/x: ...").
std::string ValidateJointDescription(const JointDescription& joint);

}  // namespace wirerig
