// Clamped-plate reference for the chest sample (paper Fig. 3; PHYSICS.md section 5).
//
// Solves the biharmonic plate equation (PHYSICS.md Eq. 19, corrected)
//   D (S_xxxx + 2 S_xxyy + S_yyyy) = q      on the rectangle [0, a] x [0, b],
//   S = 0 and dS/dn = 0                      on all four edges (clamped, Eq. 20),
// for a uniform pressure q by finite differences on a uniform grid of n intervals per side,
// hx = a/n, hy = b/n, nodes (x_i, y_j) = (i hx, j hy), i, j = 0..n. In the normalised
// coordinates of the paper, u = x/a and v = y/b.
//
// Stencil (13 points): the central differences of each fourth-order term at interior node
// (i, j), with alpha = 1/hx^4, beta = 1/hy^4, gamma = 1/(hx^2 hy^2):
//   S(i, j)                 6 alpha + 6 beta + 8 gamma
//   S(i +- 1, j)           -4 alpha - 4 gamma
//   S(i, j +- 1)           -4 beta  - 4 gamma
//   S(i +- 2, j)              alpha
//   S(i, j +- 2)              beta
//   S(i +- 1, j +- 1)       2 gamma
// i.e. the matrix K_x (x) I + 2 L_x (x) L_y + I (x) K_y of PHYSICS.md section 5, where L is the
// second-difference matrix with Dirichlet ends and K = L^2 + 2 (e_1 e_1^T + e_m e_m^T)/h^4.
//
// Boundary conditions: the edge nodes are not unknowns (S = 0); dS/dn = 0 enters through
// ghost nodes one spacing outside each edge, mirrored by the central difference
// S(-1, j) = S(1, j) and S(n+1, j) = S(n-1, j) (likewise in y). Only the +-2 terms of nodes next
// to an edge reach a ghost; the corner terms reach edge nodes only (zero).
//
// The matrix is symmetric positive definite, (n-1)^2 unknowns; it is factored with Eigen's
// SimplicialLDLT (AMD ordering). The error is O(h^2): the square's centre deflection is
// 0.0012701, 0.0012665 q a^4/D at n = 48, 96 against 0.00126532 (PHYSICS.md), and a
// Richardson step (4 S_2n - S_n)/3 removes the h^2 term. n = 96 solves in about 0.1 s.
#pragma once

#include <cstddef>
#include <vector>

#include "wirerig/runtime/status.h"

namespace wirerig::chest {

struct PlateProblem {
  // Largest accepted grid, n: (n - 1)^2 unknowns and their fill-in stay below ~1 GB.
  static constexpr int kMaxIntervals = 1024;

  double width = 1.0;              // a, extent along x (u = x/a), m; > 0
  double length = 1.0;             // b, extent along y (v = y/b), m; > 0
  double flexural_rigidity = 1.0;  // D = E h^3 / (12 (1 - nu^2)), N m; > 0
  double pressure = 1.0;           // q, uniform load, N/m^2, positive along the deflection
  int intervals = 48;              // n per side, 4 <= n <= kMaxIntervals

  // Names the first invalid field: non-finite or non-positive sizes and rigidity, a
  // non-finite pressure, or n outside [4, kMaxIntervals].
  Status Validate() const;
};

// The deflection on the (n + 1) x (n + 1) grid nodes, edges included (zero there), along the
// load: S > 0 where q > 0.
struct PlateSolution {
  PlateProblem problem;
  std::vector<double> deflection;  // (n + 1)^2 values, index i * (n + 1) + j; m

  int intervals() const { return problem.intervals; }
  // S at node (i, j), x = i a/n, y = j b/n; 0 <= i, j <= n.
  double At(int i, int j) const {
    return deflection[static_cast<std::size_t>(i) * static_cast<std::size_t>(intervals() + 1) +
                      static_cast<std::size_t>(j)];
  }
  // Bilinear interpolation at normalised (u, v), each clamped to [0, 1].
  double Sample(double u, double v) const;
  // S at the centre (u, v) = (1/2, 1/2) (a node when n is even).
  double Centre() const { return Sample(0.5, 0.5); }
  // Largest |S| over the grid.
  double Peak() const;
};

// Assembles and solves the plate problem. On failure `out` is left unchanged and the Status
// names the invalid field (or "intervals" if the factorisation fails).
Status SolveClampedPlate(const PlateProblem& problem, PlateSolution* out);

// Richardson extrapolation of an O(h^2) quantity from grids n and 2n: (4 f_2n - f_n) / 3.
inline double RichardsonH2(double coarse, double fine) { return (4.0 * fine - coarse) / 3.0; }

// Centre deflection of the clamped square plate under uniform load, in units of q a^4 / D
// (PHYSICS.md section 5; Timoshenko gives 0.00126).
inline constexpr double kClampedSquareCentre = 0.00126532;

}  // namespace wirerig::chest
