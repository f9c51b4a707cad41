// ModalBasis against independent references: published eigenvalues, a finite-difference
// eigenproblem of X'''' = lambda X (Eigen, dense), the textbook cosh/sinh mode shapes in long
// double, the boundary conditions, and orthonormality by composite Simpson quadrature.
#include "wirerig/runtime/modal_basis.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr BoundaryCondition kFamilies[] = {
    BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped,
    BoundaryCondition::kCantileverFree, BoundaryCondition::kCantileverGuided};

ModalBasis Build(BoundaryCondition bc, int modes) {
  ModalBasis basis;
  const Status status = BuildModalBasis(bc, modes, &basis);
  EXPECT_TRUE(status.ok()) << ToString(status);
  return basis;
}

TEST(ModalBasis, EigenvaluesMatchPublishedValues) {
  // Blevins, "Formulas for natural frequency and mode shape", table 8-1 (lambda_i).
  const ModalBasis cf = Build(BoundaryCondition::kCantileverFree, 8);
  EXPECT_NEAR(cf.beta[0], 1.875104, 1e-6);
  EXPECT_NEAR(cf.beta[1], 4.694091, 1e-6);
  EXPECT_NEAR(cf.beta[2], 7.854757, 1e-6);
  EXPECT_NEAR(cf.beta[3], 10.995541, 1e-6);
  const ModalBasis cc = Build(BoundaryCondition::kClamped, 8);
  EXPECT_NEAR(cc.beta[0], 4.730041, 1e-6);
  EXPECT_NEAR(cc.beta[1], 7.853205, 1e-6);
  EXPECT_NEAR(cc.beta[2], 10.995608, 1e-6);
  EXPECT_NEAR(cc.beta[3], 14.137165, 1e-6);
  const ModalBasis ss = Build(BoundaryCondition::kSimplySupported, 32);
  for (int n = 0; n < 32; ++n) EXPECT_DOUBLE_EQ(ss.beta[n], (n + 1) * std::numbers::pi);
  // Clamped-sliding (guided) beam: 2.365020, 5.497804 (Blevins table 8-1).
  const ModalBasis cg = Build(BoundaryCondition::kCantileverGuided, 8);
  EXPECT_NEAR(cg.beta[0], 2.365020, 1e-6);
  EXPECT_NEAR(cg.beta[1], 5.497804, 1e-6);
  // A guided end is a plane of symmetry: the guided modes are the symmetric modes (odd ones,
  // 1st, 3rd, ...) of a clamped wire of twice the length, beta_CG,n = beta_CC,2n-1 / 2.
  const ModalBasis cc16 = Build(BoundaryCondition::kClamped, 16);
  for (int n = 0; n < 8; ++n) EXPECT_NEAR(cg.beta[n], 0.5 * cc16.beta[2 * n], 1e-13);
  // Large-n asymptotes: (n + 1/2) pi, (n - 1/2) pi, (n - 1/4) pi.
  const ModalBasis cf32 = Build(BoundaryCondition::kCantileverFree, 32);
  const ModalBasis cc32 = Build(BoundaryCondition::kClamped, 32);
  const ModalBasis cg32 = Build(BoundaryCondition::kCantileverGuided, 32);
  EXPECT_NEAR(cc32.beta[31], 32.5 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(cf32.beta[31], 31.5 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(cg32.beta[31], 31.75 * std::numbers::pi, 1e-12);
}

// Smallest eigenvalues of the 5-point stencil of X'''' on N intervals, the boundary conditions
// by ghost nodes (central differences, as in support/fd_beam_reference.h).
std::vector<double> FiniteDifferenceEigenvalues(BoundaryCondition bc, int intervals, int count) {
  const bool ss = bc == BoundaryCondition::kSimplySupported;
  const bool end_fixed = ss || bc == BoundaryCondition::kClamped;
  const int unknowns = end_fixed ? intervals - 1 : intervals;  // nodes 1 .. unknowns
  const double h = 1.0 / intervals;
  // Node k as a combination of the unknowns.
  const auto node = [&](int k) {
    Eigen::VectorXd r = Eigen::VectorXd::Zero(unknowns);
    const auto unit = [&](int j, double c) {
      if (j >= 1 && j <= unknowns) r[j - 1] += c;
    };
    if (k == -1) {
      unit(1, ss ? -1.0 : 1.0);  // X'' = 0 or X' = 0 at v = 0 (X(0) = 0)
    } else if (k >= 1 && k <= unknowns) {
      unit(k, 1.0);
    } else if (k == intervals + 1) {
      switch (bc) {
        case BoundaryCondition::kSimplySupported:
          unit(intervals - 1, -1.0);
          break;
        case BoundaryCondition::kClamped:
        case BoundaryCondition::kCantileverGuided:
          unit(intervals - 1, 1.0);
          break;
        case BoundaryCondition::kCantileverFree:  // X'' = 0
          unit(intervals, 2.0);
          unit(intervals - 1, -1.0);
          break;
      }
    } else if (k == intervals + 2) {
      if (bc == BoundaryCondition::kCantileverGuided) {  // X''' = 0 with X' = 0
        unit(intervals - 2, 1.0);
      } else {  // free: X''' = 0 with X'' = 0
        unit(intervals, 4.0);
        unit(intervals - 1, -4.0);
        unit(intervals - 2, 1.0);
      }
    }
    return r;  // k = 0, or k = N on a fixed end: zero
  };
  Eigen::MatrixXd a(unknowns, unknowns);
  for (int k = 1; k <= unknowns; ++k)
    a.row(k - 1) =
        (node(k - 2) - 4.0 * node(k - 1) + 6.0 * node(k) - 4.0 * node(k + 1) + node(k + 2))
            .transpose() /
        (h * h * h * h);
  Eigen::EigenSolver<Eigen::MatrixXd> solver(a, false);
  std::vector<double> lambda;
  for (int i = 0; i < unknowns; ++i) lambda.push_back(solver.eigenvalues()[i].real());
  std::sort(lambda.begin(), lambda.end());
  lambda.resize(count);
  return lambda;
}

TEST(ModalBasis, EigenvaluesMatchFiniteDifferenceEigenproblem) {
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    const ModalBasis basis = Build(bc, 4);
    const std::vector<double> coarse = FiniteDifferenceEigenvalues(bc, 100, 4);
    const std::vector<double> fine = FiniteDifferenceEigenvalues(bc, 200, 4);
    double worst = 0.0;
    for (int n = 0; n < 4; ++n) {
      // The stencil's error is even in h: one Richardson level removes the h^2 term.
      const double lambda = (4.0 * fine[n] - coarse[n]) / 3.0;
      const double beta = std::pow(lambda, 0.25);
      EXPECT_NEAR(basis.beta[n], beta, 1e-5 * beta) << "mode " << n + 1;
      worst = std::max(worst, std::abs(basis.beta[n] / beta - 1.0));
    }
    std::printf("[measure] %s: beta_1..4 against the FD eigenproblem, worst %.1e relative\n",
                std::string(ToString(bc)).c_str(), worst);
  }
}

// The textbook form phi = cosh - cos - sigma (sinh - sin), in long double (good to ~1e-13 for
// beta < 15), normalised to integral 1 with phi''(0) = 2 beta^2 > 0 (Blevins table 8-1).
long double TextbookMode(BoundaryCondition bc, long double beta, long double v) {
  const long double b = beta, x = beta * v;
  long double sigma = 0.0L;
  if (bc == BoundaryCondition::kClamped)
    sigma = (std::cosh(b) - std::cos(b)) / (std::sinh(b) - std::sin(b));
  else  // cantilever free
    sigma = (std::sinh(b) - std::sin(b)) / (std::cosh(b) + std::cos(b));
  return std::cosh(x) - std::cos(x) - sigma * (std::sinh(x) - std::sin(x));
}

TEST(ModalBasis, ModesMatchTheTextbookShapes) {
  for (BoundaryCondition bc : {BoundaryCondition::kClamped, BoundaryCondition::kCantileverFree}) {
    SCOPED_TRACE(ToString(bc));
    const ModalBasis basis = Build(bc, 4);
    for (int n = 0; n < 4; ++n)
      for (int i = 0; i <= 50; ++i) {
        const double v = i / 50.0;
        EXPECT_NEAR(ModeValue(basis, n, v), double(TextbookMode(bc, basis.beta[n], v)), 1e-10)
            << "mode " << n + 1 << " v " << v;
      }
  }
  const ModalBasis ss = Build(BoundaryCondition::kSimplySupported, 32);
  for (int n = 0; n < 32; ++n)
    for (double v : {0.1, 0.37, 0.5, 0.93})
      EXPECT_NEAR(ModeValue(ss, n, v), std::sqrt(2.0) * std::sin((n + 1) * std::numbers::pi * v),
                  1e-13);
  // Cantilever free ends at phi(1) = +-2 (alternating).
  const ModalBasis cf = Build(BoundaryCondition::kCantileverFree, 32);
  for (int n = 0; n < 32; ++n) EXPECT_NEAR(ModeValue(cf, n, 1.0), n % 2 == 0 ? 2.0 : -2.0, 1e-11);
}

// phi^(k)(v) by central differences of ModeValue / ModeSlope (k = 2, 3).
double SecondDerivative(const ModalBasis& b, int n, double v, double h) {
  return (ModeSlope(b, n, v + h) - ModeSlope(b, n, v - h)) / (2.0 * h);
}
double ThirdDerivative(const ModalBasis& b, int n, double v, double h) {
  return (ModeSlope(b, n, v + h) - 2.0 * ModeSlope(b, n, v) + ModeSlope(b, n, v - h)) / (h * h);
}

TEST(ModalBasis, EveryModeMeetsItsBoundaryConditions) {
  // The derivatives at the ends, extended just outside [0, 1] (the closed form is analytic).
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    const ModalBasis basis = Build(bc, 32);
    for (int n = 0; n < 32; ++n) {
      SCOPED_TRACE(n);
      const double beta = basis.beta[n], h = 1e-4 / beta;
      // Scale: phi^(k) ~ beta^k. Differences lose digits: tolerances follow h.
      const double t0 = 1e-12, t1 = 1e-12 * beta, t2 = 1e-6 * beta * beta,
                   t3 = 1e-3 * beta * beta * beta;
      EXPECT_NEAR(ModeValue(basis, n, 0.0), 0.0, t0);
      if (bc == BoundaryCondition::kSimplySupported) {
        EXPECT_NEAR(SecondDerivative(basis, n, 0.0, h), 0.0, t2);
        EXPECT_GT(ModeSlope(basis, n, 0.0), 0.0);
      } else {
        EXPECT_NEAR(ModeSlope(basis, n, 0.0), 0.0, t1);
        EXPECT_GT(SecondDerivative(basis, n, 0.0, h), 0.0);
      }
      switch (bc) {
        case BoundaryCondition::kSimplySupported:
          EXPECT_NEAR(ModeValue(basis, n, 1.0), 0.0, t0);
          EXPECT_NEAR(SecondDerivative(basis, n, 1.0, h), 0.0, t2);
          break;
        case BoundaryCondition::kClamped:
          EXPECT_NEAR(ModeValue(basis, n, 1.0), 0.0, t0);
          EXPECT_NEAR(ModeSlope(basis, n, 1.0), 0.0, t1);
          break;
        case BoundaryCondition::kCantileverFree:
          EXPECT_NEAR(SecondDerivative(basis, n, 1.0, h), 0.0, t2);
          EXPECT_NEAR(ThirdDerivative(basis, n, 1.0, h), 0.0, t3);
          break;
        case BoundaryCondition::kCantileverGuided:
          EXPECT_NEAR(ModeSlope(basis, n, 1.0), 0.0, t1);
          EXPECT_NEAR(ThirdDerivative(basis, n, 1.0, h), 0.0, t3);
          break;
      }
    }
  }
}

// Composite Simpson on [0, 1] with `intervals` (even) intervals: the weights.
std::vector<double> SimpsonWeights(int intervals) {
  std::vector<double> w(intervals + 1);
  const double h = 1.0 / intervals;
  for (int i = 0; i <= intervals; ++i)
    w[i] = h / 3.0 * (i == 0 || i == intervals ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0));
  return w;
}

void ExpectOrthonormal(BoundaryCondition bc, int modes, int intervals, double tolerance) {
  SCOPED_TRACE(::testing::Message() << ToString(bc) << " N=" << modes);
  const ModalBasis basis = Build(bc, modes);
  const std::vector<double> w = SimpsonWeights(intervals);
  std::vector<double> v(intervals + 1);
  for (int i = 0; i <= intervals; ++i) v[i] = double(i) / intervals;
  std::vector<double> phi(v.size() * modes);
  ASSERT_TRUE(TabulateModes(basis, v, phi, {}).ok());
  double worst = 0.0;
  for (int m = 0; m < modes; ++m) {
    double integral = 0.0;
    for (int i = 0; i <= intervals; ++i) integral += w[i] * phi[i * modes + m];
    EXPECT_NEAR(basis.integral[m], integral, tolerance) << "integral of mode " << m + 1;
    for (int n = m; n < modes; ++n) {
      double dot = 0.0;
      for (int i = 0; i <= intervals; ++i) dot += w[i] * phi[i * modes + m] * phi[i * modes + n];
      worst = std::max(worst, std::abs(dot - (m == n ? 1.0 : 0.0)));
    }
  }
  EXPECT_LT(worst, tolerance);
  if (modes == 16 || modes == 32)
    std::printf("[measure] %s N=%d: orthonormality worst %.1e\n", std::string(ToString(bc)).c_str(),
                modes, worst);
}

TEST(ModalBasis, ModesAreOrthonormal) {
  // Simpson's error ~ h^4 (2 beta)^4 / 180: below 1e-11 for beta <= 52 at 20000 intervals.
  for (BoundaryCondition bc : kFamilies)
    for (int modes = 1; modes <= 16; ++modes) ExpectOrthonormal(bc, modes, 20000, 1e-8);
  // All 32 modes (beta up to 102: the cosh form would have lost every digit).
  for (BoundaryCondition bc : kFamilies) ExpectOrthonormal(bc, 32, 40000, 1e-8);
}

TEST(ModalBasis, IntegralMatchesQuadratureOverPatches) {
  const ModalBasis basis = Build(BoundaryCondition::kCantileverGuided, 12);
  const std::vector<double> w = SimpsonWeights(20000);
  for (int n = 0; n < 12; ++n)
    for (auto [a, b] : {std::pair{0.0, 0.3}, std::pair{0.25, 0.8}, std::pair{0.9, 1.0}}) {
      double integral = 0.0;
      for (int i = 0; i <= 20000; ++i)
        integral += w[i] * (b - a) * ModeValue(basis, n, a + (b - a) * i / 20000.0);
      EXPECT_NEAR(ModeIntegral(basis, n, a, b), integral, 1e-12);
    }
}

// The first moment about a, integral_a^b (v - a) phi_n dv, against composite Simpson on
// [a, b] (20000 intervals: error ~ h^4 beta^4 (b - a)^6 / 180, below 1e-13 here), for every
// family, all 32 modes, wide, narrow and end-touching stretches; the ramp integral is the
// moment over the width, and the basis's `moment` the moment over the whole wire.
TEST(ModalBasis, MomentMatchesQuadratureOverPatches) {
  const std::vector<double> w = SimpsonWeights(20000);
  double worst = 0.0;
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    const ModalBasis basis = Build(bc, 32);
    for (int n = 0; n < 32; ++n)
      for (auto [a, b] :
           {std::pair{0.0, 1.0}, std::pair{0.0, 0.3}, std::pair{0.25, 0.8}, std::pair{0.9, 1.0},
            std::pair{0.41, 0.415}, std::pair{0.6, 0.6 + 1e-7}}) {
        const double d = b - a;
        double moment = 0.0;
        for (int i = 0; i <= 20000; ++i) {
          const double t = i / 20000.0;
          moment += w[i] * d * (d * t) * ModeValue(basis, n, a + d * t);
        }
        // Relative to the size of the moment's terms, d^2 max|phi| (|phi| <= 2).
        const double scale = d * d;
        const double error = std::abs(ModeMoment(basis, n, a, b) - moment) / scale;
        worst = std::max(worst, error);
        EXPECT_LT(error, 1e-12) << "mode " << n + 1 << " on [" << a << ", " << b << "]";
        EXPECT_NEAR(ModeRampIntegral(basis, n, a, b), moment / d, 1e-12 * d)
            << "mode " << n + 1 << " on [" << a << ", " << b << "]";
      }
    for (int n = 0; n < 32; ++n) EXPECT_EQ(basis.moment[n], ModeMoment(basis, n, 0.0, 1.0));
    EXPECT_EQ(ModeMoment(basis, 3, 0.5, 0.5), 0.0);
    EXPECT_EQ(ModeRampIntegral(basis, 3, 0.5, 0.5), 0.0);
  }
  std::printf("[measure] ModeMoment vs Simpson: worst %.1e of (b - a)^2\n", worst);
}

// Where the kernels switch from their Taylor series to the closed forms (beta (b - a) = 1),
// the moment is continuous to rounding.
TEST(ModalBasis, MomentIsContinuousWhereItsKernelsSwitchForm) {
  const ModalBasis basis = Build(BoundaryCondition::kCantileverFree, 8);
  for (int n = 0; n < 8; ++n) {
    const double d = 1.0 / basis.beta[n];
    const double below = ModeMoment(basis, n, 0.1, 0.1 + std::nextafter(d, 0.0));
    const double at = ModeMoment(basis, n, 0.1, 0.1 + d);
    EXPECT_NEAR(below, at, 1e-14 * d * d) << "mode " << n + 1;
  }
}

TEST(ModalBasis, InvalidInputsAreNamed) {
  ModalBasis basis;
  EXPECT_EQ(BuildModalBasis(BoundaryCondition::kClamped, 0, &basis).field, "modes");
  EXPECT_EQ(BuildModalBasis(BoundaryCondition::kClamped, 33, &basis).field, "modes");
  EXPECT_EQ(BuildModalBasis(static_cast<BoundaryCondition>(7), 8, &basis).field, "boundary");
  EXPECT_EQ(BuildModalBasis(BoundaryCondition::kClamped, 8, nullptr).field, "out");
  EXPECT_TRUE(BuildModalBasis(BoundaryCondition::kClamped, 1, &basis).ok());
  EXPECT_TRUE(BuildModalBasis(BoundaryCondition::kClamped, 32, &basis).ok());

  const std::vector<double> v = {0.0, 0.5, 1.0};
  std::vector<double> values(3 * 32), slopes(3 * 32), short_table(5);
  EXPECT_EQ(TabulateModes(ModalBasis(), v, values, {}).field, "basis");
  EXPECT_EQ(TabulateModes(basis, {}, values, {}).field, "samples");
  const std::vector<double> outside = {0.5, 1.5};
  EXPECT_EQ(TabulateModes(basis, outside, values, {}).field, "samples");
  EXPECT_EQ(TabulateModes(basis, v, short_table, {}).field, "values");
  EXPECT_EQ(TabulateModes(basis, v, values, short_table).field, "slopes");
  EXPECT_TRUE(TabulateModes(basis, v, values, slopes).ok());
  EXPECT_NEAR(values[1 * 32 + 3], ModeValue(basis, 3, 0.5), 1e-14);
  EXPECT_NEAR(slopes[2 * 32 + 5], ModeSlope(basis, 5, 1.0), 1e-14 * basis.beta[5]);
}

TEST(ModalBasis, EvaluateModeGivesValueAndSlopeTogether) {
  for (BoundaryCondition bc : kFamilies) {
    const ModalBasis basis = Build(bc, 32);
    for (int n = 0; n < 32; ++n)
      for (int i = 0; i <= 20; ++i) {
        const double v = i / 20.0;
        double value = 0.0, slope = 0.0;
        EvaluateMode(basis, n, v, &value, &slope);
        EXPECT_NEAR(value, ModeValue(basis, n, v), 1e-14);
        EXPECT_NEAR(slope, ModeSlope(basis, n, v), 1e-14 * basis.beta[n]);
      }
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
