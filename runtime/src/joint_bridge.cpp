#include "wirerig/runtime/joint_bridge.h"

#include <algorithm>
#include <cmath>

namespace wirerig {
namespace {

double SmoothStep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Length of the Hermite tangents that make a cubic follow the circular arc turning by the
// angle between unit tangents a and b over a chord of length `chord`: the arc's Bezier handle
// (4/3) R tan(theta/4), times 3, with R = chord / (2 sin(theta/2)). Tends to the chord as the
// turn vanishes; a straight line then has constant speed.
double ArcHandle(double chord, const Vec3& a, const Vec3& b) {
  const double theta = std::atan2(a.cross(b).norm(), a.dot(b));
  if (theta < 1e-6) return chord;
  return chord * 2.0 * std::tan(0.25 * theta) / std::sin(0.5 * theta);
}

struct Hermite {
  Vec3 p0, m0, p1, m1;
  Vec3 At(double t) const {
    const double t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * p1 +
           (t3 - t2) * m1;
  }
  Vec3 SecondDerivative(double t) const {
    return (12 * t - 6) * p0 + (6 * t - 4) * m0 + (6 - 12 * t) * p1 + (6 * t - 2) * m1;
  }
  Vec3 Derivative(double t) const {
    const double t2 = t * t;
    return (6 * t2 - 6 * t) * p0 + (3 * t2 - 4 * t + 1) * m0 + (-6 * t2 + 6 * t) * p1 +
           (3 * t2 - 2 * t) * m1;
  }
};

Hermite CurveOf(const BridgeEnds& ends) {
  const double handle =
      ArcHandle((ends.end - ends.start).norm(), ends.start_tangent, ends.end_tangent);
  return {ends.start, handle * ends.start_tangent, ends.end, handle * ends.end_tangent};
}

// How near the bend's centre of curvature a section may reach, as a fraction of its radius.
constexpr double kFit = 0.9;
// The most a section may widen across the bend: a deep bend's short centre curve would
// otherwise take all the flesh's volume sideways (the skin there stretched as much).
constexpr double kMaxAcross = 1.9;

// The in-plane scale of the cross-section where the bent curve has velocity v and acceleration
// a, growing its area by `area`. Evenly where the bend allows; but the section must not reach
// the bend's centre of curvature (sections would cross there), so towards it the scale is held
// to what fits within kFit of the radius of curvature beyond the limb's radius, and the rest of
// the growth goes across the bend, along the binormal (flesh squeezed on the inside of an elbow
// bulges sideways).
Mat3 CrossSectionScale(const Vec3& v, const Vec3& a, double area, double limb_radius) {
  const double speed = v.norm();
  if (!(speed > 0.0)) return Mat3::Identity();
  const Vec3 t = v / speed;
  const Vec3 bend = a - a.dot(t) * t;  // |bend| = curvature * speed^2
  const double curvature = bend.norm() / (speed * speed);
  double towards = std::sqrt(area);
  if (curvature * limb_radius > 1e-9)
    towards = std::min(towards, std::max(1.0, kFit / (curvature * limb_radius)));
  const double across = std::min(area / towards, kMaxAcross);
  Mat3 scale = t * t.transpose();
  if (curvature * limb_radius > 1e-9) {
    const Vec3 n = bend.normalized(), b = t.cross(n);
    scale += towards * n * n.transpose() + across * b * b.transpose();
  } else {
    scale += towards * (Mat3::Identity() - t * t.transpose());
  }
  return scale;
}

// Scales by `along` along the unit vector t and by `across` in the plane normal to it.
Mat3 AxialScale(const Vec3& t, double along, double across) {
  return across * Mat3::Identity() + (along - across) * t * t.transpose();
}

// Curvature x inward normal of a curve with velocity v and acceleration a.
Vec3 Bend(const Vec3& v, const Vec3& a) {
  const double speed2 = v.squaredNorm();
  if (!(speed2 > 0.0)) return Vec3::Zero();
  return (a - a.dot(v) / speed2 * v) / speed2;
}
double Curvature(const Vec3& v, const Vec3& a) { return Bend(v, a).norm(); }

// The bend's inward normal over the reach kFit / (curvature beyond the rest curvature): zero
// where the bridge bends no more than at rest, so rest is reproduced exactly.
Vec3 Inward(const Vec3& v, const Vec3& a, double rest_curvature) {
  const Vec3 bend = Bend(v, a);
  const double curvature = bend.norm();
  if (!(curvature > rest_curvature)) return Vec3::Zero();
  return bend * ((curvature - rest_curvature) / (curvature * kFit));
}

}  // namespace

RestBridge MakeRestBridge(const BridgeEnds& rest) {
  RestBridge out;
  out.ends = rest;
  const Hermite curve = CurveOf(rest);
  for (int k = 0; k <= kBridgeSegments; ++k) {
    const double u = double(k) / kBridgeSegments;
    out.points[k] = curve.At(u);
    const Vec3 velocity = curve.Derivative(u);
    out.curvature[k] = Curvature(velocity, curve.SecondDerivative(u));
    out.speed[k] = velocity.norm();
  }
  return out;
}

JointBinding BindToJoint(const JointModel& joint, const RestBridge& rest_bridge, const Vec3& p,
                         JointSide side, double reach) {
  const BridgeEnds& rest = rest_bridge.ends;
  JointBinding out;
  const double h = joint.blend_length;
  if (!(h > 0.0) || !(joint.radius > 0.0)) return out;
  // Far from the whole bridge (every point of it lies within h of the rest root point, the
  // start of the rest curve at h from it): nothing to bind.
  const double far = 2.0 * h + reach + kBridgeOuter * std::max(joint.radius, joint.parent_radius);
  if ((p - (rest.start + h * rest.start_tangent)).squaredNorm() > far * far) return out;
  // Where p lies along the rest bridge: the nearest of its samples, refined on the chord to the
  // nearer neighbour; beyond its ends, along the end tangents.
  const std::array<Vec3, kBridgeSegments + 1>& points = rest_bridge.points;
  int nearest = 0;
  for (int k = 0; k <= kBridgeSegments; ++k)
    if ((points[k] - p).squaredNorm() < (points[nearest] - p).squaredNorm()) nearest = k;
  double best = 1e300;
  for (int k = std::max(0, nearest - 1); k < std::min(kBridgeSegments, nearest + 1); ++k) {
    const Vec3 a = points[k], ab = points[k + 1] - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    const double distance = (a + t * ab - p).squaredNorm();
    if (distance < best) best = distance, out.u = (k + t) / kBridgeSegments;
  }
  const double before = (p - rest.start).dot(rest.start_tangent);  // < 0: beyond the parent end
  const double after = (p - rest.end).dot(rest.end_tangent);       // > 0: beyond the child end
  const Vec3 along = before < 0.0 ? rest.start_tangent : rest.end_tangent;
  const Vec3 from = out.u <= 0.0 ? rest.start : out.u >= 1.0 ? rest.end : CurveOf(rest).At(out.u);
  const Vec3 d = p - from;
  const double rho =
      (out.u <= 0.0 || out.u >= 1.0) ? (d - d.dot(along) * along).norm() : std::sqrt(best);
  const bool child_side = side == JointSide::kChild;
  // A point of one side lying beyond the bridge's far end (a vertex its part claimed across
  // the joint) follows the other side near the bone line: the bridge's end there.
  const double fade = kBridgeEndFade * h;
  if (child_side ? (before <= -reach || after >= fade) : (before <= -fade || after >= reach)) {
    out.u = 0.0;
    return out;
  }
  // The limb's radius: the parent's over the parent's half, the child's from the middle on.
  const double parent_radius = joint.parent_radius > 0.0 ? joint.parent_radius : joint.radius;
  const double mix = SmoothStep(0.25, 0.5, out.u);
  const double radius = (1.0 - mix) * parent_radius + mix * joint.radius;
  out.bridge = 1.0 - SmoothStep(kBridgeInner * radius, kBridgeOuter * radius, rho);
  const double beyond = child_side ? after : -before;
  if (beyond > 0.0) out.bridge *= 1.0 - SmoothStep(0.0, fade, beyond);
  out.section = rho > radius ? radius / rho : 1.0;
  out.weight = 1.0;
  return out;
}

void SampleJointBridge(const JointModel& joint, const RestBridge& rest_bridge,
                       const BridgeEnds& posed, const Mat3& parent_rotation,
                       const Mat3& child_rotation, BridgeSamples* out) {
  const BridgeEnds& rest = rest_bridge.ends;
  out->parent_turn = parent_rotation * AxialScale(rest.start_tangent, 1.0, posed.start_scale);
  out->parent_offset = posed.start - out->parent_turn * rest.start;
  out->child_turn = child_rotation * AxialScale(rest.end_tangent, 1.0, posed.end_scale);
  out->child_offset = posed.end - out->child_turn * rest.end;
  const Hermite curve = CurveOf(posed);
  const Quat parent(parent_rotation);
  const Quat relative = (parent.conjugate() * Quat(child_rotation)).normalized();
  Quat swing, twist;
  SwingTwist(relative, joint.axes.col(2), &swing, &twist);
  // Area growth s(u)^2 (1 + c bump(u)), s the ends' in-plane scales blended by smoothstep(u)
  // and bump = 4u(1 - u): the sides' own sections at both ends, and c chosen so the bridge keeps
  // the volume of its flesh, integral of area x speed (Simpson's rule over the samples): the
  // rest bridge's, each section scaled by s(u)^2 and stretched by 1 at the start to the child's
  // stretch at the end (smoothstep(u)), times the joint's growth scale for the bend
  // (BendGrowthScale) (the mesh's skin is no tube of constant section about the curve: the builder
  // fits it). A straight limb strained evenly keeps its sections: c = 0. The curves' velocities and
  // accelerations at the samples, computed once.
  std::array<Vec3, kBridgeSegments + 1> velocity, acceleration;
  std::array<double, kBridgeSegments + 1> scale;
  double flesh = 0.0, bent = 0.0, bumped = 0.0;
  for (int k = 0; k <= kBridgeSegments; ++k) {
    const double u = double(k) / kBridgeSegments;
    velocity[k] = curve.Derivative(u);
    acceleration[k] = curve.SecondDerivative(u);
    const double blend = SmoothStep(0.0, 1.0, u);
    scale[k] = posed.start_scale + blend * (posed.end_scale - posed.start_scale);
    const double simpson = (k == 0 || k == kBridgeSegments) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    const double area = simpson * scale[k] * scale[k];
    flesh += area * (1.0 + blend * (posed.end_stretch - 1.0)) * rest_bridge.speed[k];
    bent += area * velocity[k].norm();
    bumped += 4.0 * u * (1.0 - u) * area * velocity[k].norm();
  }
  const double growth =
      bumped > 0.0 ? BendGrowthScale(joint, swing) * (flesh - bent) / bumped : 0.0;
  // swing^u and twist^u at u_k = k / kBridgeSegments as powers of their first step.
  const Quat swing_step = ScaleRotation(swing, 1.0 / kBridgeSegments);
  const Quat twist_step = ScaleRotation(twist, 1.0 / kBridgeSegments);
  Quat swing_u = Quat::Identity(), twist_u = Quat::Identity();
  for (int k = 0; k <= kBridgeSegments; ++k) {
    const double u = double(k) / kBridgeSegments;
    BridgeSamples::Sample& sample = out->samples[k];
    const Vec3& rest_centre = rest_bridge.points[k];
    sample.centre = curve.At(u);
    const Mat3 rotation = (parent * swing_u * twist_u).toRotationMatrix();
    swing_u = (swing_u * swing_step).normalized();
    twist_u = (twist_u * twist_step).normalized();
    const double area =
        std::clamp(scale[k] * scale[k] * (1.0 + growth * 4.0 * u * (1.0 - u)), 0.25, 4.0);
    const double speed = velocity[k].norm();
    sample.turn =
        speed > 0.0 ? AxialScale(velocity[k] / speed, 1.0, scale[k]) * rotation : rotation;
    sample.turn_offset = sample.centre - sample.turn * rest_centre;
    sample.inward = Inward(velocity[k], acceleration[k], rest_bridge.curvature[k]);
    sample.map = CrossSectionScale(velocity[k], acceleration[k], area, joint.radius) * rotation;
    sample.map_offset = sample.centre - sample.map * rest_centre;
  }
}

}  // namespace wirerig
