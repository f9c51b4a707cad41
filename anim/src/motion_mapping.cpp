// Mapping files: how a motion capture's joints drive a rig's parts.
#include <cmath>

#include <nlohmann/json.hpp>

#include "wirerig/anim/motion_mapping.h"
#include "wirerig/io/input_file.h"
#include "wirerig/io/json_fields.h"
#include "wirerig/io/json_text.h"

namespace wirerig {
namespace {

using nlohmann::json;

constexpr const char* kFormat = "wirerig.motion_mapping";

std::string RequireName(const json& value, const std::string& path, const char* what) {
  if (!value.is_string() || value.get<std::string>().empty())
    throw FieldError(path, std::string("must be a non-empty string (") + what + ")");
  return value.get<std::string>();
}

}  // namespace

Result<MotionMapping> ParseMotionMapping(const nlohmann::json& document) {
  try {
    const JsonObject root(document, "");
    root.RejectUnknownKeys(
        {"format", "version", "source", "channels", "limits", "root_scale", "floor", "joints"});
    if (root.String("format") != kFormat)
      throw FieldError("/format", std::string("must be \"") + kFormat + "\"");
    if (root.Integer("version", -1) != MotionMapping::kFormatVersion)
      throw FieldError("/version", "must be 1 (this wirerig reads mapping format version 1)");
    MotionMapping mapping;
    if (root.Has("source")) {
      const JsonObject source = root.Object("source");
      source.RejectUnknownKeys({"up_axis", "unit_scale"});
      if (source.Has("up_axis") && !ParseUpAxis(source.String("up_axis"), &mapping.up_axis))
        throw FieldError(source.PathOf("up_axis"), "must be \"x\", \"y\" or \"z\"");
      mapping.unit_scale = source.Number("unit_scale", 1.0);
      if (!(std::isfinite(mapping.unit_scale) && mapping.unit_scale >= 1e-9 &&
            mapping.unit_scale <= 1e9))
        throw FieldError(source.PathOf("unit_scale"),
                         "must be a finite number of metres per unit in [1e-9, 1e9]");
    }
    mapping.channels =
        root.Keyword<RetargetChannels>("channels",
                                       {{"rotation", RetargetChannels::kRotation},
                                        {"joint_angles", RetargetChannels::kJointAngles}},
                                       mapping.channels);
    mapping.limits =
        root.Keyword<RetargetLimits>("limits",
                                     {{"pass_to_parents", RetargetLimits::kPassToParents},
                                      {"clamp", RetargetLimits::kClamp},
                                      {"ignore", RetargetLimits::kIgnore}},
                                     mapping.limits);
    mapping.root_scale = root.Keyword<RootScale>(
        "root_scale", {{"leg_length", RootScale::kLegLength}, {"unit", RootScale::kUnit}},
        mapping.root_scale);
    mapping.floor = root.Keyword<RetargetFloor>(
        "floor", {{"above", RetargetFloor::kAbove}, {"free", RetargetFloor::kFree}}, mapping.floor);
    const JsonObject joints = root.Object("joints");
    for (const auto& item : root.Required("joints").items()) {
      const std::string path = joints.PathOf(item.key());
      if (item.key().empty()) throw FieldError(path, "a joint name must not be empty");
      JointMapping entry;
      entry.joint = item.key();
      if (item.value().is_string()) {
        entry.part = RequireName(item.value(), path, "the part's name");
      } else {
        const JsonObject o(item.value(), path);
        o.RejectUnknownKeys({"part", "tip"});
        entry.part = RequireName(o.Required("part"), o.PathOf("part"), "the part's name");
        if (o.Has("tip"))
          entry.tip = RequireName(o.Required("tip"), o.PathOf("tip"), "a joint of the capture");
      }
      for (const JointMapping& earlier : mapping.joints)
        if (earlier.part == entry.part)
          throw FieldError(path, "part \"" + entry.part + "\" is already driven by joint \"" +
                                     earlier.joint + "\"");
      mapping.joints.push_back(std::move(entry));
    }
    if (mapping.joints.empty()) throw FieldError("/joints", "maps no joint");
    return mapping;
  } catch (const FieldError& e) {
    return Error{e.what()};
  } catch (const nlohmann::json::exception& e) {
    return Error{std::string("/: ") + e.what()};
  }
}

Result<MotionMapping> LoadMotionMapping(const std::filesystem::path& path) {
  Result<std::string> text = ReadInputFile(path, "motion mapping file (JSON)");
  if (!text) return Error{text.error()};
  const Result<json> document = ParseJsonText(text.value(), path.string());
  if (!document) return Error{document.error()};
  Result<MotionMapping> mapping = ParseMotionMapping(document.value());
  if (!mapping) return Error{path.string() + ": " + mapping.error()};
  mapping.value().source_file = path.string();
  return mapping;
}

}  // namespace wirerig
