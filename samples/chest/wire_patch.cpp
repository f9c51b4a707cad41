#include "wire_patch.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/loads.h"

namespace wirerig::chest {
namespace {

// The plate lies in the x-z plane with +Y up and q pushing down (-Y); deflection is reported
// along the load, so a positive q gives positive values, as PlateSolution does.
constexpr int kLoadAxis = 1;
constexpr double kLoadSign = -1.0;

// Closed-form deflection of interior wire j (xi = 1) under pressure q at `samples`, along the
// load, into `out`. `scratch` holds samples.size() vectors.
Status SolveWire(const WirePatch& patch, int j, double pressure, std::span<const double> samples,
                 std::span<Vec3> scratch, std::span<double> out) {
  const std::size_t wire = static_cast<std::size_t>(j);
  LineLoad load;
  load.from = 0.0;
  load.to = 1.0;
  load.force_per_length = Vec3::Zero();
  load.force_per_length[kLoadAxis] = kLoadSign * patch.strip_width[wire] * pressure;
  BendingJob job;
  job.boundary = BoundaryCondition::kClamped;
  job.length = patch.length;
  job.bending_stiffness = patch.flexural_rigidity * patch.strip_width[wire];
  job.line_loads = {&load, 1};
  job.samples = samples;
  job.displacement = scratch;
  if (Status s = job.Run(); !s) return s;
  for (std::size_t k = 0; k < samples.size(); ++k) out[k] = kLoadSign * scratch[k][kLoadAxis];
  return Status::Ok();
}

}  // namespace

Status FitWirePatch(const PlateSolution& plate, int wire_count, XiFit fit, WirePatch* out) {
  if (out == nullptr) return Status::Invalid("out", "must not be null");
  if (Status s = plate.problem.Validate(); !s) return s;
  const int n = plate.intervals();
  if (plate.deflection.size() != static_cast<std::size_t>(n + 1) * static_cast<std::size_t>(n + 1))
    return Status::Invalid("plate", "deflection must hold (n + 1)^2 values");
  if (wire_count < 3) return Status::Invalid("wire_count", "must be at least 3");
  if (n % (wire_count - 1) != 0)
    return Status::Invalid("wire_count", "wire_count - 1 must divide the plate's intervals");
  if (!(plate.Peak() > 0.0)) return Status::Invalid("plate", "has no deflection to fit");

  const PlateProblem& p = plate.problem;
  WirePatch patch;
  patch.width = p.width;
  patch.length = p.length;
  patch.flexural_rigidity = p.flexural_rigidity;
  const std::size_t m = static_cast<std::size_t>(wire_count);
  const double spacing = p.width / (wire_count - 1);
  patch.u.resize(m);
  patch.strip_width.assign(m, 0.0);
  patch.xi.assign(m, 0.0);
  for (std::size_t j = 0; j < m; ++j) {
    patch.u[j] = static_cast<double>(j) / static_cast<double>(m - 1);
    // b_j = (b_{j-1} + b_j)/2 with equal spacings; edge wires are clamped (X = 0).
    if (j > 0 && j + 1 < m) patch.strip_width[j] = spacing;
  }

  // Trapezoidal products of S(u_j, v) and X_j(v) on the plate's nodes v_k = k/n.
  std::vector<double> samples(static_cast<std::size_t>(n + 1));
  for (int k = 0; k <= n; ++k) samples[static_cast<std::size_t>(k)] = static_cast<double>(k) / n;
  std::vector<Vec3> scratch(samples.size());
  std::vector<double> x(samples.size());
  std::vector<double> numerator(m, 0.0), denominator(m, 0.0);
  const int column_step = n / (wire_count - 1);
  for (std::size_t j = 1; j + 1 < m; ++j) {
    if (Status s = SolveWire(patch, static_cast<int>(j), p.pressure, samples, scratch, x); !s)
      return s;
    const int i = static_cast<int>(j) * column_step;
    for (int k = 0; k <= n; ++k) {
      const double weight = (k == 0 || k == n) ? 0.5 : 1.0;
      const double xk = x[static_cast<std::size_t>(k)];
      numerator[j] += weight * plate.At(i, k) * xk;
      denominator[j] += weight * xk * xk;
    }
    if (!(denominator[j] > 0.0)) return Status::Invalid("plate", "wire deflection vanishes");
  }

  double sum_numerator = 0.0, sum_denominator = 0.0;
  for (std::size_t j = 1; j + 1 < m; ++j) {
    sum_numerator += numerator[j];
    sum_denominator += denominator[j];
  }
  for (std::size_t j = 1; j + 1 < m; ++j) {
    switch (fit) {
      case XiFit::kNone:
        patch.xi[j] = 1.0;
        break;
      case XiFit::kSingle:
        patch.xi[j] = sum_numerator / sum_denominator;
        break;
      case XiFit::kPerWire:
        patch.xi[j] = numerator[j] / denominator[j];
        break;
    }
  }
  *out = std::move(patch);
  return Status::Ok();
}

Status WirePatchJob::Run() const {
  if (patch == nullptr) return Status::Invalid("patch", "must not be null");
  const std::size_t m = patch->u.size();
  if (m < 3 || patch->strip_width.size() != m || patch->xi.size() != m)
    return Status::Invalid("patch", "needs at least 3 wires and one width and xi per wire");
  if (!std::isfinite(pressure)) return Status::Invalid("pressure", "must be finite");
  if (samples.empty()) return Status::Invalid("samples", "must not be empty");
  if (scratch.size() != samples.size())
    return Status::Invalid("scratch", "must hold samples.size() vectors");
  if (deflection.size() != m * samples.size())
    return Status::Invalid("deflection", "must hold wire_count * samples.size() values");
  for (std::size_t j = 1; j + 1 < m; ++j)
    if (!std::isfinite(patch->xi[j]))
      return Status::InvalidElement("patch", int(j), "xi", "must be finite");

  const std::size_t count = samples.size();
  std::fill_n(deflection.begin(), count, 0.0);                    // wire 0: clamped edge
  std::fill_n(deflection.begin() + (m - 1) * count, count, 0.0);  // wire m-1: clamped edge
  for (std::size_t j = 1; j + 1 < m; ++j) {
    std::span<double> out = deflection.subspan(j * count, count);
    if (Status s = SolveWire(*patch, static_cast<int>(j), pressure, samples, scratch, out); !s)
      return s;
    for (double& value : out) value *= patch->xi[j];
  }
  return Status::Ok();
}

Status CompareWithPlate(const WirePatch& patch, const PlateSolution& plate, WirePatchErrors* out) {
  if (out == nullptr) return Status::Invalid("out", "must not be null");
  const int n = plate.intervals();
  const int m = patch.wire_count();
  if (m < 3 || n % (m - 1) != 0)
    return Status::Invalid("plate", "wire_count - 1 must divide the plate's intervals");
  const double peak = plate.Peak();
  if (!(peak > 0.0)) return Status::Invalid("plate", "has no deflection to compare with");

  const std::size_t count = static_cast<std::size_t>(n + 1);
  std::vector<double> samples(count);
  for (int k = 0; k <= n; ++k) samples[static_cast<std::size_t>(k)] = static_cast<double>(k) / n;
  std::vector<Vec3> scratch(count);
  std::vector<double> model(static_cast<std::size_t>(m) * count);
  WirePatchJob job;
  job.patch = &patch;
  job.pressure = plate.problem.pressure;
  job.samples = samples;
  job.scratch = scratch;
  job.deflection = model;
  if (Status s = job.Run(); !s) return s;
  auto wire_value = [&](int j, int k) {
    return model[static_cast<std::size_t>(j) * count + static_cast<std::size_t>(k)];
  };

  WirePatchErrors errors;
  errors.plate_peak = peak;
  errors.max_per_wire.assign(static_cast<std::size_t>(m), 0.0);
  const int column_step = n / (m - 1);
  double sum_wires = 0.0;
  for (int j = 1; j + 1 < m; ++j) {
    for (int k = 0; k <= n; ++k) {
      const double e = std::abs(wire_value(j, k) - plate.At(j * column_step, k)) / peak;
      double& wire_max = errors.max_per_wire[static_cast<std::size_t>(j)];
      wire_max = std::max(wire_max, e);
      sum_wires += e * e;
    }
    errors.max_on_wires =
        std::max(errors.max_on_wires, errors.max_per_wire[static_cast<std::size_t>(j)]);
  }
  errors.rms_on_wires =
      std::sqrt(sum_wires / (static_cast<double>(m - 2) * static_cast<double>(count)));

  double sum_surface = 0.0;
  for (int i = 0; i <= n; ++i) {
    const int left = std::min(i / column_step, m - 2);
    const double t = static_cast<double>(i - left * column_step) / column_step;
    for (int k = 0; k <= n; ++k) {
      const double value = (1.0 - t) * wire_value(left, k) + t * wire_value(left + 1, k);
      const double e = std::abs(value - plate.At(i, k)) / peak;
      errors.max_surface = std::max(errors.max_surface, e);
      sum_surface += e * e;
    }
  }
  errors.rms_surface =
      std::sqrt(sum_surface / (static_cast<double>(count) * static_cast<double>(count)));
  *out = std::move(errors);
  return Status::Ok();
}

}  // namespace wirerig::chest
