// One wire problem: the input format of `wirerig wire` (documented in docs/wire-format.md).
// Parse checks structure and types and validates material and section; Solve runs the
// runtime jobs, whose validation errors come back with the JSON pointer of the field.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "wirerig/io/result.h"
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
  std::vector<LinearLineLoad> linear_line_loads;
};

struct WireAxialSpec {
  double fixed_at = 0.0;
  std::vector<AxialPointLoad> point_loads;
  std::vector<AxialLineLoad> line_loads;
};

struct WireProblem {
  // Largest accepted "samples": bounds memory and time for hostile input.
  static constexpr int kMaxSamples = 1000000;
  // Largest accepted work (EstimateWireOperations): bounds the time of valid but huge problems
  // (1e6 samples x 1e5 series terms or point loads) to seconds. docs/wire-format.md.
  static constexpr double kMaxOperations = 2e9;

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

// The work of solving `problem`, in units of one exact-mode point load at one sample: per
// sample, 1 + point loads + 7 x (linear) line loads in exact mode, or one per term in series
// mode (whose coefficients cost terms x (5 x point and line loads + 20 x linear line loads));
// per sample, one per axial load (plus one). docs/wire-format.md gives the measurements.
double EstimateWireOperations(const WireProblem& problem);

// Errors read "<json pointer>: <reason>". A problem whose work is over kMaxOperations is refused
// with its estimate.
Result<WireProblem> ParseWireProblem(const nlohmann::json& document);
// Reads JSON text (at most kMaxJsonFileBytes); errors read "<source_name>: <json pointer>:
// <reason>" (or the parse or read error). A stream that fails to read (a directory) is an error.
Result<WireProblem> LoadWireProblem(std::istream& in, std::string_view source_name);
// The same from a file, refused unless it is a regular file of at most kMaxJsonFileBytes
// (input_file.h); errors start with the path.
Result<WireProblem> LoadWireProblem(const std::filesystem::path& path);

// Runs the bending and axial jobs at every sample; refuses (as ParseWireProblem does) samples
// out of range and work over kMaxOperations.
Result<WireSolution> SolveWireProblem(const WireProblem& problem);

// What a solution warns about: a bending or axial displacement larger than the wire's length,
// where linear beam theory no longer holds (a 1e12 N load on a soft wire: 3e24 m). Messages
// name the part, the largest displacement, where, and the length.
std::vector<std::string> WireSolutionWarnings(const WireProblem& problem,
                                              const WireSolution& solution);

// {"v": [...], "bending": [[x,y,z], ...], "axial": [...]}; absent parts are omitted.
nlohmann::json WireSolutionToJson(const WireSolution& solution);

}  // namespace wirerig
