// Binding mesh vertices between two adjacent profile wires (paper section 5, in the robust
// precomputed form of PHYSICS.md section 6). Bind once at rest; apply every frame.
//
// A vertex p between profile wires W_i, W_{i+1} (closed or open polylines) with spine points
// c_i, c_{i+1}: in the plane through p, c_i and c_{i+1}, find the material points p_1 on W_i and
// p_2 on W_{i+1} (stored as segment k and fraction lambda); in the frame built from p_1, p_2
// and c = (c_i + c_{i+1})/2 store alpha, beta, gamma. Apply rebuilds the frame from the
// deformed wires and spine points and reproduces p exactly at rest, rigidly under rigid
// motion, with similar triangles under uniform scale.
//
// One departure from PHYSICS.md section 6: p's height off the edge e = p2 - p1 (beta, gamma)
// is measured in units of the section's size SectionUnit(c - p1, e) ~ |c - p1|, not of |e|.
// The two agree under rigid motion and uniform scale; where the flesh is strained unevenly they
// do not: e runs along the bone, so a limb shortened by 14% and widened by 8% (axial load,
// volume kept) shrank in |e| every height it should have widened, and skin bound far from its
// wires (an armpit's crease) jumped by 2 cm while its neighbours moved 1 mm.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>

#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

// SectionUnit's share of the edge, squared.
inline constexpr double kEdgeInSectionUnit2 = 1e-6;

// One wire: a polyline of points, closed (last joins first) or open.
struct WirePolyline {
  std::span<const Vec3> points;
  bool closed = false;
};

// The unit of a bound point's height: sqrt(|c - p1|^2 + (1e-3 |e|)^2), the distance from the
// edge's first point to the pair's spine centre (the section's size, scaling as the section
// does), with a thousandth of the edge so it never vanishes where a wire meets the spine.
inline double SectionUnit(const Vec3& to_center, const Vec3& e) {
  return std::sqrt(to_center.squaredNorm() + kEdgeInSectionUnit2 * e.squaredNorm());
}

// Flags recording which fallback of PHYSICS.md section 6 fired at bind time.
enum BindingFlags : std::uint8_t {
  kBindingPlaneDegenerate = 1,  // p on the spine line: plane from the first wire's point
  kBindingMissedFirstWire = 2,  // the plane met no point of W_i on p's side: closest point used
  kBindingMissedSecondWire = 4,
};

struct PairBinding {
  std::uint32_t k1 = 0;  // segment of W_i: points k1 and k1 + 1 (wrapping when closed)
  double lambda1 = 0.0;  // fraction along that segment
  std::uint32_t k2 = 0;
  double lambda2 = 0.0;
  double alpha = 0.0, beta = 0.0, gamma = 0.0;
  Vec3 rest_normal = Vec3::UnitZ();  // n_f at rest, for the degenerate-frame fallback
  Vec3 rest_edge = Vec3::UnitX();    // unit e at rest, likewise
  std::uint8_t flags = 0;
};

// Binds p to the pair. Refuses, naming the field ("p", "wire_i", "wire_j", "spine_i",
// "spine_j", "out"): a null out; non-finite coordinates or coordinates beyond 1e100 m;
// wires with fewer than 2 points; spine points that coincide (to 1e-12 of their magnitude);
// and ("p") a vertex whose material points on the two wires coincide, p1 == p2 (the wires
// meet there; |p2 - p1| <= 1e-12 max(|c_j - c_i|, |p - p1|)), where no frame exists.
// *out is written only on success. Degenerate configurations use these fallbacks:
//  * p within 1e-9 |c_j - c_i| of the spine line (kBindingPlaneDegenerate): the plane holds
//    the spine line and w_i[0] (or the first point of wire_i, then wire_j, off that line;
//    a world axis if there is none), and "p's side" is that point's side, for every such
//    vertex of the pair alike.
//  * No plane hit on p's side of a wire (kBindingMissed*): the closest point of that wire.
//  * A vertex of a wire lying in the plane (p on a wire, tangency) counts as one hit.
//  * c on the line p1 p2 at rest: n_f is the bind plane's normal (no flag).
Status BindToWirePair(const Vec3& p, const WirePolyline& wire_i, const WirePolyline& wire_j,
                      const Vec3& spine_i, const Vec3& spine_j, PairBinding* out);

// The bound point for deformed wires (same point counts as at bind time) and spine points,
// all finite with coordinates within 1e100 m (not checked: this is the per-frame path).
// Allocation-free; never NaN, Inf or a floating-point exception. Degenerate frames:
//  * e' x (c' - p1') ~ 0 (sine of the angle below 1e-8): n_f' is the rest normal turned by
//    the minimal rotation taking the rest edge to e', then made perpendicular to e'; if e'
//    is reversed (1 + cos < 1e-6) the half turn about the rest normal is used (n_f' = n_f).
//  * e' = 0 (the wires meet): returns p1' (no frame exists).
Vec3 ApplyPairBinding(const PairBinding& binding, const WirePolyline& wire_i,
                      const WirePolyline& wire_j, const Vec3& spine_i, const Vec3& spine_j);

// The frame ApplyPairBinding builds for the same arguments, as the columns of a rotation:
// e_hat, m_hat = n_f x e_hat, n_f (the degenerate-frame fallback above included). False, with
// *axes unchanged, where e' = 0 (no frame). The rest frame is (rest_edge, rest_normal x
// rest_edge, rest_normal).
bool ApplyPairFrame(const PairBinding& binding, const WirePolyline& wire_i,
                    const WirePolyline& wire_j, const Vec3& spine_i, const Vec3& spine_j,
                    Mat3* axes);

}  // namespace wirerig
