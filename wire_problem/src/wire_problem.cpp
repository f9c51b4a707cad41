#include "wirerig/wire_problem/wire_problem.h"
#include "wirerig/io/json_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <istream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "wirerig/io/input_file.h"
#include "wirerig/io/json_fields.h"
#include "wirerig/rig/json_physics.h"
#include "wirerig/runtime/axial_job.h"

namespace wirerig {
namespace {

WireBendingSpec ReadBending(const JsonObject& b) {
  b.RejectUnknownKeys({"bc", "mode", "terms", "ends", "tip_force", "point_loads", "line_loads",
                       "linear_line_loads"});
  WireBendingSpec spec;
  const std::string bc = b.String("bc");
  if (!ParseBoundaryCondition(bc, &spec.boundary))
    throw FieldError(b.PathOf("bc"), "unknown boundary condition '" + bc +
                                         "' (simply_supported, clamped, cantilever_free, "
                                         "cantilever_guided)");
  if (b.Has("mode")) {
    const std::string mode = b.String("mode");
    if (!ParseBendingMode(mode, &spec.mode))
      throw FieldError(b.PathOf("mode"), "unknown mode '" + mode + "' (exact, series)");
  }
  spec.series_terms = b.Integer("terms", spec.series_terms);
  if (b.Has("ends")) {
    const std::string path = b.PathOf("ends");
    const nlohmann::json& ends = RequireArray(b.Required("ends"), path);
    if (ends.size() != 2) throw FieldError(path, "must hold two displacements [X0, X1]");
    spec.start_displacement = ReadVector3(ends[0], path + "/0");
    spec.end_displacement = ReadVector3(ends[1], path + "/1");
  }
  spec.tip_force = b.Vector3("tip_force", Vec3::Zero());
  ForEachElement(b, "point_loads", [&](const JsonObject& load) {
    load.RejectUnknownKeys({"at", "force"});
    spec.point_loads.push_back(
        {load.Number("at"), ReadVector3(load.Required("force"), load.PathOf("force"))});
  });
  ForEachElement(b, "line_loads", [&](const JsonObject& load) {
    load.RejectUnknownKeys({"from", "to", "force_per_length"});
    spec.line_loads.push_back(
        {load.Number("from"), load.Number("to"),
         ReadVector3(load.Required("force_per_length"), load.PathOf("force_per_length"))});
  });
  ForEachElement(b, "linear_line_loads", [&](const JsonObject& load) {
    load.RejectUnknownKeys({"from", "to", "start_force_per_length", "end_force_per_length"});
    spec.linear_line_loads.push_back(
        {load.Number("from"), load.Number("to"),
         ReadVector3(load.Required("start_force_per_length"),
                     load.PathOf("start_force_per_length")),
         ReadVector3(load.Required("end_force_per_length"), load.PathOf("end_force_per_length"))});
  });
  return spec;
}

WireAxialSpec ReadAxial(const JsonObject& a) {
  a.RejectUnknownKeys({"fixed_at", "point_loads", "line_loads"});
  WireAxialSpec spec;
  spec.fixed_at = a.Number("fixed_at", 0.0);
  ForEachElement(a, "point_loads", [&](const JsonObject& load) {
    load.RejectUnknownKeys({"at", "force"});
    spec.point_loads.push_back({load.Number("at"), load.Number("force")});
  });
  ForEachElement(a, "line_loads", [&](const JsonObject& load) {
    load.RejectUnknownKeys({"from", "to", "force_per_length"});
    spec.line_loads.push_back(
        {load.Number("from"), load.Number("to"), load.Number("force_per_length")});
  });
  return spec;
}

// JSON pointer of a runtime job's field, for error messages.
std::string JobFieldPath(const Status& status, std::string_view part) {
  std::string path = "/";
  path += part;
  if (status.field == "length") return "/length";
  if (status.field == "samples") return "/samples";
  if (status.field == "bending_stiffness" || status.field == "axial_stiffness") return "/section";
  if (status.field == "loads") return path;
  if (status.field == "start_displacement") return path.append("/ends/0");
  if (status.field == "end_displacement") return path.append("/ends/1");
  if (status.field == "series_terms") return path.append("/terms");
  if (status.field == "boundary") return path.append("/bc");
  path.append("/").append(status.field);
  if (status.index >= 0) path.append("/").append(std::to_string(status.index));
  if (!status.member.empty()) path.append("/").append(status.member);
  return path;
}

Error JobError(const Status& status, std::string_view part) {
  return Error{JobFieldPath(status, part) + ": " + std::string(status.reason)};
}

// "/: ..." when the problem's work is over the limit, else empty.
std::string CheckWork(const WireProblem& problem) {
  const double operations = EstimateWireOperations(problem);
  if (operations <= WireProblem::kMaxOperations) return {};
  std::string what = std::to_string(problem.samples) + " samples";
  if (problem.bending && problem.bending->mode == BendingMode::kSeries)
    what += " x " + std::to_string(problem.bending->series_terms) + " series terms";
  if (problem.bending)
    what +=
        ", " +
        std::to_string(problem.bending->point_loads.size() + problem.bending->line_loads.size() +
                       problem.bending->linear_line_loads.size()) +
        " bending loads";
  if (problem.axial)
    what += ", " +
            std::to_string(problem.axial->point_loads.size() + problem.axial->line_loads.size()) +
            " axial loads";
  char numbers[160];
  std::snprintf(numbers, sizeof numbers, "about %.3g operations, more than the %.3g allowed",
                operations, WireProblem::kMaxOperations);
  return "/: too much work (" + what + "): " + numbers +
         "; use fewer samples, terms or loads (docs/wire-format.md)";
}

}  // namespace

Result<WireProblem> ParseWireProblem(const nlohmann::json& document) {
  try {
    const JsonObject root(document, "");
    root.RejectUnknownKeys({"length", "material", "section", "samples", "bending", "axial"});
    WireProblem problem;
    problem.length = root.Number("length");
    problem.material = ReadMaterial(root, "material");
    problem.section = ReadSection(root, "section");
    problem.samples = root.Integer("samples", 101);
    if (problem.samples < 2 || problem.samples > WireProblem::kMaxSamples)
      throw FieldError(root.PathOf("samples"), "must lie in [2, 1000000]");
    if (root.Has("bending")) problem.bending = ReadBending(root.Object("bending"));
    if (root.Has("axial")) problem.axial = ReadAxial(root.Object("axial"));
    if (!problem.bending && !problem.axial)
      throw FieldError("/", "needs \"bending\", \"axial\" or both");
    if (std::string work = CheckWork(problem); !work.empty()) return Error{work};
    return problem;
  } catch (const FieldError& e) {
    return Error{e.what()};
  }
}

namespace {

// Parses one wire problem's JSON text; errors start with `source_name`.
Result<WireProblem> ParseWireProblemText(std::string_view text, std::string_view source_name) {
  const Result<nlohmann::json> document = ParseJsonText(text, source_name);
  if (!document) return Error{document.error()};
  Result<WireProblem> problem = ParseWireProblem(document.value());
  if (!problem) return Error{std::string(source_name) + ": " + problem.error()};
  return problem;
}

}  // namespace

Result<WireProblem> LoadWireProblem(std::istream& in, std::string_view source_name) {
  // Read whole (bounded) before parsing: a stream whose buffer throws (libstdc++'s filebuf on a
  // directory throws std::ios_base::failure) or fails is an error, never an escaping exception.
  std::string text;
  try {
    std::istreambuf_iterator<char> it(in), end;
    for (; it != end && text.size() <= kMaxJsonFileBytes; ++it) text.push_back(*it);
  } catch (const std::exception& e) {
    return Error{std::string(source_name) + ": cannot read (" + e.what() + ")"};
  }
  if (in.bad()) return Error{std::string(source_name) + ": cannot read"};
  if (text.size() > kMaxJsonFileBytes)
    return Error{std::string(source_name) + ": more than the " + std::to_string(kMaxJsonFileBytes) +
                 " bytes a wire problem may have"};
  return ParseWireProblemText(text, source_name);
}

Result<WireProblem> LoadWireProblem(const std::filesystem::path& path) {
  Result<std::string> text = ReadInputFile(path, "wire problem (JSON)");
  if (!text) return Error{text.error()};
  return ParseWireProblemText(text.value(), path.string());
}

double EstimateWireOperations(const WireProblem& problem) {
  const double samples = problem.samples;
  double operations = 0.0;
  // Units of one exact-mode point load at one sample (~3.5 ns); the other costs measured
  // against it: an exact-mode (linear) line load 7, a series term of a point or line load 5,
  // of a linear line load 20 (a 2e9 problem of any kind takes seconds, not minutes).
  if (problem.bending) {
    const WireBendingSpec& b = *problem.bending;
    const double points = double(b.point_loads.size());
    const double lines = double(b.line_loads.size()) + double(b.linear_line_loads.size());
    if (b.mode == BendingMode::kSeries) {
      // Terms out of range are the bending job's to refuse, by their own field.
      const double terms = std::clamp(b.series_terms, 0, BendingJob::kMaxSeriesTerms);
      operations += samples * terms + terms * (5.0 * (points + double(b.line_loads.size())) +
                                               20.0 * double(b.linear_line_loads.size()));
    } else {
      operations += samples * (1.0 + points + 7.0 * lines);
    }
  }
  if (problem.axial) {
    const WireAxialSpec& a = *problem.axial;
    operations += samples * (1.0 + double(a.point_loads.size()) + double(a.line_loads.size()));
  }
  return operations;
}

Result<WireSolution> SolveWireProblem(const WireProblem& problem) {
  if (problem.samples < 2 || problem.samples > WireProblem::kMaxSamples)
    return Error{"/samples: must lie in [2, 1000000]"};
  if (std::string work = CheckWork(problem); !work.empty()) return Error{work};
  WireSolution solution;
  solution.stiffness = ComputeStiffness(problem.material, problem.section);
  const auto n = static_cast<std::size_t>(problem.samples);
  solution.v.resize(n);
  for (std::size_t i = 0; i < n; ++i) solution.v[i] = double(i) / double(n - 1);

  if (problem.bending) {
    const WireBendingSpec& spec = *problem.bending;
    solution.bending.resize(n);
    solution.slope.resize(n);
    solution.curvature.resize(n);
    BendingJob job;
    job.boundary = spec.boundary;
    job.mode = spec.mode;
    job.series_terms = spec.series_terms;
    job.length = problem.length;
    job.bending_stiffness = solution.stiffness.bending;
    job.start_displacement = spec.start_displacement;
    job.end_displacement = spec.end_displacement;
    job.tip_force = spec.tip_force;
    job.point_loads = spec.point_loads;
    job.line_loads = spec.line_loads;
    job.linear_line_loads = spec.linear_line_loads;
    job.samples = solution.v;
    job.displacement = solution.bending;
    job.slope = solution.slope;
    job.curvature = solution.curvature;
    if (const Status status = job.Run(); !status) return JobError(status, "bending");
  }
  if (problem.axial) {
    const WireAxialSpec& spec = *problem.axial;
    solution.axial.resize(n);
    solution.normal_force.resize(n);
    AxialJob job;
    job.length = problem.length;
    job.axial_stiffness = solution.stiffness.axial;
    job.fixed_at = spec.fixed_at;
    job.point_loads = spec.point_loads;
    job.line_loads = spec.line_loads;
    job.samples = solution.v;
    job.displacement = solution.axial;
    job.normal_force = solution.normal_force;
    if (const Status status = job.Run(); !status) return JobError(status, "axial");
  }
  return solution;
}

std::vector<std::string> WireSolutionWarnings(const WireProblem& problem,
                                              const WireSolution& solution) {
  std::vector<std::string> warnings;
  auto check = [&](const char* part, std::size_t count, auto magnitude) {
    double largest = 0.0;
    std::size_t at = 0;
    for (std::size_t i = 0; i < count; ++i) {
      if (const double m = magnitude(i); m > largest) largest = m, at = i;
    }
    if (!(largest > problem.length)) return;
    char text[256];
    std::snprintf(
        text, sizeof text,
        "%s displacement %.3g m at v = %.3g exceeds the wire's length %.3g m: linear beam "
        "theory no longer holds (the loads are far too large for the stiffness)",
        part, largest, solution.v[at], problem.length);
    warnings.emplace_back(text);
  };
  check("bending", solution.bending.size(),
        [&](std::size_t i) { return solution.bending[i].norm(); });
  check("axial", solution.axial.size(), [&](std::size_t i) { return std::abs(solution.axial[i]); });
  return warnings;
}

nlohmann::json WireSolutionToJson(const WireSolution& solution) {
  nlohmann::json out;
  out["v"] = solution.v;
  if (!solution.bending.empty()) {
    nlohmann::json bending = nlohmann::json::array();
    for (const Vec3& x : solution.bending) bending.push_back({x.x(), x.y(), x.z()});
    out["bending"] = std::move(bending);
  }
  if (!solution.axial.empty()) out["axial"] = solution.axial;
  return out;
}

}  // namespace wirerig
