#include "wirerig/runtime/corotational_wire.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "scalar_root.h"
#include "validation.h"

namespace wirerig {
namespace {

constexpr double kMinLength = 1e-9;                        // m
constexpr double kMaxLength = 1e10;                        // m
constexpr double kMinStiffnessOverLengthSquared = 1e-100;  // N
constexpr double kMaxLoad = 1e100;                         // N, N/m or N m

// Finite and within kMaxLoad (isfinite first: an ordered comparison with NaN raises FE_INVALID).
bool Bounded(double x) { return std::isfinite(x) && std::abs(x) <= kMaxLoad; }
bool Bounded(const Vec3& x) { return Bounded(x.x()) && Bounded(x.y()) && Bounded(x.z()); }

// 2D helpers in the wire's X-Y plane.
struct Vec2 {
  double x = 0.0, y = 0.0;
};
Vec2 Planar(const Vec3& v) { return {v.x(), v.y()}; }
double Dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }

// The smallest EI along the wire (EI varies monotonically between its ends).
double MinStiffness(const CorotationalWireJob& job) {
  return job.tip_bending_stiffness > 0.0
             ? std::min(job.bending_stiffness, job.tip_bending_stiffness)
             : job.bending_stiffness;
}

// Largest root moment any shape could need: every load point lies within L of the root
// (the 1.1 covers the slight stretch of the chain's segments).
double MomentBound(const CorotationalWireJob& job) {
  double force = job.tip_force.norm();
  for (const PointLoad& p : job.point_loads) force += p.force.norm();
  for (const LineLoad& q : job.line_loads)
    force += q.force_per_length.norm() * job.length * (q.to - q.from);
  return std::abs(job.tip_moment) + 1.1 * job.length * force;
}

// Loads and geometry of one chain, independent of its shape (dead loads).
struct ChainSetup {
  const CorotationalWireJob* job = nullptr;
  int segments = 0;
  double h = 0.0;       // segment length, m
  double ei = 0.0;      // EI at the root, N m^2 (scales the tip residual)
  double min_ei = 0.0;  // the smallest EI along the wire, N m^2
  // EI of each segment: the inverse of its mean compliance 1/EI(v) (exact for the turn under a
  // constant moment), N m^2.
  std::array<double, CorotationalWireJob::kMaxSegments> segment_ei;
  // Fraction of the loads applied (load continuation); 1 for the final solve.
  double load_factor = 1.0;
  // force_beyond[k]: total force applied at s > s_k (node k), N; k in [0, K].
  std::array<Vec2, CorotationalWireJob::kMaxSegments + 1> force_beyond;
  // Segment of each point load (-1: at the root, carried by the clamp).
  std::array<int, CorotationalWireJob::kMaxPointLoads> point_segment;
};

int SegmentOf(double v, int segments) {
  // Node k sits at v = k/K; a load on node k+1 belongs to segment k.
  const int k = static_cast<int>(std::ceil(v * segments)) - 1;
  return std::min(k, segments - 1);
}

void BuildSetup(const CorotationalWireJob& job, int segments, ChainSetup* setup) {
  setup->job = &job;
  setup->segments = segments;
  setup->h = job.length / segments;
  setup->ei = job.bending_stiffness;
  setup->min_ei = MinStiffness(job);
  const double k_count = segments;
  // EI(v) = EI0 r^v, r = EI1 / EI0: the mean of 1/EI over [v0, v1] is
  // (r^-v0 - r^-v1) / ((v1 - v0) ln r) / EI0.
  const double ratio =
      job.tip_bending_stiffness > 0.0 ? job.tip_bending_stiffness / job.bending_stiffness : 1.0;
  const double log_ratio = std::log(ratio);
  for (int k = 0; k < segments; ++k) {
    const double v0 = k / k_count, v1 = (k + 1) / k_count;
    double mean_compliance = 1.0;  // times 1/EI0
    if (std::abs(log_ratio) > 1e-12)
      mean_compliance =
          (std::exp(-v0 * log_ratio) - std::exp(-v1 * log_ratio)) / ((v1 - v0) * log_ratio);
    setup->segment_ei[static_cast<std::size_t>(k)] = job.bending_stiffness / mean_compliance;
  }
  for (int k = 0; k <= segments; ++k) {
    const double v_node = k / k_count;
    Vec2 f = Planar(job.tip_force);
    for (const PointLoad& p : job.point_loads)
      if (SegmentOf(p.at, segments) >= k && p.at > 0.0) {
        f.x += p.force.x();
        f.y += p.force.y();
      }
    for (const LineLoad& q : job.line_loads) {
      const double extent = std::max(q.to - std::max(q.from, v_node), 0.0) * job.length;
      f.x += q.force_per_length.x() * extent;
      f.y += q.force_per_length.y() * extent;
    }
    setup->force_beyond[static_cast<std::size_t>(k)] = f;
  }
  for (std::size_t j = 0; j < job.point_loads.size(); ++j)
    setup->point_segment[j] =
        job.point_loads[j].at > 0.0 ? SegmentOf(job.point_loads[j].at, segments) : -1;
}

// The state of the chain at node k.
struct Node {
  Vec2 p;               // position, m
  double theta = 0.0;   // tangent angle, rad
  double moment = 0.0;  // moment about p of everything beyond, N m
};

// Segment k's loads in its own frame, ready for BendingJob, with the samples the moment
// balance needs: v = 1, each point load's position, three Gauss points per line-load patch.
struct SegmentProblem {
  static constexpr int kMaxSamples =
      4 + CorotationalWireJob::kMaxPointLoads + 3 * CorotationalWireJob::kMaxLineLoads;
  std::array<PointLoad, CorotationalWireJob::kMaxPointLoads> points;
  std::array<LineLoad, CorotationalWireJob::kMaxLineLoads> lines;
  std::array<double, CorotationalWireJob::kMaxPointLoads> point_tangential{};  // P . t, N
  std::array<double, CorotationalWireJob::kMaxLineLoads> line_tangential{};    // q . t, N/m
  std::array<double, CorotationalWireJob::kMaxLineLoads> line_normal{};        // q . n, N/m
  int point_count = 0, line_count = 0;
  double ei = 0.0;     // the segment's EI, N m^2
  double shear = 0.0;  // V = F_beyond . n at the tip, N
  double axial = 0.0;  // A = F_beyond . t, N (tension positive)
};

// Load continuation: each step may add at most about this much turn (bounded as for
// kAutoSegmentTurn), in at most this many steps.
constexpr double kContinuationTurn = 1.0;  // rad
constexpr int kMaxContinuationSteps = 64;

// Gauss-Legendre, three points on [-1, 1].
constexpr double kGaussNode = 0.7745966692414834;  // sqrt(3/5)
constexpr double kGaussWeightEnd = 5.0 / 9.0, kGaussWeightMid = 8.0 / 9.0;

void BuildSegment(const ChainSetup& setup, int k, double theta, SegmentProblem* seg) {
  const CorotationalWireJob& job = *setup.job;
  const Vec2 t{std::cos(theta), std::sin(theta)};
  const Vec2 n{-t.y, t.x};
  const double v0 = static_cast<double>(k) / setup.segments;
  const double v1 = static_cast<double>(k + 1) / setup.segments;
  const double factor = setup.load_factor;
  const Vec2 beyond_full = setup.force_beyond[static_cast<std::size_t>(k + 1)];
  const Vec2 beyond{factor * beyond_full.x, factor * beyond_full.y};
  seg->ei = setup.segment_ei[static_cast<std::size_t>(k)];
  seg->shear = Dot(beyond, n);
  seg->axial = Dot(beyond, t);
  seg->point_count = 0;
  for (std::size_t j = 0; j < job.point_loads.size(); ++j) {
    if (setup.point_segment[j] != k) continue;
    const PointLoad& p = job.point_loads[j];
    const Vec2 f = Planar(factor * p.force);
    const int i = seg->point_count++;
    const double local = std::clamp((p.at - v0) * setup.segments, 0.0, 1.0);
    seg->points[static_cast<std::size_t>(i)] = {local, Vec3(0.0, Dot(f, n), 0.0)};
    seg->point_tangential[static_cast<std::size_t>(i)] = Dot(f, t);
  }
  seg->line_count = 0;
  for (const LineLoad& q : job.line_loads) {
    const double a = std::max(q.from, v0), b = std::min(q.to, v1);
    const double from = std::clamp((a - v0) * setup.segments, 0.0, 1.0);
    const double to = std::clamp((b - v0) * setup.segments, 0.0, 1.0);
    if (!(to > from)) continue;
    const Vec2 f = Planar(factor * q.force_per_length);
    const int i = seg->line_count++;
    seg->lines[static_cast<std::size_t>(i)] = {from, to, Vec3(0.0, Dot(f, n), 0.0)};
    seg->line_normal[static_cast<std::size_t>(i)] = Dot(f, n);
    seg->line_tangential[static_cast<std::size_t>(i)] = Dot(f, t);
  }
}

// Runs BendingJob on the segment (without its tip moment) at `samples` (local v).
void SolveSegment(const ChainSetup& setup, const SegmentProblem& seg,
                  std::span<const double> samples, std::span<Vec3> w, std::span<Vec3> slope) {
  BendingJob bending;
  bending.boundary = BoundaryCondition::kCantileverFree;
  bending.length = setup.h;
  bending.bending_stiffness = seg.ei;
  bending.tip_force = Vec3(0.0, seg.shear, 0.0);
  bending.point_loads =
      std::span<const PointLoad>(seg.points.data(), static_cast<std::size_t>(seg.point_count));
  bending.line_loads =
      std::span<const LineLoad>(seg.lines.data(), static_cast<std::size_t>(seg.line_count));
  bending.samples = samples;
  bending.displacement = w;
  bending.slope = slope;
  // The inputs were validated by the chain (finite loads within the deflection bound).
  (void)bending.Run();
}

// Where the segment's point at local length x sits in its frame, and how far it has turned.
// The linear solution's slope w'(x) is the turn itself (the integral of M / EI, exact for the
// segment's moment field); the position integrates (cos w', sin w') to second order:
// (x - integral of w'^2 / 2, w(x)). `gauss_slope` holds w' at the three Gauss points of [0, x].
struct LocalPoint {
  double along = 0.0, across = 0.0, turn = 0.0;
};
LocalPoint Kinematics(double x, double w, double slope, const double* gauss_slope) {
  const double half = 0.5 * x;
  const double shortening = 0.5 * half *
                            (kGaussWeightEnd * gauss_slope[0] * gauss_slope[0] +
                             kGaussWeightMid * gauss_slope[1] * gauss_slope[1] +
                             kGaussWeightEnd * gauss_slope[2] * gauss_slope[2]);
  return {x - shortening, w, slope};
}

// Appends the three Gauss points of [0, local] to samples.
void AddGaussPoints(double local, double* samples) {
  samples[0] = 0.5 * local * (1.0 - kGaussNode);
  samples[1] = 0.5 * local;
  samples[2] = 0.5 * local * (1.0 + kGaussNode);
}

// Places a point at local v on the segment (its tip moment m_next) in the chain's frame.
LocalPoint SegmentPoint(const ChainSetup& setup, const SegmentProblem& seg, double m_next,
                        double local) {
  std::array<double, 4> samples{};
  std::array<Vec3, 4> w, slope;
  samples[0] = local;
  AddGaussPoints(local, &samples[1]);
  SolveSegment(setup, seg, samples, w, slope);
  std::array<double, 3> gauss_slope{};
  for (std::size_t i = 0; i < 3; ++i)
    gauss_slope[i] = slope[i + 1].y() + m_next * samples[i + 1] * setup.h / seg.ei;
  const double x = local * setup.h;
  return Kinematics(x, w[0].y() + m_next * x * x / (2.0 * seg.ei),
                    slope[0].y() + m_next * x / seg.ei, gauss_slope.data());
}

// Advances the chain over segment k: from `node` (with its moment) to the next node.
// Returns false if the segment's moment balance degenerates (never for validated inputs).
bool StepSegment(const ChainSetup& setup, int k, const Node& node, Node* next) {
  SegmentProblem seg;
  BuildSegment(setup, k, node.theta, &seg);
  std::array<double, SegmentProblem::kMaxSamples> samples{};
  std::array<Vec3, SegmentProblem::kMaxSamples> w, slope;
  int count = 0;
  samples[static_cast<std::size_t>(count++)] = 1.0;
  for (int i = 0; i < seg.point_count; ++i)
    samples[static_cast<std::size_t>(count++)] = seg.points[static_cast<std::size_t>(i)].at;
  for (int i = 0; i < seg.line_count; ++i) {
    const LineLoad& q = seg.lines[static_cast<std::size_t>(i)];
    const double mid = 0.5 * (q.from + q.to), half = 0.5 * (q.to - q.from);
    samples[static_cast<std::size_t>(count++)] = mid - half * kGaussNode;
    samples[static_cast<std::size_t>(count++)] = mid;
    samples[static_cast<std::size_t>(count++)] = mid + half * kGaussNode;
  }
  const int gauss = count;  // three Gauss points of [0, 1] for the shortening
  AddGaussPoints(1.0, &samples[static_cast<std::size_t>(count)]);
  count += 3;
  const auto n_samples = static_cast<std::size_t>(count);
  SolveSegment(setup, seg, std::span<const double>(samples.data(), n_samples),
               std::span<Vec3>(w.data(), n_samples), std::span<Vec3>(slope.data(), n_samples));

  // M_k = c0 + c1 M_{k+1}: the moment about node k of the loads beyond node k+1 (moved by the
  // deflected chord) and of the segment's own loads at their deflected positions; w(x) =
  // w0(x) + M_{k+1} x^2 / 2EI.
  const double h = setup.h, ei = seg.ei;
  double c0 = h * seg.shear - seg.axial * w[0].y();
  double c1 = 1.0 - seg.axial * h * h / (2.0 * ei);
  int s = 1;
  for (int i = 0; i < seg.point_count; ++i, ++s) {
    const auto ii = static_cast<std::size_t>(i);
    const double x = seg.points[ii].at * h;
    c0 += x * seg.points[ii].force.y() -
          seg.point_tangential[ii] * w[static_cast<std::size_t>(s)].y();
    c1 -= seg.point_tangential[ii] * x * x / (2.0 * ei);
  }
  for (int i = 0; i < seg.line_count; ++i, s += 3) {
    const auto ii = static_cast<std::size_t>(i);
    const double xa = seg.lines[ii].from * h, xb = seg.lines[ii].to * h;
    const double half = 0.5 * (xb - xa);
    const auto si = static_cast<std::size_t>(s);
    const double integral_w0 =
        half * (kGaussWeightEnd * w[si].y() + kGaussWeightMid * w[si + 1].y() +
                kGaussWeightEnd * w[si + 2].y());
    c0 += seg.line_normal[ii] * (xb * xb - xa * xa) / 2.0 - seg.line_tangential[ii] * integral_w0;
    c1 -= seg.line_tangential[ii] * (xb * xb * xb - xa * xa * xa) / (6.0 * ei);
  }
  if (!(c1 > 0.1)) return false;
  const double m_next = (node.moment - c0) / c1;
  std::array<double, 3> gauss_slope{};
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t si = static_cast<std::size_t>(gauss) + i;
    gauss_slope[i] = slope[si].y() + m_next * samples[si] * h / ei;
  }
  const LocalPoint tip = Kinematics(h, w[0].y() + m_next * h * h / (2.0 * ei),
                                    slope[0].y() + m_next * h / ei, gauss_slope.data());
  const double ct = std::cos(node.theta), st = std::sin(node.theta);
  next->p = {node.p.x + tip.along * ct - tip.across * st,
             node.p.y + tip.along * st + tip.across * ct};
  next->theta = node.theta + tip.turn;
  next->moment = m_next;
  return std::isfinite(next->p.x) && std::isfinite(next->p.y) && std::isfinite(next->theta) &&
         std::isfinite(next->moment);
}

using Nodes = std::array<Node, CorotationalWireJob::kMaxSegments + 1>;

// Sweeps the chain from the root with root moment m0; returns the tip condition's residual
// (free: M_K - tip_moment, scaled to an angle by L/EI; guided: theta_K), or false.
bool Sweep(const ChainSetup& setup, double m0, Nodes* nodes, double* residual) {
  (*nodes)[0] = {{0.0, 0.0}, 0.0, m0};
  for (int k = 0; k < setup.segments; ++k)
    if (!StepSegment(setup, k, (*nodes)[static_cast<std::size_t>(k)],
                     &(*nodes)[static_cast<std::size_t>(k + 1)]))
      return false;
  const Node& tip = (*nodes)[static_cast<std::size_t>(setup.segments)];
  if (setup.job->boundary == BoundaryCondition::kCantileverGuided)
    *residual = tip.theta;
  else
    *residual =
        (tip.moment - setup.load_factor * setup.job->tip_moment) * setup.job->length / setup.ei;
  return true;
}

// Root moment of the loads on the straight wire: the small-deflection answer, the first guess.
double StraightRootMoment(const CorotationalWireJob& job) {
  const double l = job.length;
  double m = job.tip_moment + l * job.tip_force.y();
  for (const PointLoad& p : job.point_loads) m += p.at * l * p.force.y();
  for (const LineLoad& q : job.line_loads)
    m += q.force_per_length.y() * l * l * (q.to * q.to - q.from * q.from) / 2.0;
  if (job.boundary == BoundaryCondition::kCantileverGuided) m *= 0.5;
  return m;
}

// Solves the shooting problem; on success leaves the converged chain in *nodes. Without a warm
// start (or if it finds no root) the load is applied in steps (continuation from the straight
// wire), each step taking the root next to the previous one: this follows the natural branch,
// not the looped equilibria that large loads also admit.
bool SolveChain(ChainSetup* setup, const double* warm_start, Nodes* nodes, double* m0_out,
                int* evaluations) {
  const CorotationalWireJob& job = *setup->job;
  int evals = 0;
  auto eval = [&](double m0, double* g) {
    ++evals;
    return Sweep(*setup, m0, nodes, g);
  };
  const double bound = MomentBound(job);
  double m0 = 0.0;
  if (bound == 0.0) {
    double g = 0.0;
    *m0_out = 0.0;
    *evaluations = 1;
    return eval(0.0, &g);
  }
  const double abs_tol = 1e-16 * bound;
  setup->load_factor = 1.0;
  const bool warm_solved =
      warm_start != nullptr &&
      detail::NearestRoot(eval, *warm_start, 1e-3 * bound, 64.0 * bound, abs_tol, &m0);
  if (!warm_solved) {  // no warm start, or it found no root: continuation
    const double turn = bound * job.length / setup->min_ei;
    const int steps = static_cast<int>(
        std::clamp(std::ceil(turn / kContinuationTurn), 1.0, double{kMaxContinuationSteps}));
    const double straight = StraightRootMoment(job);
    double previous_factor = 0.0;
    for (int i = 1; i <= steps; ++i) {
      const double factor = static_cast<double>(i) / steps;
      setup->load_factor = factor;
      const double guess = i == 1 ? straight * factor : m0 * factor / previous_factor;
      if (!detail::NearestRoot(eval, guess, 1e-3 * bound * factor, 64.0 * bound, abs_tol * factor,
                               &m0))
        return false;
      previous_factor = factor;
    }
  }
  double g = 0.0;
  if (!eval(m0, &g)) return false;  // leaves the converged chain in *nodes
  *m0_out = m0;
  *evaluations = evals;
  return true;
}

// A follower tip force is the dead force rotated by the tip's own turn theta_K. The chain then
// has two unknowns, the root moment m0 and the tip's turn theta, and two conditions, the free
// tip's moment and theta_K(m0, theta) = theta, solved by damped Newton (Jacobian by differences,
// one sweep per evaluation) with load continuation from the straight wire. (Nesting a dead solve
// inside a root search on theta fails at large loads: the follower's equilibria sit near folds
// of the dead problem.)
// `dead` starts as a copy of the job; on success it holds the equivalent dead force, *setup is
// built from it and *nodes holds the converged chain.
bool SolveFollower(CorotationalWireJob* dead_job, int k_count, ChainSetup* setup_out,
                   Nodes* nodes_out, double* m0_out, int* evaluations_out) {
  const CorotationalWireJob job = *dead_job;  // the follower's own loads
  CorotationalWireJob& dead = *dead_job;
  dead.tip_force_follows = false;
  ChainSetup& setup = *setup_out;
  Nodes& nodes = *nodes_out;
  int evaluations = 0;
  // Residuals at (m0, theta) for the loads scaled by `factor`.
  auto residuals = [&](double m0, double theta, double factor, double* r_moment, double* r_turn) {
    const double c = std::cos(theta), s = std::sin(theta);
    dead.tip_force = Vec3(c * job.tip_force.x() - s * job.tip_force.y(),
                          s * job.tip_force.x() + c * job.tip_force.y(), 0.0);
    BuildSetup(dead, k_count, &setup);
    setup.load_factor = factor;
    ++evaluations;
    if (!Sweep(setup, m0, &nodes, r_moment)) return false;
    *r_turn = theta - nodes[static_cast<std::size_t>(k_count)].theta;
    return std::isfinite(*r_turn);
  };
  const double bound = MomentBound(job);
  const double turn = bound * job.length / MinStiffness(job);
  const int steps = static_cast<int>(
      std::clamp(std::ceil(turn / kContinuationTurn), 1.0, double{kMaxContinuationSteps}));
  // Newton at load `factor` from (m0, theta); false if it does not converge.
  auto newton = [&](double factor, double* m0_io, double* theta_io) {
    double m0 = *m0_io, theta = *theta_io, f1 = 0.0, f2 = 0.0;
    if (!residuals(m0, theta, factor, &f1, &f2)) return false;
    for (int iter = 0; iter < 30; ++iter) {
      if (std::hypot(f1, f2) <= 1e-13) break;
      const double dm = 1e-7 * bound, dt = 1e-7;
      double a1 = 0.0, a2 = 0.0, b1 = 0.0, b2 = 0.0;
      if (!residuals(m0 + dm, theta, factor, &a1, &a2) ||
          !residuals(m0, theta + dt, factor, &b1, &b2))
        return false;
      const double j11 = (a1 - f1) / dm, j21 = (a2 - f2) / dm;
      const double j12 = (b1 - f1) / dt, j22 = (b2 - f2) / dt;
      const double det = j11 * j22 - j12 * j21;
      if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
      double step_m = -(j22 * f1 - j12 * f2) / det;
      double step_t = -(j11 * f2 - j21 * f1) / det;
      // At most half a radian of turn per step; halve until the residual falls.
      const double limit = std::max(std::abs(step_t), std::abs(step_m) * job.length / setup.ei);
      if (limit > 0.5) {
        step_m *= 0.5 / limit;
        step_t *= 0.5 / limit;
      }
      bool improved = false;
      for (int halving = 0; halving < 30 && !improved; ++halving) {
        double g1 = 0.0, g2 = 0.0;
        if (residuals(m0 + step_m, theta + step_t, factor, &g1, &g2) &&
            std::hypot(g1, g2) < std::hypot(f1, f2)) {
          m0 += step_m;
          theta += step_t;
          f1 = g1;
          f2 = g2;
          improved = true;
        } else {
          step_m *= 0.5;
          step_t *= 0.5;
        }
      }
      if (!improved) break;  // at the noise floor, or stuck
    }
    if (!(std::hypot(f1, f2) <= 1e-9)) return false;
    *m0_io = m0;
    *theta_io = theta;
    return true;
  };
  // Adaptive continuation: a step that fails is halved (down to 1/4096 of the load).
  double m0 = 0.0, theta = 0.0, factor = 0.0, df = 1.0 / steps;
  while (factor < 1.0) {
    const double next = std::min(1.0, factor + df);
    double m_try = factor > 0.0 ? m0 * next / factor : 0.0;
    double t_try = factor > 0.0 ? theta * next / factor : 0.0;
    if (newton(next, &m_try, &t_try)) {
      m0 = m_try;
      theta = t_try;
      factor = next;
      df = std::min(1.5 * df, 1.0 / steps);
    } else {
      df *= 0.5;
      if (df < 1.0 / 4096.0) return false;
    }
  }
  // Leave the converged chain (and its setup) for the outputs.
  double f1 = 0.0, f2 = 0.0;
  if (!residuals(m0, theta, 1.0, &f1, &f2)) return false;
  *m0_out = m0;
  *evaluations_out = evaluations;
  return true;
}

}  // namespace

int AutomaticSegmentCount(const CorotationalWireJob& job) {
  const double turn = MomentBound(job) * job.length / MinStiffness(job);
  if (!std::isfinite(turn)) return CorotationalWireJob::kMaxSegments;
  const double k = std::ceil(turn / CorotationalWireJob::kAutoSegmentTurn);
  return static_cast<int>(std::clamp(k, 8.0, double{CorotationalWireJob::kMaxSegments}));
}

Status CorotationalWireJob::Validate() const {
  if (boundary != BoundaryCondition::kCantileverFree &&
      boundary != BoundaryCondition::kCantileverGuided)
    return Status::Invalid("boundary", "must be cantilever_free or cantilever_guided");
  // The magnitude limits keep every product of the solve finite (no overflow, no NaN).
  if (!(std::isfinite(length) && length >= kMinLength && length <= kMaxLength))
    return Status::Invalid("length", "must lie in [1e-9, 1e10] (m)");
  if (Status s = detail::CheckPositive("bending_stiffness", bending_stiffness,
                                       "must be positive and finite (N m^2)");
      !s)
    return s;
  if (bending_stiffness < kMinStiffnessOverLengthSquared * length * length)
    return Status::Invalid("bending_stiffness", "too small for the length: below 1e-100 L^2");
  if (!(std::isfinite(tip_bending_stiffness) && tip_bending_stiffness >= 0.0))
    return Status::Invalid("tip_bending_stiffness", "must be zero (uniform) or positive (N m^2)");
  if (tip_bending_stiffness > 0.0 && !(tip_bending_stiffness >= 1e-12 * bending_stiffness &&
                                       tip_bending_stiffness <= 1e12 * bending_stiffness))
    return Status::Invalid("tip_bending_stiffness", "must lie within 1e12 of bending_stiffness");
  if (segments < 0 || segments > kMaxSegments)
    return Status::Invalid("segments", "must lie in [0, 256] (0: automatic)");
  if (!Bounded(tip_force) || tip_force.z() != 0.0)
    return Status::Invalid("tip_force", "must have |components| <= 1e100 and z = 0 (N, planar)");
  if (!Bounded(tip_moment)) return Status::Invalid("tip_moment", "must have |M| <= 1e100 (N m)");
  if (warm_start && !Bounded(root_moment_guess))
    return Status::Invalid("root_moment_guess", "must have |M| <= 1e100 (N m)");
  if (tip_moment != 0.0 && boundary == BoundaryCondition::kCantileverGuided)
    return Status::Invalid("tip_moment", "must be zero on a guided tip (its support takes it)");
  if (point_loads.size() > static_cast<std::size_t>(kMaxPointLoads))
    return Status::Invalid("point_loads", "at most 16");
  for (std::size_t i = 0; i < point_loads.size(); ++i) {
    const int index = static_cast<int>(i);
    if (Status s = detail::CheckLoadPosition("point_loads", index, point_loads[i].at); !s) return s;
    if (!Bounded(point_loads[i].force) || point_loads[i].force.z() != 0.0)
      return Status::InvalidElement("point_loads", index, "force",
                                    "must have |components| <= 1e100 and z = 0 (N, planar)");
  }
  if (line_loads.size() > static_cast<std::size_t>(kMaxLineLoads))
    return Status::Invalid("line_loads", "at most 8");
  for (std::size_t i = 0; i < line_loads.size(); ++i) {
    const LineLoad& q = line_loads[i];
    const int index = static_cast<int>(i);
    if (Status s = detail::CheckLoadExtent("line_loads", index, q.from, q.to); !s) return s;
    if (!Bounded(q.force_per_length) || q.force_per_length.z() != 0.0)
      return Status::InvalidElement("line_loads", index, "force_per_length",
                                    "must have |components| <= 1e100 and z = 0 (N/m, planar)");
  }
  // Every segment's possible turn: the largest moment times h / EI.
  const double turn = MomentBound(*this) * length / MinStiffness(*this);
  if (!(std::isfinite(turn) && turn < detail::kMaxDeflectionBound))
    return Status::Invalid("loads", "too large for the stiffness: the deflection would overflow");
  const int k = segments == 0 ? AutomaticSegmentCount(*this) : segments;
  if (turn / k > kMaxSegmentTurn)
    return Status::Invalid("segments",
                           "too few for the loads: a segment could turn more than 1 rad");
  if (!samples.empty())
    if (Status s = detail::CheckSamples(samples); !s) return s;
  if (Status s = detail::CheckOutput("position", position.size(), samples.size(), false); !s)
    return s;
  if (Status s = detail::CheckOutput("tangent", tangent.size(), samples.size(), false); !s)
    return s;
  return Status::Ok();
}

Status CorotationalWireJob::Run() const {
  if (Status s = Validate(); !s) return s;
  const int k_count = segments == 0 ? AutomaticSegmentCount(*this) : segments;
  ChainSetup setup;
  Nodes nodes;
  double m0 = 0.0;
  int evaluations = 0;
  // A guided tip does not turn: its follower force is the dead force.
  CorotationalWireJob rotated = *this;  // the follower's equivalent dead job (outlives setup)
  if (tip_force_follows && !tip_force.isZero(0.0) &&
      boundary == BoundaryCondition::kCantileverFree) {
    if (!SolveFollower(&rotated, k_count, &setup, &nodes, &m0, &evaluations))
      return Status::Invalid("tip_force",
                             "the follower force found no equilibrium: raise segments");
  } else {
    BuildSetup(*this, k_count, &setup);
    if (!SolveChain(&setup, warm_start ? &root_moment_guess : nullptr, &nodes, &m0, &evaluations))
      return Status::Invalid("loads", "the chain did not converge: raise segments");
  }

  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double v = samples[i];
    const int k = std::clamp(static_cast<int>(std::floor(v * k_count)), 0, k_count - 1);
    const Node& node = nodes[static_cast<std::size_t>(k)];
    const double m_next = nodes[static_cast<std::size_t>(k + 1)].moment;
    SegmentProblem seg;
    BuildSegment(setup, k, node.theta, &seg);
    const double local = std::clamp(v * k_count - k, 0.0, 1.0);
    const LocalPoint point = SegmentPoint(setup, seg, m_next, local);
    const double theta = node.theta + point.turn;
    const double ct = std::cos(node.theta), st = std::sin(node.theta);
    if (!position.empty())
      position[i] = Vec3(node.p.x + point.along * ct - point.across * st,
                         node.p.y + point.along * st + point.across * ct, 0.0);
    if (!tangent.empty()) tangent[i] = Vec3(std::cos(theta), std::sin(theta), 0.0);
  }
  if (result != nullptr) {
    const Node& tip = nodes[static_cast<std::size_t>(k_count)];
    result->tip_position = Vec3(tip.p.x, tip.p.y, 0.0);
    result->tip_tangent = Vec3(std::cos(tip.theta), std::sin(tip.theta), 0.0);
    result->tip_rotation = tip.theta;
    result->root_moment = m0;
    result->segments = k_count;
    result->iterations = evaluations;
  }
  return Status::Ok();
}

}  // namespace wirerig
