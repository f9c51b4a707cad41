// Finite-difference reference for wire bending, EI X''''(s) = p(s) on s in [0, L].
//
// An independent check of BendingJob: it shares no code and no formula with the closed form
// (PHYSICS.md section 2). Each component of X is solved on a uniform grid of N intervals,
// h = L/N, with the standard 5-point stencil
//   EI (X[k-2] - 4 X[k-1] + 6 X[k] - 4 X[k+1] + X[k+2]) / h^4 = p[k]
// and ghost nodes for the boundary conditions (central differences):
//   X(0) = X0 always (node 0 is not an unknown);
//   simply supported end  X'' = 0:              X[-1] = 2 X[0] - X[1]
//   clamped end           X'  = 0:              X[-1] = X[1]
//   free end (s = L)      X'' = 0, EI X''' = -F: X[N+1] = 2 X[N] - X[N-1],
//                         X[N+2] = 2 X[N+1] - 2 X[N-1] + X[N-2] - 2 h^3 F/EI
//   guided end (s = L)    X'  = 0, EI X''' = -F: X[N+1] = X[N-1], X[N+2] likewise.
// (The same relations mirrored at s = L for simply supported and clamped wires, X(L) = X1.)
//
// Loads: a point load P at node k becomes p[k] = P/h; a uniform patch load q over [a, b] gives
// p[k] = q strictly inside, q/2 at an interior end node, and q at a free or guided end node
// (the one-sided value there); a linearly varying load gives its value p(s_k) likewise (half
// of it at an interior end node). For a linear load the nodal residuals near its ends are
// r h/120, 7 r h/30, r h/120 (r its slope, a symmetric pattern), so the error stays even in h.
// Loads on a node with a prescribed displacement are taken by the support; a point load on a
// cantilever's end node is added to the tip force. Every load position must lie on a node of the
// coarsest grid; otherwise the solve fails with a message.
//
// Accuracy: every truncation error of this scheme is even in h, so the error is
// c2 h^2 + c4 h^4 + c6 h^6 + ...; two Richardson levels over N = n, 2n, 4n remove the h^2 and
// h^4 terms. (For point and patch loads the exact solution is piecewise polynomial and the
// nodal error turns out to be exactly c2 h^2, so the extrapolation is exact up to rounding.)
// Rounding: the stencil's condition number grows as N^4 (about 1e10 at N = 400); a plain
// LU solve then loses up to 1e-5 relative at N = 400 and 6e-8 after extrapolation at n = 100.
// So each solve is refined iteratively, with the right-hand side and the residual kept in long
// double. Measured against textbook formulas at n = 100: a single solve is 5e-5 to 8e-4
// relative (O(h^2)); the extrapolated reference is within 1e-14 of max |X|, and within 3e-13
// against a 40-digit evaluation in random multi-load cases (see TEST(FdBeamReference, ...) in
// tests/runtime/bending_reference_test.cpp).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/loads.h"

namespace wirerig::testing {

// A lateral bending problem in 3D; each component is solved independently with the same
// (once factored) matrix. Types and meanings follow BendingJob: v in [0, 1], s = L v.
struct FdBeamProblem {
  BoundaryCondition boundary = BoundaryCondition::kSimplySupported;
  double length = 1.0;                     // L > 0, m
  double bending_stiffness = 1.0;          // EI > 0, N*m^2
  Vec3 start_displacement = Vec3::Zero();  // X0, m
  Vec3 end_displacement = Vec3::Zero();    // X1, m; ignored by cantilevers
  Vec3 tip_force = Vec3::Zero();           // F at v = 1, N; cantilevers only (EI X'''(L) = -F)
  std::span<const PointLoad> point_loads;  // positions on grid nodes
  std::span<const LineLoad> line_loads;    // from < to, both on grid nodes
  std::span<const LinearLineLoad> linear_line_loads;  // from < to, both on grid nodes
};

// The same problem for one scalar component.
struct FdScalarPointLoad {
  double at = 0.0;     // v in [0, 1]
  double force = 0.0;  // N
};
struct FdScalarLineLoad {
  double from = 0.0;              // v in [0, 1]
  double to = 1.0;                // v in [0, 1], from < to
  double force_per_length = 0.0;  // N/m
};
struct FdScalarLinearLineLoad {
  double from = 0.0;                    // v in [0, 1]
  double to = 1.0;                      // v in [0, 1], from < to
  double start_force_per_length = 0.0;  // N/m at v = from
  double end_force_per_length = 0.0;    // N/m at v = to
};
struct FdScalarBeamProblem {
  BoundaryCondition boundary = BoundaryCondition::kSimplySupported;
  double length = 1.0;
  double bending_stiffness = 1.0;
  double start_displacement = 0.0;
  double end_displacement = 0.0;
  double tip_force = 0.0;
  std::vector<FdScalarPointLoad> point_loads;
  std::vector<FdScalarLineLoad> line_loads;
  std::vector<FdScalarLinearLineLoad> linear_line_loads;
};

// Displacements X(v_k) at the nodes v_k = k/n, k = 0..n, or an error message.
struct FdBeamSolution {
  std::string error;               // empty on success
  std::vector<Vec3> displacement;  // n + 1 values (3D solvers)
  std::vector<double> scalar;      // n + 1 values (scalar solvers)
  // Richardson only: max over nodes and components of |last level - previous level|, m.
  // A rough upper bound of the remaining error.
  double change_estimate = 0.0;

  bool ok() const { return error.empty(); }
};

// One finite-difference solve on the grid of n intervals (n >= 4). O(h^2) accurate.
FdBeamSolution SolveFdBeam(const FdBeamProblem& problem, int n);
FdBeamSolution SolveFdBeam(const FdScalarBeamProblem& problem, int n);

// Solves on n, 2n and 4n intervals and extrapolates twice (h^2, then h^4) to the n + 1 coarse
// nodes v_k = k/n. Load positions must lie on nodes of the n grid.
FdBeamSolution SolveFdBeamRichardson(const FdBeamProblem& problem, int n);
FdBeamSolution SolveFdBeamRichardson(const FdScalarBeamProblem& problem, int n);

}  // namespace wirerig::testing
