// Finite-difference reference for wire bending; see fd_beam_reference.h.
#include "support/fd_beam_reference.h"

#include <Eigen/OrderingMethods>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace wirerig::testing {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Rhs = Eigen::Matrix<double, Eigen::Dynamic, 3>;
using RhsLong = Eigen::Matrix<long double, Eigen::Dynamic, 3>;

bool IsCantileverEnd(BoundaryCondition bc) {
  return bc == BoundaryCondition::kCantileverFree || bc == BoundaryCondition::kCantileverGuided;
}

// A node value as an affine expression of the unknowns and of the known quantities
// X0, X1 and F (tip force): X[j] = sum coef_i u[node_i] + x0 X0 + x1 X1 + f F.
struct Affine {
  std::array<int, 3> node{};  // node indices of unknowns
  std::array<double, 3> coef{};
  int count = 0;
  double x0 = 0.0;
  double x1 = 0.0;
  double f = 0.0;

  void Add(int k, double c) {
    for (int i = 0; i < count; ++i) {
      if (node[i] == k) {
        coef[i] += c;
        return;
      }
    }
    node[count] = k;
    coef[count] = c;
    ++count;
  }
};

// The grid: n intervals, unknown nodes 1..last (last = n for cantilevers, n - 1 otherwise).
struct Grid {
  BoundaryCondition bc;
  int n;
  double h;
  double ei;
  int last;

  // X[j] for -1 <= j <= n + 2 (n + 2 only for cantilevers).
  Affine Node(int j) const {
    Affine a;
    if (j == -1) {
      // Start: simply supported X'' = 0, otherwise clamped X' = 0 (central differences).
      if (bc == BoundaryCondition::kSimplySupported) {
        a.x0 = 2.0;
        a.Add(1, -1.0);
      } else {
        a.Add(1, 1.0);
      }
    } else if (j == 0) {
      a.x0 = 1.0;
    } else if (j <= last) {
      a.Add(j, 1.0);
    } else if (j == n) {  // simply supported or clamped end: X(L) = X1
      a.x1 = 1.0;
    } else if (j == n + 1) {
      switch (bc) {
        case BoundaryCondition::kSimplySupported:  // X'' = 0
          a.x1 = 2.0;
          a.Add(n - 1, -1.0);
          break;
        case BoundaryCondition::kClamped:  // X' = 0
        case BoundaryCondition::kCantileverGuided:
          a.Add(n - 1, 1.0);
          break;
        case BoundaryCondition::kCantileverFree:  // X'' = 0
          a.Add(n, 2.0);
          a.Add(n - 1, -1.0);
          break;
      }
    } else {  // j == n + 2, cantilevers: EI (X[n+2] - 2X[n+1] + 2X[n-1] - X[n-2]) / 2h^3 = -F
      const Affine g = Node(n + 1);
      for (int i = 0; i < g.count; ++i) a.Add(g.node[i], 2.0 * g.coef[i]);
      a.Add(n - 1, -2.0);
      a.Add(n - 2, 1.0);
      a.f = -2.0 * h * h * h / ei;
    }
    return a;
  }
};

struct Loads {
  std::vector<Vec3> node_load;  // p at each node 0..n, N/m
  Vec3 tip_force = Vec3::Zero();
};

// Snaps v to a node of the grid of n intervals; false if it is not on one.
bool SnapToNode(double v, int n, int* k) {
  const double x = v * n;
  const double r = std::round(x);
  if (!(std::abs(x - r) <= 1e-9 * n) || r < 0.0 || r > n) return false;
  *k = static_cast<int>(r);
  return true;
}

std::string AssembleLoads(const FdBeamProblem& p, const Grid& g, Loads* out) {
  out->node_load.assign(g.n + 1, Vec3::Zero());
  out->tip_force = IsCantileverEnd(p.boundary) ? p.tip_force : Vec3::Zero();
  const bool free_end = IsCantileverEnd(p.boundary);
  for (size_t i = 0; i < p.point_loads.size(); ++i) {
    const PointLoad& load = p.point_loads[i];
    int k = 0;
    if (!SnapToNode(load.at, g.n, &k)) {
      return "point_loads[" + std::to_string(i) + "].at is not on a grid node";
    }
    if (k == g.n && free_end) {
      out->tip_force += load.force;  // the end node carries the load as a tip force
    } else {
      out->node_load[k] += load.force / g.h;  // taken by the support when k is prescribed
    }
  }
  for (size_t i = 0; i < p.line_loads.size(); ++i) {
    const LineLoad& load = p.line_loads[i];
    int ka = 0;
    int kb = 0;
    if (!SnapToNode(load.from, g.n, &ka) || !SnapToNode(load.to, g.n, &kb)) {
      return "line_loads[" + std::to_string(i) + "] end is not on a grid node";
    }
    if (ka >= kb) return "line_loads[" + std::to_string(i) + "] needs from < to";
    for (int k = ka; k <= kb; ++k) {
      double w = 1.0;
      if (k == ka || k == kb) w = 0.5;    // the average of the one-sided densities
      if (k == g.n && free_end) w = 1.0;  // one-sided density at the free or guided end
      out->node_load[k] += w * load.force_per_length;
    }
  }
  for (size_t i = 0; i < p.linear_line_loads.size(); ++i) {
    const LinearLineLoad& load = p.linear_line_loads[i];
    int ka = 0;
    int kb = 0;
    if (!SnapToNode(load.from, g.n, &ka) || !SnapToNode(load.to, g.n, &kb)) {
      return "linear_line_loads[" + std::to_string(i) + "] end is not on a grid node";
    }
    if (ka >= kb) return "linear_line_loads[" + std::to_string(i) + "] needs from < to";
    for (int k = ka; k <= kb; ++k) {
      double w = 1.0;
      if (k == ka || k == kb) w = 0.5;
      if (k == g.n && free_end) w = 1.0;
      const double t = static_cast<double>(k - ka) / (kb - ka);
      out->node_load[k] +=
          w * ((1.0 - t) * load.start_force_per_length + t * load.end_force_per_length);
    }
  }
  return {};
}

// Solves A x = b with iterative refinement. b is kept in long double: near a prescribed end
// it is the small load term h^4 p/EI minus the much larger end-displacement terms, and
// rounding it to double would perturb the load. The residual is formed in long double too,
// where the integer stencil applied to double values is (nearly always) exact.
Rhs SolveRefined(const Eigen::SparseLU<SparseMatrix>& lu, const SparseMatrix& a, const RhsLong& b) {
  Rhs x = lu.solve(Rhs(b.cast<double>()));
  for (int iteration = 0; iteration < 3; ++iteration) {
    // A x first (exact), then b - A x: subtracting from b term by term would round b's
    // small value to the precision of the large terms.
    RhsLong ax = RhsLong::Zero(b.rows(), 3);
    for (Eigen::Index col = 0; col < a.outerSize(); ++col) {
      for (SparseMatrix::InnerIterator it(a, col); it; ++it) {
        for (int c = 0; c < 3; ++c) {
          ax(it.row(), c) += static_cast<long double>(it.value()) * x(col, c);
        }
      }
    }
    const RhsLong r = b - ax;
    const Rhs d = lu.solve(Rhs(r.cast<double>()));
    x += d;
  }
  return x;
}

// One solve on n intervals; fills x (n + 1 nodes).
std::string SolveOnGrid(const FdBeamProblem& p, int n, std::vector<Vec3>* x) {
  if (n < 4) return "n must be at least 4";
  if (!(p.length > 0.0) || !std::isfinite(p.length)) return "length must be positive";
  if (!(p.bending_stiffness > 0.0) || !std::isfinite(p.bending_stiffness)) {
    return "bending_stiffness must be positive";
  }
  const bool cantilever = IsCantileverEnd(p.boundary);
  Grid g{p.boundary, n, p.length / n, p.bending_stiffness, cantilever ? n : n - 1};
  Loads loads;
  if (std::string error = AssembleLoads(p, g, &loads); !error.empty()) return error;

  const Vec3 x0 = p.start_displacement;
  const Vec3 x1 = cantilever ? Vec3::Zero() : p.end_displacement;
  const long double h = static_cast<long double>(p.length) / n;
  const long double load_scale = h * h * h * h / static_cast<long double>(g.ei);
  const int unknowns = g.last;
  std::vector<Eigen::Triplet<double>> triplets;
  RhsLong b = RhsLong::Zero(unknowns, 3);
  static constexpr std::array<double, 5> kStencil = {1.0, -4.0, 6.0, -4.0, 1.0};
  for (int k = 1; k <= g.last; ++k) {
    // The free or guided end's row is halved, which makes the matrix symmetric.
    const double scale = (cantilever && k == n) ? 0.5 : 1.0;
    const int row = k - 1;
    Eigen::Matrix<long double, 3, 1> rhs = loads.node_load[k].cast<long double>() * load_scale;
    for (int s = 0; s < 5; ++s) {
      const double c = kStencil[s];
      const Affine a = g.Node(k - 2 + s);
      for (int i = 0; i < a.count; ++i) {
        triplets.emplace_back(row, a.node[i] - 1, scale * c * a.coef[i]);
      }
      for (int comp = 0; comp < 3; ++comp) {
        rhs[comp] -=
            static_cast<long double>(c) *
            (static_cast<long double>(a.x0) * x0[comp] + static_cast<long double>(a.x1) * x1[comp] +
             static_cast<long double>(a.f) * loads.tip_force[comp]);
      }
    }
    b.row(row) = static_cast<long double>(scale) * rhs.transpose();
  }
  SparseMatrix a(unknowns, unknowns);
  a.setFromTriplets(triplets.begin(), triplets.end());  // sums duplicates
  a.makeCompressed();
  Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(a);
  if (lu.info() != Eigen::Success) return "sparse LU failed";
  const Rhs u = SolveRefined(lu, a, b);

  x->assign(n + 1, Vec3::Zero());
  (*x)[0] = x0;
  for (int k = 1; k <= g.last; ++k) (*x)[k] = u.row(k - 1).transpose();
  if (!cantilever) (*x)[n] = x1;
  return {};
}

// Scalar problems are solved as the x component of a 3D one.
struct ScalarAs3d {
  std::vector<PointLoad> points;
  std::vector<LineLoad> lines;
  std::vector<LinearLineLoad> linear_lines;
  FdBeamProblem problem;

  explicit ScalarAs3d(const FdScalarBeamProblem& s) {
    for (const FdScalarPointLoad& l : s.point_loads) {
      points.push_back({l.at, Vec3(l.force, 0.0, 0.0)});
    }
    for (const FdScalarLineLoad& l : s.line_loads) {
      lines.push_back({l.from, l.to, Vec3(l.force_per_length, 0.0, 0.0)});
    }
    for (const FdScalarLinearLineLoad& l : s.linear_line_loads) {
      linear_lines.push_back({l.from, l.to, Vec3(l.start_force_per_length, 0.0, 0.0),
                              Vec3(l.end_force_per_length, 0.0, 0.0)});
    }
    problem.boundary = s.boundary;
    problem.length = s.length;
    problem.bending_stiffness = s.bending_stiffness;
    problem.start_displacement = Vec3(s.start_displacement, 0.0, 0.0);
    problem.end_displacement = Vec3(s.end_displacement, 0.0, 0.0);
    problem.tip_force = Vec3(s.tip_force, 0.0, 0.0);
    problem.point_loads = points;
    problem.line_loads = lines;
    problem.linear_line_loads = linear_lines;
  }
};

FdBeamSolution ToScalar(FdBeamSolution solution) {
  solution.scalar.clear();
  for (const Vec3& x : solution.displacement) solution.scalar.push_back(x.x());
  solution.displacement.clear();
  return solution;
}

}  // namespace

FdBeamSolution SolveFdBeam(const FdBeamProblem& problem, int n) {
  FdBeamSolution solution;
  solution.error = SolveOnGrid(problem, n, &solution.displacement);
  return solution;
}

FdBeamSolution SolveFdBeam(const FdScalarBeamProblem& problem, int n) {
  const ScalarAs3d p(problem);
  return ToScalar(SolveFdBeam(p.problem, n));
}

FdBeamSolution SolveFdBeamRichardson(const FdBeamProblem& problem, int n) {
  FdBeamSolution solution;
  // Load positions must lie on the coarse grid (so they also lie on the finer ones).
  for (size_t i = 0; i < problem.point_loads.size(); ++i) {
    int k = 0;
    if (!SnapToNode(problem.point_loads[i].at, std::max(n, 1), &k)) {
      solution.error = "point_loads[" + std::to_string(i) + "].at is not on a coarse grid node";
      return solution;
    }
  }
  for (size_t i = 0; i < problem.line_loads.size(); ++i) {
    int k = 0;
    if (!SnapToNode(problem.line_loads[i].from, std::max(n, 1), &k) ||
        !SnapToNode(problem.line_loads[i].to, std::max(n, 1), &k)) {
      solution.error = "line_loads[" + std::to_string(i) + "] end is not on a coarse grid node";
      return solution;
    }
  }
  for (size_t i = 0; i < problem.linear_line_loads.size(); ++i) {
    int k = 0;
    if (!SnapToNode(problem.linear_line_loads[i].from, std::max(n, 1), &k) ||
        !SnapToNode(problem.linear_line_loads[i].to, std::max(n, 1), &k)) {
      solution.error =
          "linear_line_loads[" + std::to_string(i) + "] end is not on a coarse grid node";
      return solution;
    }
  }
  std::array<std::vector<Vec3>, 3> levels;
  for (int level = 0; level < 3; ++level) {
    solution.error = SolveOnGrid(problem, n << level, &levels[level]);
    if (!solution.error.empty()) return solution;
  }
  solution.displacement.assign(n + 1, Vec3::Zero());
  double change = 0.0;
  for (int k = 0; k <= n; ++k) {
    const Vec3& a = levels[0][k];
    const Vec3& b = levels[1][2 * k];
    const Vec3& c = levels[2][4 * k];
    const Vec3 ab = (4.0 * b - a) / 3.0;  // h^2 removed
    const Vec3 bc = (4.0 * c - b) / 3.0;
    const Vec3 abc = (16.0 * bc - ab) / 15.0;  // h^4 removed
    solution.displacement[k] = abc;
    change = std::max(change, (abc - bc).cwiseAbs().maxCoeff());
  }
  solution.change_estimate = change;
  return solution;
}

FdBeamSolution SolveFdBeamRichardson(const FdScalarBeamProblem& problem, int n) {
  const ScalarAs3d p(problem);
  return ToScalar(SolveFdBeamRichardson(p.problem, n));
}

}  // namespace wirerig::testing
