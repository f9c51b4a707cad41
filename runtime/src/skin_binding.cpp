// Skin binding: see skin_binding.h for the contract and PHYSICS.md section 6 ("Robust
// formulation") for the construction.
//
// Bind. t = unit(c_j - c_i), c_m the closest point to p on the spine segment and
// r = (p - c_m) perpendicular to t, the radial direction of p. The plane through p, c_i and
// c_j has normal n = unit((c_i - p) x (c_j - p)) = unit(t x r): the two are equal because
// (c_i - p) x (c_j - p) = |c_j - c_i| t x (p - c_i) and only the part of p - c_i
// perpendicular to t survives the cross product. The second form is used: it cannot overflow
// and is exact in direction when p is close to the spine. When |r| < kAxisFraction |c_j - c_i|
// (p on the spine line) the plane and "p's side" are taken from the first wire point off the
// spine line (w_i[0] unless it lies on the spine line too) and kBindingPlaneDegenerate is set.
//
// Intersections. d_k = n . (a_k - p) is computed once per vertex; segment k (a_k to a_{k+1},
// wrapping when closed) yields a hit at lambda = 0 when d_k == 0 and at
// lambda = d_k / (d_k - d_{k+1}) when d_k and d_{k+1} have strictly opposite signs. The last
// vertex of an open wire is tried as lambda = 1 of the last segment. So a vertex lying in the
// plane (p itself on a wire, a tangency, a segment inside the plane) counts exactly once,
// and since every d_k is used by both of its segments the crossings are topologically
// consistent. Hits must lie strictly on p's side, (x - c_W) . r > 0; the closest to p wins.
//
// Frame. FrameAxes() builds e_hat and n_f = unit(e x (c - p1)) from unit vectors, so no
// cross product of raw differences is ever formed. When the sine of the angle between e and
// c - p1 is below kDegenerateSine, Apply turns the rest normal by the minimal rotation taking
// the rest edge to the current one; Bind (where the rest normal is being made) uses the bind
// plane's normal instead. Bind and Apply call the same FrameAxes() and PointOnWire(), so at
// rest Apply rebuilds the very same frame and reproduces p to rounding.
//
// Floating point. Inputs are refused unless finite with coordinates within kMaxCoordinate, so
// squared lengths cannot overflow. Every normalisation goes through Unit(), which scales by
// the largest component first and reports zero vectors instead of dividing by zero.
#include "wirerig/runtime/skin_binding.h"

#include "vector_math.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>

namespace wirerig {
namespace {

using detail::MaxAbs;
using detail::OrthonormalizeAgainst;
using detail::PerpendicularTo;
using detail::Unit;

// Coordinates beyond this (m) are refused: squares of lengths must not overflow.
constexpr double kMaxCoordinate = 1e100;
// Spine points closer than this fraction of their coordinates' magnitude coincide ...
constexpr double kCoincidentFraction = 1e-12;
// ... or closer than this, in metres, whatever their magnitude.
constexpr double kCoincidentAbsolute = 1e-100;
// p closer to the spine line than this fraction of |c_j - c_i| lies on it.
constexpr double kAxisFraction = 1e-9;
// e x (c - p1) is degenerate when the sine of the angle between e and c - p1 is below this.
constexpr double kDegenerateSine = 1e-8;
// The frame edge |p2 - p1| must exceed this fraction of max(|c_j - c_i|, |p - p1|); this
// keeps |alpha|, |beta| and |gamma| below about 1e12.
constexpr double kMinEdgeFraction = 1e-12;
// Below this, 1 + cos(angle) makes the minimal rotation ill-defined (the edge reversed).
constexpr double kReversedEdge = 1e-6;

constexpr std::string_view kCoordinateReason = "must be finite, with coordinates within 1e100 m";

// True when every coordinate is finite and within kMaxCoordinate. Uses no arithmetic that
// could raise a floating-point exception on Inf or NaN.
bool CoordinatesOk(const Vec3& v) {
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(v(i)) || std::abs(v(i)) > kMaxCoordinate) return false;
  return true;
}

// The minimal rotation taking the unit vector a to the unit vector b, applied to v
// (Rodrigues with k = a x b, cos = a . b). For b (nearly) opposite to a the rotation is not
// unique: the half turn about v itself is used, which leaves v unchanged (v is the rest
// normal, perpendicular to a, so this is a half turn taking a to -a).
Vec3 MinimalRotation(const Vec3& a, const Vec3& b, const Vec3& v) {
  const double cos_angle = a.dot(b);
  if (!(1.0 + cos_angle > kReversedEdge)) return v;
  const Vec3 k = a.cross(b);
  return cos_angle * v + k.cross(v) + (k.dot(v) / (1.0 + cos_angle)) * k;
}

// Point `lambda` of the way along segment k of the wire (points k and k + 1, wrapping). The
// same expression at bind and apply time makes the rest frame reproducible bit for bit.
// Out-of-range k (a wire with fewer points than at bind time) is clamped, never read past.
Vec3 PointOnWire(const WirePolyline& wire, std::uint32_t k, double lambda) {
  const std::size_t n = wire.points.size();
  if (n == 0) return Vec3::Zero();
  const std::size_t i0 = std::min<std::size_t>(k, n - 1);
  const std::size_t i1 = i0 + 1 < n ? i0 + 1 : 0;
  return (1.0 - lambda) * wire.points[i0] + lambda * wire.points[i1];
}

// The frame axes of PHYSICS.md section 6 step 4 for edge e = p2 - p1 and to_center = c - p1.
// Sets *length = |e| (0: nothing else is set). Returns true and sets *e_hat and *normal =
// unit(e x (c - p1)) when that cross product is well defined; returns false (with *e_hat
// set when |e| > 0) when c - p1 is zero or (anti)parallel to e to within kDegenerateSine.
bool FrameAxes(const Vec3& e, const Vec3& to_center, Vec3* e_hat, double* length, Vec3* normal) {
  *length = Unit(e, e_hat);
  if (*length == 0.0) return false;
  Vec3 to_center_hat;
  if (Unit(to_center, &to_center_hat) == 0.0) return false;
  return Unit(e_hat->cross(to_center_hat), normal) > kDegenerateSine;
}

// Intersection of the plane {x : n . (x - p) = 0} with the wire, on p's side of the wire's
// spine point (radial direction r). Returns false when there is no such point.
bool IntersectWire(const Vec3& p, const WirePolyline& wire, const Vec3& spine_point, const Vec3& n,
                   const Vec3& r, std::uint32_t* k_out, double* lambda_out) {
  const std::size_t count = wire.points.size();
  const std::size_t segments = wire.closed ? count : count - 1;
  bool found = false;
  double best = 0.0;
  const auto consider = [&](std::size_t k, double lambda) {
    const Vec3 x = PointOnWire(wire, static_cast<std::uint32_t>(k), lambda);
    if (!((x - spine_point).dot(r) > 0.0)) return;
    const double distance2 = (x - p).squaredNorm();
    if (!found || distance2 < best) {
      found = true;
      best = distance2;
      *k_out = static_cast<std::uint32_t>(k);
      *lambda_out = lambda;
    }
  };
  double d0 = n.dot(wire.points[0] - p);
  for (std::size_t k = 0; k < segments; ++k) {
    const std::size_t next = k + 1 < count ? k + 1 : 0;
    const double d1 = n.dot(wire.points[next] - p);
    if (d0 == 0.0) {
      consider(k, 0.0);
    } else if ((d0 < 0.0 && d1 > 0.0) || (d0 > 0.0 && d1 < 0.0)) {
      consider(k, d0 / (d0 - d1));  // |d0 - d1| > |d0| > 0: lambda in (0, 1]
    }
    d0 = d1;
  }
  if (!wire.closed && d0 == 0.0) consider(count - 2, 1.0);  // last vertex of an open wire
  return found;
}

// Closest point of the wire to p, as segment and fraction.
void ClosestPointOnWire(const Vec3& p, const WirePolyline& wire, std::uint32_t* k_out,
                        double* lambda_out) {
  const std::size_t count = wire.points.size();
  const std::size_t segments = wire.closed ? count : count - 1;
  double best = 0.0;
  for (std::size_t k = 0; k < segments; ++k) {
    const Vec3& a = wire.points[k];
    const Vec3 v = wire.points[k + 1 < count ? k + 1 : 0] - a;
    const double along = (p - a).dot(v);
    const double length2 = v.squaredNorm();
    // Clamped before dividing: no division by a zero (or overflowing) length.
    const double lambda = along <= 0.0 ? 0.0 : (along >= length2 ? 1.0 : along / length2);
    const double distance2 = (a + lambda * v - p).squaredNorm();
    if (k == 0 || distance2 < best) {
      best = distance2;
      *k_out = static_cast<std::uint32_t>(k);
      *lambda_out = lambda;
    }
  }
}

Status CheckWire(std::string_view field, const WirePolyline& wire) {
  if (wire.points.size() < 2) return Status::Invalid(field, "needs at least 2 points");
  if (wire.points.size() > std::numeric_limits<std::uint32_t>::max())
    return Status::Invalid(field, "has more than 2^32 - 1 points");
  for (std::size_t i = 0; i < wire.points.size(); ++i)
    if (!CoordinatesOk(wire.points[i]))
      return Status::InvalidElement(field, static_cast<int>(i), "", kCoordinateReason);
  return Status::Ok();
}

// The radial direction used when p lies on the spine line: that of the first point of
// wire_i, then of wire_j, that is off the spine line; a world axis if every point is on it.
Vec3 FallbackRadial(const WirePolyline& wire_i, const WirePolyline& wire_j, const Vec3& spine_i,
                    const Vec3& t, double spine_length) {
  for (const WirePolyline* wire : {&wire_i, &wire_j}) {
    for (const Vec3& a : wire->points) {
      const Vec3 offset = a - spine_i;
      Vec3 radial;
      if (Unit(offset - offset.dot(t) * t, &radial) >= kAxisFraction * spine_length) return radial;
    }
  }
  return PerpendicularTo(t);
}

}  // namespace

Status BindToWirePair(const Vec3& p, const WirePolyline& wire_i, const WirePolyline& wire_j,
                      const Vec3& spine_i, const Vec3& spine_j, PairBinding* out) {
  if (out == nullptr) return Status::Invalid("out", "must not be null");
  if (!CoordinatesOk(p)) return Status::Invalid("p", kCoordinateReason);
  if (Status s = CheckWire("wire_i", wire_i); !s.ok()) return s;
  if (Status s = CheckWire("wire_j", wire_j); !s.ok()) return s;
  if (!CoordinatesOk(spine_i)) return Status::Invalid("spine_i", kCoordinateReason);
  if (!CoordinatesOk(spine_j)) return Status::Invalid("spine_j", kCoordinateReason);

  PairBinding binding;

  // Step 1: spine direction and p's radial direction.
  Vec3 t;
  const double spine_length = Unit(spine_j - spine_i, &t);
  if (!(spine_length > kCoincidentAbsolute &&
        spine_length > kCoincidentFraction * std::max(MaxAbs(spine_i), MaxAbs(spine_j))))
    return Status::Invalid("spine_j", "must differ from spine_i");
  const double along = std::clamp((p - spine_i).dot(t), 0.0, spine_length);
  const Vec3 closest_on_spine = spine_i + along * t;  // c_m
  const Vec3 offset = p - closest_on_spine;
  Vec3 radial;  // unit r
  if (Unit(offset - offset.dot(t) * t, &radial) < kAxisFraction * spine_length) {
    // Step 2, degenerate: p on the spine line.
    radial = FallbackRadial(wire_i, wire_j, spine_i, t, spine_length);
    binding.flags |= kBindingPlaneDegenerate;
  }
  // Step 2: the plane through p, c_i and c_j (see the top of the file).
  Vec3 plane_normal = PerpendicularTo(t);
  Unit(t.cross(radial), &plane_normal);

  // Step 3: material points on each wire.
  if (!IntersectWire(p, wire_i, spine_i, plane_normal, radial, &binding.k1, &binding.lambda1)) {
    ClosestPointOnWire(p, wire_i, &binding.k1, &binding.lambda1);
    binding.flags |= kBindingMissedFirstWire;
  }
  if (!IntersectWire(p, wire_j, spine_j, plane_normal, radial, &binding.k2, &binding.lambda2)) {
    ClosestPointOnWire(p, wire_j, &binding.k2, &binding.lambda2);
    binding.flags |= kBindingMissedSecondWire;
  }
  const Vec3 p1 = PointOnWire(wire_i, binding.k1, binding.lambda1);
  const Vec3 p2 = PointOnWire(wire_j, binding.k2, binding.lambda2);

  // Step 4: the frame.
  const Vec3 center = 0.5 * (spine_i + spine_j);
  Vec3 e_hat = t, normal;
  double length = 0.0;
  const bool regular = FrameAxes(p2 - p1, center - p1, &e_hat, &length, &normal);
  const Vec3 from_p1 = p - p1;
  if (!(length > kMinEdgeFraction * std::max(spine_length, from_p1.norm())))
    return Status::Invalid("p", "binds to coincident points of wire_i and wire_j (p1 == p2)");
  // c on the line p1 p2 at rest: the bind plane holds p1, p2 and p, so its normal is the
  // natural n_f (Apply keeps it, turned with the edge, while the frame stays degenerate).
  if (!regular) normal = OrthonormalizeAgainst(plane_normal, e_hat);
  const Vec3 m_hat = normal.cross(e_hat);

  // Step 5: coordinates in the frame: along e in units of |e|, across it in units of the
  // section's size (SectionUnit).
  const double section = SectionUnit(center - p1, p2 - p1);
  binding.alpha = from_p1.dot(e_hat) / length;
  binding.beta = from_p1.dot(m_hat) / section;
  binding.gamma = from_p1.dot(normal) / section;
  binding.rest_normal = normal;
  binding.rest_edge = e_hat;
  *out = binding;
  return Status::Ok();
}

namespace {

// Apply's frame for deformed wires: p1', e' = p2' - p1', the centre c' and the axes (e_hat,
// m_hat = n_f x e_hat, n_f) as columns. False (axes not set) where the wires meet, e' = 0.
bool DeformedFrame(const PairBinding& binding, const WirePolyline& wire_i,
                   const WirePolyline& wire_j, const Vec3& spine_i, const Vec3& spine_j, Vec3* p1,
                   Vec3* e, Vec3* center, Mat3* axes) {
  *p1 = PointOnWire(wire_i, binding.k1, binding.lambda1);
  const Vec3 p2 = PointOnWire(wire_j, binding.k2, binding.lambda2);
  *center = 0.5 * (spine_i + spine_j);
  *e = p2 - *p1;
  Vec3 e_hat, normal;
  double length = 0.0;
  const bool regular = FrameAxes(*e, *center - *p1, &e_hat, &length, &normal);
  if (length == 0.0) return false;
  if (!regular)
    normal = OrthonormalizeAgainst(MinimalRotation(binding.rest_edge, e_hat, binding.rest_normal),
                                   e_hat);
  axes->col(0) = e_hat;
  axes->col(1) = normal.cross(e_hat);
  axes->col(2) = normal;
  return true;
}

}  // namespace

Vec3 ApplyPairBinding(const PairBinding& binding, const WirePolyline& wire_i,
                      const WirePolyline& wire_j, const Vec3& spine_i, const Vec3& spine_j) {
  Vec3 p1, e, center;
  Mat3 axes;
  // No frame where the wires meet: p1'.
  if (!DeformedFrame(binding, wire_i, wire_j, spine_i, spine_j, &p1, &e, &center, &axes)) return p1;
  return p1 + binding.alpha * e +
         SectionUnit(center - p1, e) * (binding.beta * axes.col(1) + binding.gamma * axes.col(2));
}

bool ApplyPairFrame(const PairBinding& binding, const WirePolyline& wire_i,
                    const WirePolyline& wire_j, const Vec3& spine_i, const Vec3& spine_j,
                    Mat3* axes) {
  Vec3 p1, e, center;
  return DeformedFrame(binding, wire_i, wire_j, spine_i, spine_j, &p1, &e, &center, axes);
}

}  // namespace wirerig
