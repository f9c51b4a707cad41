// Independent references for large planar deflections of a cantilever clamped at the origin
// with its tangent along +X (never the code under test):
//   - the exact elastica under a dead tip force of direction beta (elliptic integrals), and
//   - a numerical shooting solve of the elastica ODE by RK4 with fine steps.
//
// Elastica with a tip force F at angle beta from +X: theta(s) is the tangent angle, and with
// phi = beta - theta the moment balance gives EI phi'' = F sin(phi), theta(0) = 0, theta'(L) = 0.
// Its first integral, phi'^2 = 2F/EI (cos phi_L - cos phi), with the substitution
// cos(phi/2) = k sin(u), k = cos(phi_L/2) (Bisshopp & Drucker 1945; Timoshenko & Gere 1961),
// gives, for a tip rotation theta_L (no inflection, 0 < phi_L = beta - theta_L <= beta):
//   lambda L = K(k) - F(k, u1),   lambda = sqrt(F/EI),   sin(u1) = cos(beta/2) / k,
//   along the force:  a = [lambda L - 2 (E(k) - E(k, u1))] / lambda,
//   across it:        b = -2 k cos(u1) / lambda        (along e_perp = (-sin beta, cos beta)).
// For beta = pi/2 this is the classic k = sin(pi/4 + theta_L/2), sin(u1) = 1/(sqrt(2) k).
#pragma once

#include <cmath>
#include <functional>

namespace wirerig::testing {

struct ElasticaTip {
  double alpha = 0.0;  // F L^2 / EI
  double x = 0.0;      // tip position / L
  double y = 0.0;
};

// The exact elastica: the load that rotates the tip by tip_rotation, and the tip position.
inline ElasticaTip ExactElasticaTip(double beta, double tip_rotation) {
  const double phi_l = beta - tip_rotation;
  const double k = std::cos(phi_l / 2.0);
  const double u1 = std::asin(std::cos(beta / 2.0) / k);
  const double lambda_l = std::comp_ellint_1(k) - std::ellint_1(k, u1);
  const double a = (lambda_l - 2.0 * (std::comp_ellint_2(k) - std::ellint_2(k, u1))) / lambda_l;
  const double b = -2.0 * k * std::cos(u1) / lambda_l;
  ElasticaTip tip;
  tip.alpha = lambda_l * lambda_l;
  tip.x = a * std::cos(beta) - b * std::sin(beta);
  tip.y = a * std::sin(beta) + b * std::cos(beta);
  return tip;
}

// State of the planar elastica ODE at arc length s.
struct ElasticaState {
  double theta = 0.0, kappa = 0.0, x = 0.0, y = 0.0;
};

// Integrates theta' = kappa, EI kappa' = dmoment(s, state), x' = cos theta, y' = sin theta from
// the clamped root with curvature kappa0 over [0, L] by RK4 in `steps` steps.
// dmoment is dM/ds of the internal moment M = EI kappa.
inline ElasticaState IntegrateElastica(
    double length, double ei, double kappa0, int steps,
    const std::function<double(double, const ElasticaState&)>& dmoment) {
  auto rhs = [&](double s, const ElasticaState& q) {
    return ElasticaState{q.kappa, dmoment(s, q) / ei, std::cos(q.theta), std::sin(q.theta)};
  };
  auto add = [](const ElasticaState& q, const ElasticaState& d, double f) {
    return ElasticaState{q.theta + f * d.theta, q.kappa + f * d.kappa, q.x + f * d.x,
                         q.y + f * d.y};
  };
  ElasticaState q{0.0, kappa0, 0.0, 0.0};
  const double h = length / steps;
  for (int i = 0; i < steps; ++i) {
    const double s = i * h;
    const ElasticaState k1 = rhs(s, q);
    const ElasticaState k2 = rhs(s + h / 2, add(q, k1, h / 2));
    const ElasticaState k3 = rhs(s + h / 2, add(q, k2, h / 2));
    const ElasticaState k4 = rhs(s + h, add(q, k3, h));
    q.theta += h / 6 * (k1.theta + 2 * k2.theta + 2 * k3.theta + k4.theta);
    q.kappa += h / 6 * (k1.kappa + 2 * k2.kappa + 2 * k3.kappa + k4.kappa);
    q.x += h / 6 * (k1.x + 2 * k2.x + 2 * k3.x + k4.x);
    q.y += h / 6 * (k1.y + 2 * k2.y + 2 * k3.y + k4.y);
  }
  return q;
}

// Shooting on the root curvature: bisection on [kappa_lo, kappa_hi] until the free tip has
// zero curvature (kappa(L) = 0). The caller checks that the bracket changes sign.
inline ElasticaState ShootElastica(
    double length, double ei, double kappa_lo, double kappa_hi, int steps,
    const std::function<double(double, const ElasticaState&)>& dmoment) {
  double lo = kappa_lo, hi = kappa_hi;
  const double f_lo = IntegrateElastica(length, ei, lo, steps, dmoment).kappa;
  for (int i = 0; i < 80 && hi - lo > 1e-15 * (std::abs(lo) + std::abs(hi)); ++i) {
    const double mid = 0.5 * (lo + hi);
    const double f = IntegrateElastica(length, ei, mid, steps, dmoment).kappa;
    if ((f > 0.0) == (f_lo > 0.0))
      lo = mid;
    else
      hi = mid;
  }
  return IntegrateElastica(length, ei, 0.5 * (lo + hi), steps, dmoment);
}

// The elastica ODE for a dead tip force F at angle beta: dM/ds = -F sin(beta - theta), shot
// over the root curvature bracket [kappa_lo, kappa_hi] (large loads also admit looped
// equilibria: the bracket picks the branch).
inline ElasticaState ShootTipForceElastica(double length, double ei, double force, double beta,
                                           double kappa_lo, double kappa_hi, int steps = 20000) {
  return ShootElastica(length, ei, kappa_lo, kappa_hi, steps, [&](double, const ElasticaState& q) {
    return -force * std::sin(beta - q.theta);
  });
}

}  // namespace wirerig::testing
