// One wire problem: the input format of `wirerig wire` (documented in docs/wire-format.md).
// Parse checks structure and types and validates material and section; Solve runs the
// runtime jobs, whose validation errors come back with the JSON pointer of the field.
#pragma once

#include <iosfwd>
#include <optional>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "wirerig/rig/result.h"
#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/loads.h"
#include "wirerig/runtime/material.h"
#include "wirerig/runtime/section.h"

namespace wirerig {

struct WireBendingSpec {
  BoundaryCondition boundary = BoundaryCondition::kSimplySupported;
  BendingMode mode = BendingMode::kExact;
  int series_terms = 20;
  Vec3 start_displacement = Vec3::Zero();  // "ends"[0], m
  Vec3 end_displacement = Vec3::Zero();    // "ends"[1], m
  Vec3 tip_force = Vec3::Zero();           // N
  std::vector<PointLoad> point_loads;
  std::vector<LineLoad> line_loads;
};

struct WireAxialSpec {
  double fixed_at = 0.0;
  std::vector<AxialPointLoad> point_loads;
  std::vector<AxialLineLoad> line_loads;
};

struct WireProblem {
  // Largest accepted "samples": bounds memory and time for hostile input.
  static constexpr int kMaxSamples = 1000000;

  double length = 0.0;  // m
  Material material;
  Section section;
  int samples = 0;  // 2 <= samples <= kMaxSamples, at v_i = i / (samples - 1)
  std::optional<WireBendingSpec> bending;
  std::optional<WireAxialSpec> axial;
};

struct WireSolution {
  WireStiffness stiffness;
  std::vector<double> v;
  std::vector<Vec3> bending, slope, curvature;  // empty when the problem has no bending
  std::vector<double> axial, normal_force;      // empty when the problem has no axial part
};

// Errors read "<json pointer>: <reason>".
Result<WireProblem> ParseWireProblem(const nlohmann::json& document);
// Reads JSON text; errors read "<source_name>: <json pointer>: <reason>" (or the parse error).
Result<WireProblem> LoadWireProblem(std::istream& in, std::string_view source_name);

// Runs the bending and axial jobs at every sample.
Result<WireSolution> SolveWireProblem(const WireProblem& problem);

// {"v": [...], "bending": [[x,y,z], ...], "axial": [...]}; absent parts are omitted.
nlohmann::json WireSolutionToJson(const WireSolution& solution);

}  // namespace wirerig
