// Spine curves (paper section 2.2): the centroids of a part's profiles, interpolated by a C2
// cubic spline with rotation-minimizing frames (Curve), and the parameter at which a child
// part's spine attaches to its parent's.
#pragma once

#include <span>

#include "wirerig/io/result.h"
#include "wirerig/rig/profile_curves.h"
#include "wirerig/runtime/curve.h"

namespace wirerig {

// The spine's points, one per profile: the profile's centroid, or its ray origin (on the central
// curve) when some of its points lie on another part (`foreign_points`, from ProfileSet), where
// the loop spills across a junction and its centroid says nothing about this part.
std::vector<Vec3> SpinePoints(std::span<const ProfileCurve> profiles,
                              std::span<const std::size_t> foreign_points);

// Through the spine points, in order (at least 2; coincident points are refused).
Result<Curve> BuildSpineCurve(std::span<const Vec3> spine_points);

// The v in [0, 1] of the point of `spine` closest to `point`.
double ClosestParameter(const Curve& spine, const Vec3& point);

}  // namespace wirerig
