// Internal to the runtime: scalar root finding without allocation, for the shooting solves
// (corotational_wire.cpp). f(x, &fx) evaluates f at x and returns false if it cannot.
#pragma once

#include <algorithm>
#include <cmath>

namespace wirerig::detail {

// Brent's method (zeroin) for f(x) = 0 on [a, b], f(a) and f(b) of opposite signs (or one
// zero). Returns false if f fails.
template <typename F>
bool Brent(F&& f, double a, double b, double fa, double fb, double abs_tol, double* root) {
  if (fa == 0.0) {
    *root = a;
    return true;
  }
  double c = a, fc = fa, d = b - a, e = d;
  for (int iter = 0; iter < 200; ++iter) {
    if ((fb > 0.0) == (fc > 0.0)) {
      c = a;
      fc = fa;
      d = e = b - a;
    }
    if (std::abs(fc) < std::abs(fb)) {
      a = b;
      b = c;
      c = a;
      fa = fb;
      fb = fc;
      fc = fa;
    }
    const double tol = 2.0 * 2.2e-16 * std::abs(b) + abs_tol;
    const double m = 0.5 * (c - b);
    if (std::abs(m) <= tol || fb == 0.0) break;
    if (std::abs(e) >= tol && std::abs(fa) > std::abs(fb)) {
      double p, q;
      const double s = fb / fa;
      if (a == c) {
        p = 2.0 * m * s;
        q = 1.0 - s;
      } else {
        const double qq = fa / fc, r = fb / fc;
        p = s * (2.0 * m * qq * (qq - r) - (b - a) * (r - 1.0));
        q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0.0)
        q = -q;
      else
        p = -p;
      if (2.0 * p < std::min(3.0 * m * q - std::abs(tol * q), std::abs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = m;
        e = m;
      }
    } else {
      d = m;
      e = m;
    }
    a = b;
    fa = fb;
    b += std::abs(d) > tol ? d : (m > 0.0 ? tol : -tol);
    if (!f(b, &fb)) return false;
  }
  *root = b;
  return true;
}

// The root of g nearest `guess` on the side its sign points to, for g increasing through its
// roots (as the chain's tip residual does with the root moment: more moment, more turn): a
// positive g(guess) searches downwards.
// Each probe steps by the secant's prediction from the last two points, overshooting by 10% to
// bracket the root in one step where g is close to linear (doubling steps from `step` where the
// secant is unusable), never farther than `reach`; then Brent on the bracket.
template <typename F>
bool NearestRoot(F&& g, double guess, double step, double reach, double abs_tol, double* root) {
  double x0 = guess, g0 = 0.0;
  if (!g(x0, &g0)) return false;
  if (g0 == 0.0) {
    *root = x0;
    return true;
  }
  const double direction = g0 > 0.0 ? -1.0 : 1.0;
  double xp = 0.0, gp = 0.0;
  bool have_previous = false;
  double doubling = step;
  for (int probe = 0; probe < 100; ++probe) {
    double dx = doubling;
    const double slope = have_previous ? (g0 - gp) / (x0 - xp) : 0.0;
    if (have_previous && slope > 0.0)
      dx = std::max(1.1 * std::abs(g0 / slope), 1e-3 * step);
    else
      doubling *= 2.0;
    dx = std::min(dx, reach);
    const double x1 = x0 + direction * dx;
    double g1 = 0.0;
    if (!g(x1, &g1)) return false;
    if ((g1 > 0.0) != (g0 > 0.0) || g1 == 0.0) return Brent(g, x0, x1, g0, g1, abs_tol, root);
    if (std::abs(x1 - guess) >= reach) return false;
    xp = x0;
    gp = g0;
    x0 = x1;
    g0 = g1;
    have_previous = true;
  }
  return false;
}

}  // namespace wirerig::detail
