// ValidateRigModel (rig_asset.h): what must hold before a model from outside (a parsed asset)
// may be evaluated.
#include <algorithm>
#include <cmath>

#include "wirerig/runtime/rig_asset.h"

namespace wirerig {
namespace {

// Geometry and binding numbers are bounded, not just finite: a character is far smaller than
// 1000 km, and a number past float range would overflow the float evaluation.
constexpr double kMaxMagnitude = 1e6;

bool Finite(double x) { return std::isfinite(x) && std::abs(x) <= kMaxMagnitude; }
bool Finite(const Vec3& v) { return Finite(v.x()) && Finite(v.y()) && Finite(v.z()); }
bool Finite(const Mat3& m) {
  return Finite(Vec3(m.col(0))) && Finite(Vec3(m.col(1))) && Finite(Vec3(m.col(2)));
}
bool Unit(const Vec3& v) { return Finite(v) && std::abs(v.norm() - 1.0) < 1e-6; }
bool Fraction(double x) { return x >= 0.0 && x <= 1.0; }
// Stiffness, mass and inertia: finite and not negative (steel's EA is ~1e9 N).
bool Physical(double x) { return std::isfinite(x) && x >= 0.0 && x <= 1e30; }
// A stiffness the wire jobs can solve with: with lengths below 1e6 m, L^3 / EI and L / EA stay
// far from overflow (AxialJob and BendingJob refuse zero, and EI so small L^3 / EI overflows).
bool Stiff(double x) { return std::isfinite(x) && x >= 1e-30 && x <= 1e30; }

Status ValidatePart(const RigModel& model, std::size_t i) {
  const PartModel& p = model.parts[i];
  const int index = int(i);
  if (p.parent >= index || p.parent < -1 || (i == 0 && p.parent != -1))
    return Status::InvalidElement("parts", index, "parent",
                                  "must be -1 (a root, as the first part is) or an earlier part");
  if (p.kind != SpineKind::kRigid && p.kind != SpineKind::kDeformable)
    return Status::InvalidElement("parts", index, "kind", "must be rigid or deformable");
  if (p.spine_points.size() < 2 || p.spine_frames.size() != p.spine_points.size())
    return Status::InvalidElement("parts", index, "spine_points",
                                  "need at least 2 samples, with one frame each");
  for (const Vec3& q : p.spine_points)
    if (!Finite(q)) return Status::InvalidElement("parts", index, "spine_points", "must be finite");
  for (const Frame& f : p.spine_frames)
    if (!Unit(f.tangent) || !Unit(f.normal) || !Unit(f.binormal))
      return Status::InvalidElement("parts", index, "spine_frames", "must be unit vectors");
  if (!(Finite(p.attachment) && p.attachment >= 0.0 && p.attachment <= 1.0))
    return Status::InvalidElement("parts", index, "attachment", "must lie in [0, 1]");
  if (!(Finite(p.spine_length) && p.spine_length > 1e-9) || !Finite(p.max_radius))
    return Status::InvalidElement("parts", index, "spine_length",
                                  "must be positive and below 1e6 m");
  if (!Physical(p.spine_stiffness.axial) || !Physical(p.spine_stiffness.bending))
    return Status::InvalidElement("parts", index, "spine_stiffness", "must be finite and >= 0");
  if (p.kind == SpineKind::kDeformable &&
      (!Stiff(p.spine_stiffness.axial) || !Stiff(p.spine_stiffness.bending)))
    return Status::InvalidElement("parts", index, "spine_stiffness",
                                  "must lie in [1e-30, 1e30] for a deformable part");
  const MassProperties& m = p.mass;
  if (!Physical(m.volume) || !Physical(m.mass) || !Finite(m.center) || !m.inertia.allFinite() ||
      !Finite(m.principal_axes) || !m.principal_moments.allFinite())
    return Status::InvalidElement("parts", index, "mass", "must be finite");
  // A skinless bone (no profiles) is a rigid segment between a parent and at least one child.
  if (p.profiles.empty() && (i == 0 || p.kind != SpineKind::kRigid ||
                             std::none_of(model.parts.begin() + index + 1, model.parts.end(),
                                          [&](const PartModel& c) { return c.parent == index; })))
    return Status::InvalidElement("parts", index, "profiles",
                                  "none only for a rigid, skinless bone with a parent and a child");
  if (p.profiles.size() == 1)
    return Status::InvalidElement("parts", index, "profiles", "need at least 2 (or none)");
  for (const ProfileModel& profile : p.profiles) {
    if (!(Finite(profile.spine_v) && profile.spine_v >= 0.0 && profile.spine_v <= 1.0))
      return Status::InvalidElement("parts", index, "profiles", "spine_v must lie in [0, 1]");
    if (profile.local_points.size() < 2)
      return Status::InvalidElement("parts", index, "profiles", "need at least 2 points each");
    for (const Vec3& q : profile.local_points)
      if (!Finite(q)) return Status::InvalidElement("parts", index, "profiles", "must be finite");
    if (!Stiff(profile.stiffness.axial) || !Stiff(profile.stiffness.bending))
      return Status::InvalidElement("parts", index, "profiles",
                                    "stiffness must lie in [1e-30, 1e30]");
  }
  const JointType type = p.joint.type;
  if (type != JointType::kBall && type != JointType::kHinge && type != JointType::kFixed)
    return Status::InvalidElement("parts", index, "joint", "type must be ball, hinge or fixed");
  if (!Finite(p.joint.axes) || !Finite(p.joint.parent_axis))
    return Status::InvalidElement("parts", index, "joint", "axes must be finite");
  if (Status s = ValidateJoint(p.joint); !s)
    return Status::InvalidElement("parts", index, "joint", s.reason);
  if (!Finite(p.joint.blend_length) || !Finite(p.joint.radius) || !Finite(p.joint.parent_radius))
    return Status::InvalidElement("parts", index, "joint", "lengths must be below 1e6 m");
  return Status::Ok();
}

// Whether a wire point index starts a segment of the profile (wrapping when closed).
bool SegmentOf(const ProfileModel& profile, std::uint32_t k) {
  const std::size_t n = profile.local_points.size();
  return profile.closed ? k < n : k + 1 < n;
}

Status ValidateVertex(const RigModel& model, std::size_t v) {
  const VertexAttachment& a = model.vertices[v];
  const int index = int(v);
  if (a.part >= model.parts.size())
    return Status::InvalidElement("vertices", index, "part", "names a part the model lacks");
  const PartModel& part = model.parts[a.part];
  const std::size_t profiles = part.profiles.size();
  // In size_t: a pair's profile + 1 must not wrap round (0xFFFFFFFF + 1 is 0 in 32 bits).
  if (a.cap ? a.profile >= profiles : std::size_t(a.profile) + 1 >= profiles)
    return Status::InvalidElement("vertices", index, "profile", "names a profile the part lacks");
  if (a.cap) {
    if (!Finite(a.cap_local))
      return Status::InvalidElement("vertices", index, "cap_local", "must be finite");
  } else {
    const PairBinding& b = a.pair;
    if (!SegmentOf(part.profiles[a.profile], b.k1) ||
        !SegmentOf(part.profiles[a.profile + 1], b.k2))
      return Status::InvalidElement("vertices", index, "pair", "names a wire point out of range");
    if (!Finite(b.lambda1) || !Finite(b.lambda2) || !Finite(b.alpha) || !Finite(b.beta) ||
        !Finite(b.gamma) || !Unit(b.rest_normal) || !Unit(b.rest_edge))
      return Status::InvalidElement("vertices", index, "pair",
                                    "must be finite, with unit rest directions");
  }
  for (const JointInfluence& j : a.joints) {
    if (j.joint < 0) continue;
    if (std::size_t(j.joint) >= model.parts.size() || model.parts[std::size_t(j.joint)].parent < 0)
      return Status::InvalidElement("vertices", index, "joints", "name a part with no joint");
    if (j.sample >= part.spine_points.size())
      return Status::InvalidElement("vertices", index, "joints",
                                    "name a spine sample past the end");
    if (!(Fraction(j.u) && Fraction(j.weight) && Fraction(j.bridge) && Fraction(j.section)))
      return Status::InvalidElement("vertices", index, "joints",
                                    "u, weight, bridge and section must lie in [0, 1]");
  }
  return Status::Ok();
}

}  // namespace

Status ValidateRigModel(const RigModel& model) {
  if (model.parts.empty()) return Status::Invalid("parts", "need at least one part");
  for (std::size_t i = 0; i < model.parts.size(); ++i)
    if (Status s = ValidatePart(model, i); !s) return s;
  for (std::size_t v = 0; v < model.vertices.size(); ++v)
    if (Status s = ValidateVertex(model, v); !s) return s;
  for (std::size_t t = 0; t < model.triangles.size(); ++t)
    for (std::uint32_t corner : model.triangles[t])
      if (corner >= model.vertices.size())
        return Status::InvalidElement("triangles", int(t), "", "name a vertex the model lacks");
  return Status::Ok();
}

}  // namespace wirerig
