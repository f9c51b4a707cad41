#include "plate_reference.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace wirerig::chest {
namespace {

bool PositiveFinite(double x) { return std::isfinite(x) && x > 0.0; }

}  // namespace

Status PlateProblem::Validate() const {
  if (!PositiveFinite(width)) return Status::Invalid("width", "must be finite and > 0");
  if (!PositiveFinite(length)) return Status::Invalid("length", "must be finite and > 0");
  if (!PositiveFinite(flexural_rigidity))
    return Status::Invalid("flexural_rigidity", "must be finite and > 0");
  if (!std::isfinite(pressure)) return Status::Invalid("pressure", "must be finite");
  if (intervals < 4 || intervals > kMaxIntervals)
    return Status::Invalid("intervals", "must lie in [4, 1024]");
  return Status::Ok();
}

double PlateSolution::Sample(double u, double v) const {
  const int n = intervals();
  const double x = std::clamp(u, 0.0, 1.0) * n;
  const double y = std::clamp(v, 0.0, 1.0) * n;
  const int i = std::min(static_cast<int>(x), n - 1);
  const int j = std::min(static_cast<int>(y), n - 1);
  const double fx = x - i;
  const double fy = y - j;
  return (1.0 - fx) * ((1.0 - fy) * At(i, j) + fy * At(i, j + 1)) +
         fx * ((1.0 - fy) * At(i + 1, j) + fy * At(i + 1, j + 1));
}

double PlateSolution::Peak() const {
  double peak = 0.0;
  for (double s : deflection) peak = std::max(peak, std::abs(s));
  return peak;
}

Status SolveClampedPlate(const PlateProblem& problem, PlateSolution* out) {
  if (out == nullptr) return Status::Invalid("out", "must not be null");
  if (Status s = problem.Validate(); !s) return s;

  const int n = problem.intervals;
  const int m = n - 1;  // unknowns per grid line: nodes 1..n-1
  const double hx = problem.width / n;
  const double hy = problem.length / n;
  const double alpha = 1.0 / (hx * hx * hx * hx);
  const double beta = 1.0 / (hy * hy * hy * hy);
  const double gamma = 1.0 / (hx * hx * hy * hy);

  // Unknown index of interior node (i, j), 1 <= i, j <= n - 1.
  auto index = [m](int i, int j) { return (i - 1) * m + (j - 1); };
  // Ghost mirror for dS/dn = 0: -1 -> 1, n + 1 -> n - 1. Edge nodes 0 and n stay (S = 0).
  auto mirror = [n](int k) { return k < 0 ? -k : (k > n ? 2 * n - k : k); };

  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(m) * static_cast<std::size_t>(m) * 13);
  auto add = [&](int row, int i, int j, double c) {
    i = mirror(i);
    j = mirror(j);
    if (i <= 0 || i >= n || j <= 0 || j >= n) return;  // edge node: S = 0
    triplets.emplace_back(row, index(i, j), c);
  };
  for (int i = 1; i < n; ++i) {
    for (int j = 1; j < n; ++j) {
      const int row = index(i, j);
      add(row, i, j, 6.0 * alpha + 6.0 * beta + 8.0 * gamma);
      add(row, i - 1, j, -4.0 * alpha - 4.0 * gamma);
      add(row, i + 1, j, -4.0 * alpha - 4.0 * gamma);
      add(row, i, j - 1, -4.0 * beta - 4.0 * gamma);
      add(row, i, j + 1, -4.0 * beta - 4.0 * gamma);
      add(row, i - 2, j, alpha);
      add(row, i + 2, j, alpha);
      add(row, i, j - 2, beta);
      add(row, i, j + 2, beta);
      add(row, i - 1, j - 1, 2.0 * gamma);
      add(row, i - 1, j + 1, 2.0 * gamma);
      add(row, i + 1, j - 1, 2.0 * gamma);
      add(row, i + 1, j + 1, 2.0 * gamma);
    }
  }
  Eigen::SparseMatrix<double> matrix(m * m, m * m);
  matrix.setFromTriplets(triplets.begin(), triplets.end());  // sums mirrored duplicates

  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(matrix);
  if (solver.info() != Eigen::Success)
    return Status::Invalid("intervals", "plate matrix factorisation failed");
  const Eigen::VectorXd rhs =
      Eigen::VectorXd::Constant(m * m, problem.pressure / problem.flexural_rigidity);
  const Eigen::VectorXd w = solver.solve(rhs);
  if (solver.info() != Eigen::Success) return Status::Invalid("intervals", "plate solve failed");

  PlateSolution solution;
  solution.problem = problem;
  solution.deflection.assign(static_cast<std::size_t>(n + 1) * static_cast<std::size_t>(n + 1),
                             0.0);
  for (int i = 1; i < n; ++i)
    for (int j = 1; j < n; ++j)
      solution.deflection[static_cast<std::size_t>(i) * static_cast<std::size_t>(n + 1) +
                          static_cast<std::size_t>(j)] = w[index(i, j)];
  *out = std::move(solution);
  return Status::Ok();
}

}  // namespace wirerig::chest
