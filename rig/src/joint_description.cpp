#include "wirerig/rig/joint_description.h"

#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "wirerig/io/json_fields.h"

namespace wirerig {
namespace {

constexpr const char* kAxisNames[3] = {"x", "y", "z"};

}  // namespace

const char* ToString(JointType type) {
  switch (type) {
    case JointType::kHinge:
      return "hinge";
    case JointType::kFixed:
      return "fixed";
    case JointType::kBall:
      break;
  }
  return "ball";
}

JointDescription ReadJointDescription(const JsonObject& part) {
  JointDescription joint;
  if (!part.Has("joint")) return joint;
  const JsonObject j = part.Object("joint");
  j.RejectUnknownKeys({"type", "axis", "limits", "blend"});
  if (j.Has("type")) {
    const std::string type = j.String("type");
    if (type == "ball")
      joint.type = JointType::kBall;
    else if (type == "hinge")
      joint.type = JointType::kHinge;
    else if (type == "fixed")
      joint.type = JointType::kFixed;
    else
      throw FieldError(j.PathOf("type"), "must be \"ball\", \"hinge\" or \"fixed\"");
  }
  if (j.Has("axis")) joint.axis = ReadVector3(j.Required("axis"), j.PathOf("axis"));
  if (j.Has("limits")) {
    const JsonObject limits = j.Object("limits");
    limits.RejectUnknownKeys({"x", "y", "z"});
    for (int k = 0; k < 3; ++k) {
      if (!limits.Has(kAxisNames[k])) continue;
      const std::string path = limits.PathOf(kAxisNames[k]);
      const nlohmann::json& range = RequireArray(limits.Required(kAxisNames[k]), path);
      if (ArraySize(range) != 2 || !range[0].is_number() || !range[1].is_number())
        throw FieldError(path, "must be [min, max] in degrees");
      joint.min_degrees[k] = range[0].get<double>();
      joint.max_degrees[k] = range[1].get<double>();
    }
  }
  if (j.Has("blend")) joint.blend_length = j.Number("blend");
  if (std::string error = ValidateJointDescription(joint); !error.empty()) {
    const std::size_t colon = error.find(": ");
    throw FieldError(j.path() + "/" + error.substr(0, colon), error.substr(colon + 2));
  }
  return joint;
}

nlohmann::json WriteJointDescription(const JointDescription& joint) {
  nlohmann::json out = {{"type", ToString(joint.type)}};
  if (joint.axis) out["axis"] = {joint.axis->x(), joint.axis->y(), joint.axis->z()};
  nlohmann::json limits = nlohmann::json::object();
  for (int k = 0; k < 3; ++k) limits[kAxisNames[k]] = {joint.min_degrees[k], joint.max_degrees[k]};
  out["limits"] = limits;
  if (joint.blend_length) out["blend"] = *joint.blend_length;
  return out;
}

std::string ValidateJointDescription(const JointDescription& joint) {
  if (joint.type == JointType::kHinge && !joint.axis) return "axis: a hinge needs its axis";
  if (joint.axis && !(joint.axis->allFinite() && joint.axis->norm() > 1e-9))
    return "axis: must be finite and of non-zero length";
  for (int k = 0; k < 3; ++k) {
    const std::string field = std::string("limits/") + kAxisNames[k];
    if (!(std::isfinite(joint.min_degrees[k]) && std::isfinite(joint.max_degrees[k])))
      return field + ": must be finite";
    if (joint.min_degrees[k] > joint.max_degrees[k]) {
      char limits[96];
      std::snprintf(limits, sizeof limits, ": the lower limit %g is above the upper limit %g",
                    joint.min_degrees[k], joint.max_degrees[k]);
      return field + limits;
    }
  }
  if (joint.blend_length && !(std::isfinite(*joint.blend_length) && *joint.blend_length >= 0.0))
    return "blend: must be finite and >= 0 (m)";
  return {};
}

}  // namespace wirerig
