#include "wirerig/runtime/corotational_wire_ik.h"

#include <algorithm>
#include <cmath>

namespace wirerig {
namespace {

struct Vec2 {
  double x = 0.0, y = 0.0;
};
Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
double Dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
double Norm(Vec2 a) { return std::hypot(a.x, a.y); }

// The wire job the search runs: no outputs, fixed K, a tip force of at most max_force.
CorotationalWireJob SearchWire(const CorotationalWireIkJob& ik) {
  CorotationalWireJob wire = ik.wire;
  wire.samples = {};
  wire.position = {};
  wire.tangent = {};
  wire.result = nullptr;
  wire.warm_start = false;
  if (wire.segments == 0) {
    wire.tip_force = Vec3(0.0, ik.max_force, 0.0);
    wire.segments = AutomaticSegmentCount(wire);
  }
  return wire;
}

// Chain solves for the search. A new force is solved from the straight wire (load
// continuation), which keeps every accepted point on the natural branch: warm-starting across
// large steps can follow an equilibrium the continuation would not reach (e.g. buckled against
// the lateral part of a compressive force). The difference steps, tiny, warm-start from the
// accepted point's root moment.
struct TipFunction {
  CorotationalWireJob wire;
  double accepted_moment = 0.0;
  bool have_moment = false;
  int solves = 0;

  // The tip for force f; its root moment in *moment. False if the chain fails.
  bool Tip(Vec2 f, bool warm, Vec2* tip, double* moment) {
    wire.tip_force = Vec3(f.x, f.y, 0.0);
    wire.warm_start = warm && have_moment;
    wire.root_moment_guess = accepted_moment;
    CorotationalWireResult r;
    wire.result = &r;
    ++solves;
    if (!wire.Run()) return false;
    *tip = {r.tip_position.x(), r.tip_position.y()};
    *moment = r.root_moment;
    return true;
  }
  void Accept(double moment) {
    accepted_moment = moment;
    have_moment = true;
  }
};

// Central-difference Jacobian d tip / d F (columns: F_x, F_y).
bool Jacobian(TipFunction* fn, Vec2 f, double step, Vec2* jx, Vec2* jy) {
  Vec2 plus, minus;
  double m = 0.0;
  if (!fn->Tip(f + Vec2{step, 0.0}, true, &plus, &m) ||
      !fn->Tip(f - Vec2{step, 0.0}, true, &minus, &m))
    return false;
  *jx = (0.5 / step) * (plus - minus);
  if (!fn->Tip(f + Vec2{0.0, step}, true, &plus, &m) ||
      !fn->Tip(f - Vec2{0.0, step}, true, &minus, &m))
    return false;
  *jy = (0.5 / step) * (plus - minus);
  return true;
}

Vec2 Project(Vec2 f, double max_force) {
  const double n = Norm(f);
  return n > max_force ? (max_force / n) * f : f;
}

}  // namespace

Status CorotationalWireIkJob::Validate() const {
  if (Status s = wire.Validate(); !s) return s;
  if (!(std::isfinite(max_force) && max_force > 0.0))
    return Status::Invalid("max_force", "must be positive and finite (N)");
  // Every force of the search (up to max_force, plus the difference steps) must be valid for K.
  CorotationalWireJob worst = SearchWire(*this);
  worst.tip_force = Vec3(0.0, 1.01 * max_force, 0.0);
  if (Status s = worst.Validate(); !s)
    return s.field == "segments" ? Status::Invalid("max_force", "too large for the wire's segments")
                                 : Status::Invalid("max_force", s.reason);
  if (!(std::isfinite(target.x()) && std::isfinite(target.y()) && target.z() == 0.0) ||
      !(target.norm() < 1e10 * wire.length))
    return Status::Invalid("target", "must be finite with z = 0 (m, planar)");
  if (!(std::isfinite(tolerance) && tolerance > 0.0 && tolerance <= 1e-3))
    return Status::Invalid("tolerance", "must lie in (0, 1e-3]");
  if (max_iterations < 1 || max_iterations > 1000)
    return Status::Invalid("max_iterations", "must lie in [1, 1000]");
  if (result == nullptr) return Status::Invalid("result", "must not be null");
  return Status::Ok();
}

Status CorotationalWireIkJob::Run() const {
  if (Status s = Validate(); !s) return s;
  const double length = wire.length, ei = wire.bending_stiffness;
  const Vec2 goal{target.x(), target.y()};
  TipFunction fn{SearchWire(*this)};

  // First guess: the wire's tip force, or the linear cantilever's for the lateral offset.
  Vec2 f{wire.tip_force.x(), wire.tip_force.y()};
  if (f.x == 0.0 && f.y == 0.0) f = {0.0, 3.0 * ei * goal.y / (length * length * length)};
  f = Project(f, max_force);

  Vec2 tip;
  double moment = 0.0;
  if (!fn.Tip(f, false, &tip, &moment))
    return Status::Invalid("wire", "the chain did not converge for the first guess");
  fn.Accept(moment);
  Vec2 r = tip - goal;
  const double force_scale = ei / (length * length);
  double mu = 1e-3;
  int iteration = 0;
  for (; iteration < max_iterations && Norm(r) > tolerance * length; ++iteration) {
    const double step = 1e-6 * std::max(Norm(f), force_scale);
    Vec2 jx, jy;
    if (!Jacobian(&fn, f, step, &jx, &jy)) break;
    // Normal equations A d = -b, A = J^T J, b = J^T r.
    const double a11 = Dot(jx, jx), a12 = Dot(jx, jy), a22 = Dot(jy, jy);
    const Vec2 b{Dot(jx, r), Dot(jy, r)};
    const double trace = a11 + a22;
    if (!(trace > 0.0)) break;
    // On the force bound with the miss falling outwards: search along the bound's circle.
    const double f_norm = Norm(f);
    const bool on_bound = f_norm >= max_force * (1.0 - 1e-12);
    const Vec2 outward = on_bound ? (1.0 / f_norm) * f : Vec2{};
    const bool along_bound = on_bound && Dot(b, outward) < 0.0;
    bool accepted = false;
    for (int attempt = 0; attempt < 30 && !accepted; ++attempt) {
      Vec2 trial;
      if (along_bound) {
        // F = max_force (cos psi, sin psi): d tip / d psi = J (max_force * tangent).
        const Vec2 t{-outward.y, outward.x};
        const Vec2 j_psi = max_force * Vec2{jx.x * t.x + jy.x * t.y, jx.y * t.x + jy.y * t.y};
        const double a = Dot(j_psi, j_psi);
        if (!(a > 0.0)) break;
        const double dpsi = -Dot(j_psi, r) / (a * (1.0 + mu));
        const double psi = std::atan2(f.y, f.x) + dpsi;
        trial = {max_force * std::cos(psi), max_force * std::sin(psi)};
      } else {
        const double damp = mu * 0.5 * trace;
        const double m11 = a11 + damp, m22 = a22 + damp;
        const double det = m11 * m22 - a12 * a12;
        if (!(det > 0.0)) break;
        const Vec2 d{-(m22 * b.x - a12 * b.y) / det, -(m11 * b.y - a12 * b.x) / det};
        trial = Project(f + d, max_force);
      }
      Vec2 trial_tip;
      double trial_moment = 0.0;
      if (fn.Tip(trial, false, &trial_tip, &trial_moment) && Norm(trial_tip - goal) < Norm(r)) {
        f = trial;
        r = trial_tip - goal;
        fn.Accept(trial_moment);
        mu = std::max(mu / 3.0, 1e-12);
        accepted = true;
      } else {
        mu *= 4.0;
      }
    }
    if (!accepted) break;  // no step lowers the miss: the closest point found
  }

  // Final chain with the solved force (and the caller's samples, if any).
  CorotationalWireJob final_wire = fn.wire;
  final_wire.samples = wire.samples;
  final_wire.position = wire.position;
  final_wire.tangent = wire.tangent;
  final_wire.tip_force = Vec3(f.x, f.y, 0.0);
  final_wire.warm_start = false;
  CorotationalWireResult chain;
  final_wire.result = &chain;
  if (Status s = final_wire.Run(); !s) return s;

  CorotationalWireIkResult& out = *result;
  out = CorotationalWireIkResult{};
  out.tip_force = final_wire.tip_force;
  out.reached = chain.tip_position;
  out.miss = (chain.tip_position - target).norm();
  out.reached_target = out.miss <= tolerance * length;
  out.force_limited = !out.reached_target && Norm(f) >= max_force * (1.0 - 1e-9);
  out.beyond_length = target.norm() >= length;
  out.root_moment = chain.root_moment;
  out.iterations = iteration;
  out.chain_solves = fn.solves + 1;
  return Status::Ok();
}

}  // namespace wirerig
