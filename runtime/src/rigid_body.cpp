#include "wirerig/runtime/rigid_body.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <Eigen/Eigenvalues>

#include "validation.h"

namespace wirerig {
namespace {

using Vec4 = Eigen::Vector4d;

// Elementwise: Eigen's allFinite() computes x - x, which raises FE_INVALID on infinities.
bool AllFinite(const Vec3& x) {
  return std::isfinite(x.x()) && std::isfinite(x.y()) && std::isfinite(x.z());
}
bool AllFinite(const Quat& q) {
  return std::isfinite(q.w()) && std::isfinite(q.x()) && std::isfinite(q.y()) &&
         std::isfinite(q.z());
}
double MaxAbs(const Vec3& x) {
  return std::max({std::abs(x.x()), std::abs(x.y()), std::abs(x.z())});
}

// ---------------------------------------------------------------------------------------
// Saturating arithmetic on non-negative bounds: results never exceed kSaturated, and no
// operation overflows whatever its (finite, non-negative) operands. Branch-free, so that no
// compiler can speculate an overflowing product past a guard.
constexpr double kSaturated = 1e300;

double Sat(double a) { return std::min(a, kSaturated); }
double SatAdd(double a, double b) { return Sat(Sat(a) + Sat(b)); }
double SatMul(double a, double b) {
  b = Sat(b);
  return Sat(std::min(Sat(a), kSaturated / std::max(b, 1.0)) * b);
}
// b > 0.
double SatDiv(double a, double b) {
  a = Sat(a);
  return Sat(a / std::max(b, a / kSaturated));
}

// ---------------------------------------------------------------------------------------
// Mass properties.

// Coordinates are bounded so that fifth powers of the extent (second moments of a volume)
// stay far from overflow.
constexpr double kMaxCoordinate = 1e50;
// A closed surface has zero vector area; an opening leaves its own vector area behind. The
// misfit accepted, relative to the total area, covers round-off and hairline cracks.
constexpr double kMaxRelativeOpening = 1e-6;
// Bound on the mass and every inertia component (kg, kg m^2).
constexpr double kMaxInertia = 1e290;

// Triangles present with indices in range; every position finite and within kMaxCoordinate.
Status CheckSurface(std::span<const Vec3> positions, std::span<const Triangle> triangles) {
  if (triangles.empty()) return Status::Invalid("triangles", "needs at least one triangle");
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (std::uint32_t v : triangles[i])
      if (v >= positions.size())
        return Status::InvalidElement("triangles", static_cast<int>(i), "",
                                      "vertex index out of range");
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (!AllFinite(positions[i]))
      return Status::InvalidElement("positions", static_cast<int>(i), "", "must be finite (m)");
    if (MaxAbs(positions[i]) > kMaxCoordinate)
      return Status::InvalidElement("positions", static_cast<int>(i), "",
                                    "must lie within 1e50 m of the origin");
  }
  return Status::Ok();
}

// The centre of the bounding box of the referenced vertices (the reference point all sums
// are taken about, for precision far from the origin) and its half extent.
struct Frame {
  Vec3 reference;
  double half_extent;
};

Frame ReferenceFrame(std::span<const Vec3> positions, std::span<const Triangle> triangles) {
  Vec3 lo = positions[triangles[0][0]], hi = lo;
  for (const Triangle& t : triangles)
    for (std::uint32_t v : t) {
      lo = lo.cwiseMin(positions[v]);
      hi = hi.cwiseMax(positions[v]);
    }
  return {0.5 * (lo + hi), 0.5 * MaxAbs(hi - lo)};
}

// a a^T + b b^T + c c^T + s s^T with s = a + b + c.
Mat3 VertexMoments(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 s = a + b + c;
  return a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose();
}

// Fills *out from the measure (volume or area), the first moment and the second moment
// about the reference point, the density per unit measure and the volume to report.
// Returns false if the centre falls outside the (doubled) bounding box, which only a
// degenerate surface can cause.
bool Finish(const Frame& frame, double measure, const Vec3& first, const Mat3& second,
            double density_per_measure, double volume, MassProperties* out) {
  const double limit = 2.0 * frame.half_extent * measure;
  if (!(std::abs(first.x()) <= limit && std::abs(first.y()) <= limit &&
        std::abs(first.z()) <= limit))
    return false;
  const Vec3 d = first / measure;  // centre relative to the reference point
  const Mat3 sigma = second - measure * (d * d.transpose());
  Mat3 inertia = density_per_measure * (sigma.trace() * Mat3::Identity() - sigma);
  inertia = 0.5 * (inertia + inertia.transpose());

  Eigen::SelfAdjointEigenSolver<Mat3> solver(inertia);
  if (solver.info() != Eigen::Success) return false;
  Mat3 axes = solver.eigenvectors();
  // Canonical signs (largest component positive) for the first two axes, then the third
  // completes a right-handed frame: det(axes) = +1.
  for (int k = 0; k < 2; ++k) {
    Eigen::Index largest = 0;
    axes.col(k).cwiseAbs().maxCoeff(&largest);
    if (axes(largest, k) < 0.0) axes.col(k) = -axes.col(k);
  }
  axes.col(2) = axes.col(0).cross(axes.col(1));

  out->volume = volume;
  out->mass = density_per_measure * measure;
  out->center = frame.reference + d;
  out->inertia = inertia;
  out->principal_axes = axes;
  out->principal_moments = solver.eigenvalues();
  return true;
}

// ---------------------------------------------------------------------------------------
// Rigid-body step.

// Bound on every position, velocity, angular velocity, momentum and energy a step may
// produce; squares of bounded quantities stay finite.
constexpr double kMaxMagnitude = 1e150;
// Accepted deviation of |q|^2 from 1 for the input orientation.
constexpr double kUnitTolerance = 1e-6;
// Fixed-point iterations for the midpoint angular velocity of the momentum form.
constexpr int kMidpointIterations = 3;
// Quaternions shorter than this (squared) are not normalised.
constexpr double kMinSquaredNorm = 1e-30;

Quat FromCoeffs(const Vec4& c) {
  Quat q;
  q.coeffs() = c;
  return q;
}

// The unit quaternion along c, or `fallback` if c is too short to have a direction (only
// possible for steps far too long for the motion).
Quat NormalizedOr(const Vec4& c, const Quat& fallback) {
  const double n2 = c.squaredNorm();
  if (!(n2 > kMinSquaredNorm)) return fallback;
  return FromCoeffs(c / std::sqrt(std::max(n2, kMinSquaredNorm)));
}

// exp of the rotation vector phi: the unit quaternion rotating by |phi| about phi.
Quat ExpMap(const Vec3& phi) {
  const double angle = phi.norm();
  // sin(angle/2)/angle, by its series where the quotient would lose precision.
  constexpr double kSeriesBelow = 1e-4;
  const double s = angle < kSeriesBelow ? 0.5 - angle * angle / 48.0
                                        : std::sin(0.5 * angle) / std::max(angle, kSeriesBelow);
  return Quat(std::cos(0.5 * angle), s * phi.x(), s * phi.y(), s * phi.z());
}

// Time derivatives of (q, omega_b): q_dot = 1/2 q (0, omega_b), and Euler's equations
// I_b omega_dot + omega_b x I_b omega_b = R^T torque.
void RotationRates(const Vec4& q, const Vec3& omega, const Vec3& torque_world, const Vec3& moments,
                   const Quat& fallback, Vec4* q_dot, Vec3* omega_dot) {
  const Vec3 torque_body = NormalizedOr(q, fallback).conjugate() * torque_world;
  *omega_dot = (torque_body - omega.cross(moments.cwiseProduct(omega))).cwiseQuotient(moments);
  *q_dot = 0.5 * (FromCoeffs(q) * Quat(0.0, omega.x(), omega.y(), omega.z())).coeffs();
}

// The rotation matrix of q, homogeneous in q (divided by |q|^2), or the identity for a
// quaternion too short to have a direction. Unlike Eigen's toRotationMatrix() and q * v, whose
// "1 - 2(y^2 + z^2)" form turns a rounding error of |q| into a scaling of the result, it has
// no bias: rotating L to the body and back, step after step, leaves |L| unchanged on average.
Mat3 RotationOf(const Quat& q) {
  const double w = q.w(), x = q.x(), y = q.y(), z = q.z();
  const double n2 = w * w + x * x + y * y + z * z;
  if (!(n2 > kMinSquaredNorm)) return Mat3::Identity();
  Mat3 r;
  r << w * w + x * x - y * y - z * z, 2.0 * (x * y - w * z), 2.0 * (x * z + w * y),
      2.0 * (x * y + w * z), w * w - x * x + y * y - z * z, 2.0 * (y * z - w * x),
      2.0 * (x * z - w * y), 2.0 * (y * z + w * x), w * w - x * x - y * y + z * z;
  return r / std::max(n2, kMinSquaredNorm);
}

// World angular velocity R I_b^-1 R^T L of a body at orientation q with momentum L.
Vec3 OmegaWorld(const Quat& q, const Vec3& moments, const Vec3& momentum) {
  const Mat3 r = RotationOf(q);
  return r * (r.transpose() * momentum).cwiseQuotient(moments);
}

// A priori bounds on every quantity the step computes (norms bounded by twice the largest
// component). True if they all stay below kMaxMagnitude.
bool StepIsBounded(const RigidBodyStepJob& job) {
  const RigidBodyState& s = *job.state;
  const double dt = job.dt;
  const double force =
      SatMul(2.0, std::max({MaxAbs(job.at_start.force), MaxAbs(job.at_middle.force),
                            MaxAbs(job.at_end.force)}));
  const double torque =
      SatMul(2.0, std::max({MaxAbs(job.at_start.torque), MaxAbs(job.at_middle.torque),
                            MaxAbs(job.at_end.torque)}));
  const double i_min = job.principal_moments.minCoeff();
  const double i_max = job.principal_moments.maxCoeff();

  // Translation (RK4 stages and the momentum form alike).
  const double v0 = SatMul(2.0, MaxAbs(s.velocity));
  const double v1 = SatAdd(v0, SatMul(dt, SatDiv(force, job.mass)));
  const double x1 = SatAdd(SatMul(2.0, MaxAbs(s.position)), SatMul(dt, SatAdd(v0, v1)));
  double worst = std::max({v1, x1, SatAdd(std::abs(s.time), dt), SatMul(job.mass, SatMul(v1, v1))});

  const double w0 = SatMul(2.0, MaxAbs(s.angular_velocity));
  double w_max = w0;
  if (job.integrator == RigidIntegrator::kRk4) {
    // Stage k at (q_k, omega_k) with |q_k| <= qk, |omega_k| <= wk:
    // |omega_dot| <= (T + I_max wk^2) / I_min, |q_dot| <= qk wk / 2.
    double qk = 1.0 + kUnitTolerance, wk = w0, q_rate = 0.0, w_rate = 0.0;
    for (int stage = 0; stage < 4; ++stage) {
      const double gyro = SatMul(i_max, SatMul(wk, wk));
      q_rate = std::max(q_rate, SatMul(0.5, SatMul(qk, wk)));
      w_rate = std::max(w_rate, SatDiv(SatAdd(torque, gyro), i_min));
      qk = SatAdd(1.0 + kUnitTolerance, SatMul(dt, q_rate));
      wk = SatAdd(w0, SatMul(dt, w_rate));
      worst = std::max({worst, gyro, qk, wk, q_rate, w_rate});
    }
    w_max = wk;
  } else {
    // |L| <= I_max |omega_0| + dt T and |omega| <= |L| / I_min.
    const double momentum = SatAdd(SatMul(i_max, w0), SatMul(dt, torque));
    w_max = std::max(w0, SatDiv(momentum, i_min));
    worst = std::max({worst, momentum, w_max, SatMul(dt, w_max)});
  }
  worst = std::max({worst, SatMul(i_max, w_max), SatMul(i_max, SatMul(w_max, w_max))});
  return worst <= kMaxMagnitude;
}

Status CheckWrench(std::string_view field, const Wrench& w) {
  if (!AllFinite(w.force)) return Status::InvalidElement(field, -1, "force", "must be finite (N)");
  if (!AllFinite(w.torque))
    return Status::InvalidElement(field, -1, "torque", "must be finite (N m)");
  return Status::Ok();
}

Status CheckState(const RigidBodyState& s) {
  constexpr std::string_view kField = "state";
  const auto bounded = [](const Vec3& x) { return AllFinite(x) && MaxAbs(x) <= kMaxMagnitude; };
  if (!bounded(s.position))
    return Status::InvalidElement(kField, -1, "position", "must be finite, within 1e150 (m)");
  if (!bounded(s.velocity))
    return Status::InvalidElement(kField, -1, "velocity", "must be finite, within 1e150 (m/s)");
  if (!AllFinite(s.orientation) || MaxAbs(s.orientation.vec()) > 2.0 ||
      std::abs(s.orientation.w()) > 2.0 ||
      !(std::abs(s.orientation.squaredNorm() - 1.0) <= kUnitTolerance))
    return Status::InvalidElement(kField, -1, "orientation", "must be a unit quaternion");
  if (!bounded(s.angular_velocity))
    return Status::InvalidElement(kField, -1, "angular_velocity",
                                  "must be finite, within 1e150 (rad/s)");
  if (!(std::isfinite(s.time) && std::abs(s.time) <= kMaxMagnitude))
    return Status::InvalidElement(kField, -1, "time", "must be finite, within 1e150 (s)");
  return Status::Ok();
}

void StepRk4(const RigidBodyStepJob& job, const RigidBodyState& s, const Quat& q0,
             RigidBodyState* next) {
  const double dt = job.dt, h = 0.5 * dt;
  const Vec3& moments = job.principal_moments;
  // Translation: RK4 of x'' = F(t)/m reduces to Simpson's rule for v and to
  // x0 + dt v0 + dt^2 (a0 + 2 a_mid)/6 for x; exact for F quadratic in t.
  const Vec3 a0 = job.at_start.force / job.mass;
  const Vec3 am = job.at_middle.force / job.mass;
  const Vec3 a1 = job.at_end.force / job.mass;
  next->position = s.position + dt * s.velocity + (dt * dt / 6.0) * (a0 + 2.0 * am);
  next->velocity = s.velocity + (dt / 6.0) * (a0 + 4.0 * am + a1);

  // Rotation: classic RK4 on (q, omega_b), torque at the start, middle (twice) and end.
  const Vec4 qc = q0.coeffs();
  const Vec3& w0 = s.angular_velocity;
  Vec4 dq1, dq2, dq3, dq4;
  Vec3 dw1, dw2, dw3, dw4;
  RotationRates(qc, w0, job.at_start.torque, moments, q0, &dq1, &dw1);
  RotationRates(qc + h * dq1, w0 + h * dw1, job.at_middle.torque, moments, q0, &dq2, &dw2);
  RotationRates(qc + h * dq2, w0 + h * dw2, job.at_middle.torque, moments, q0, &dq3, &dw3);
  RotationRates(qc + dt * dq3, w0 + dt * dw3, job.at_end.torque, moments, q0, &dq4, &dw4);
  next->orientation = NormalizedOr(qc + (dt / 6.0) * (dq1 + 2.0 * dq2 + 2.0 * dq3 + dq4), q0);
  next->angular_velocity = w0 + (dt / 6.0) * (dw1 + 2.0 * dw2 + 2.0 * dw3 + dw4);
}

void StepMomentum(const RigidBodyStepJob& job, const RigidBodyState& s, const Quat& q0,
                  RigidBodyState* next) {
  const double dt = job.dt;
  const Vec3& moments = job.principal_moments;
  // Translation: midpoint force, trapezoidal position; exact for F linear in t.
  next->velocity = s.velocity + (dt / job.mass) * job.at_middle.force;
  next->position = s.position + (0.5 * dt) * (s.velocity + next->velocity);

  // Rotation: L advances by the midpoint torque (exactly conserved when it is zero); q turns
  // by the angular velocity of the midpoint orientation, found by fixed-point iteration.
  const Vec3 momentum = RotationOf(q0) * moments.cwiseProduct(s.angular_velocity);
  const Vec3 momentum_mid = momentum + (0.5 * dt) * job.at_middle.torque;
  const Vec3 momentum_end = momentum + dt * job.at_middle.torque;
  Vec3 omega_mid = OmegaWorld(q0, moments, momentum_mid);
  for (int i = 0; i < kMidpointIterations; ++i)
    omega_mid = OmegaWorld(ExpMap((0.5 * dt) * omega_mid) * q0, moments, momentum_mid);
  const Quat q1 = NormalizedOr((ExpMap(dt * omega_mid) * q0).coeffs(), q0);
  next->orientation = q1;
  next->angular_velocity = (RotationOf(q1).transpose() * momentum_end).cwiseQuotient(moments);
}

}  // namespace

// ---------------------------------------------------------------------------------------

Status ComputeSolidMassProperties(std::span<const Vec3> positions,
                                  std::span<const Triangle> triangles, double density,
                                  MassProperties* out) {
  if (out == nullptr) return Status::Invalid("out", "is required");
  if (Status s = detail::CheckPositive("density", density, "must be positive and finite (kg/m^3)");
      !s)
    return s;
  if (Status s = CheckSurface(positions, triangles); !s) return s;

  const Frame frame = ReferenceFrame(positions, triangles);
  double volume = 0.0, abs_volume = 0.0, area = 0.0;
  Vec3 first = Vec3::Zero(), vector_area = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  for (const Triangle& t : triangles) {
    const Vec3 a = positions[t[0]] - frame.reference;
    const Vec3 b = positions[t[1]] - frame.reference;
    const Vec3 c = positions[t[2]] - frame.reference;
    const Vec3 n = (b - a).cross(c - a);
    const double v = a.dot(b.cross(c)) / 6.0;  // signed tetrahedron (reference, a, b, c)
    volume += v;
    abs_volume += std::abs(v);
    vector_area += n;
    area += n.norm();
    first += (v / 4.0) * (a + b + c);
    second += (v / 20.0) * VertexMoments(a, b, c);
  }
  if (!(vector_area.norm() <= kMaxRelativeOpening * area))
    return Status::Invalid("volume",
                           "is not enclosed: the surface is open (its vector area is not zero)");
  if (!(volume > 0.0))
    return Status::Invalid("volume",
                           "is not positive: the surface faces inward or encloses nothing");
  // |I| <= 14 rho sum|V_t| R^2 and m <= rho sum|V_t|, with R the half extent.
  const double r2 = frame.half_extent * frame.half_extent;
  if (!(SatMul(density, SatMul(abs_volume, std::max(1.0, 16.0 * r2))) <= kMaxInertia))
    return Status::Invalid("density", "too large for the body: the inertia would overflow");
  if (!(density * volume > 0.0))
    return Status::Invalid("density", "too small for the body: the mass underflows");
  if (!Finish(frame, volume, first, second, density, volume, out))
    return Status::Invalid("volume", "is degenerate: too small for the surface's extent");
  return Status::Ok();
}

Status ComputeShellMassProperties(std::span<const Vec3> positions,
                                  std::span<const Triangle> triangles, double density,
                                  double thickness, MassProperties* out) {
  if (out == nullptr) return Status::Invalid("out", "is required");
  if (Status s = detail::CheckPositive("density", density, "must be positive and finite (kg/m^3)");
      !s)
    return s;
  if (Status s = detail::CheckPositive("thickness", thickness, "must be positive and finite (m)");
      !s)
    return s;
  if (Status s = CheckSurface(positions, triangles); !s) return s;

  const Frame frame = ReferenceFrame(positions, triangles);
  double area = 0.0;
  Vec3 first = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  for (const Triangle& t : triangles) {
    const Vec3 a = positions[t[0]] - frame.reference;
    const Vec3 b = positions[t[1]] - frame.reference;
    const Vec3 c = positions[t[2]] - frame.reference;
    const double at = 0.5 * (b - a).cross(c - a).norm();
    area += at;
    first += (at / 3.0) * (a + b + c);
    second += (at / 12.0) * VertexMoments(a, b, c);  // integral of x x^T over the triangle
  }
  if (!(area > 0.0)) return Status::Invalid("triangles", "have no area (all degenerate)");
  const double r2 = frame.half_extent * frame.half_extent;
  const double areal_density = SatMul(density, thickness);
  if (!(SatMul(areal_density, SatMul(area, std::max(1.0, 16.0 * r2))) <= kMaxInertia))
    return Status::Invalid("density", "too large for the body: the inertia would overflow");
  if (!(areal_density * area > 0.0))
    return Status::Invalid("density", "too small for the body: the mass underflows");
  if (!Finish(frame, area, first, second, areal_density, area * thickness, out))
    return Status::Invalid("triangles", "are degenerate: too small for the surface's extent");
  return Status::Ok();
}

Vec3 TorqueAbout(const Vec3& center, const Vec3& point, const Vec3& force) {
  return (point - center).cross(force);
}

Status RigidBodyStepJob::Validate() const {
  switch (integrator) {
    case RigidIntegrator::kRk4:
    case RigidIntegrator::kMomentum:
      break;
    default:
      return Status::Invalid("integrator", "unknown integrator");
  }
  if (Status s = detail::CheckPositive("mass", mass, "must be positive and finite (kg)"); !s)
    return s;
  for (int k = 0; k < 3; ++k)
    if (!detail::PositiveFinite(principal_moments[k]))
      return Status::InvalidElement("principal_moments", k, "",
                                    "must be positive and finite (kg m^2)");
  if (Status s = detail::CheckPositive("dt", dt, "must be positive and finite (s)"); !s) return s;
  if (Status s = CheckWrench("at_start", at_start); !s) return s;
  if (Status s = CheckWrench("at_middle", at_middle); !s) return s;
  if (Status s = CheckWrench("at_end", at_end); !s) return s;
  if (state == nullptr) return Status::Invalid("state", "is required");
  if (Status s = CheckState(*state); !s) return s;
  if (!StepIsBounded(*this))
    return Status::Invalid("dt", "too long for the motion and loads: the step could overflow");
  return Status::Ok();
}

Status RigidBodyStepJob::Run() const {
  const Status status = Validate();
  if (!status) return status;
  const RigidBodyState& s = *state;
  // Validated unit within kUnitTolerance; renormalised so every step starts exactly unit.
  const Quat q0 = NormalizedOr(s.orientation.coeffs(), Quat::Identity());
  RigidBodyState next;
  if (integrator == RigidIntegrator::kRk4)
    StepRk4(*this, s, q0, &next);
  else
    StepMomentum(*this, s, q0, &next);
  next.time = s.time + dt;
  *state = next;
  return Status::Ok();
}

double KineticEnergy(const RigidBodyState& state, double mass, const Vec3& principal_moments) {
  const Vec3& w = state.angular_velocity;
  return 0.5 * mass * state.velocity.squaredNorm() + 0.5 * w.dot(principal_moments.cwiseProduct(w));
}

Vec3 AngularMomentumWorld(const RigidBodyState& state, const Vec3& principal_moments) {
  return RotationOf(state.orientation) * principal_moments.cwiseProduct(state.angular_velocity);
}

}  // namespace wirerig
