// RigModel: the runtime's immutable rig, built once (by wirerig::rig's BuildRigModel) and read
// by every frame's evaluation. Per part: the spine at rest (samples at equal arc length with
// rotation-minimizing frames), its stiffness and mass, and its profile wires expressed in the
// spine's frame; per welded mesh vertex: how it follows the wires (the precomputed binding of
// PHYSICS.md section 6 between two adjacent profiles, or rigidly an end profile's frame for
// vertices beyond the first or last profile: the end caps) and, near a joint, how it follows the
// joint's skin bridge.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "wirerig/runtime/curve.h"
#include "wirerig/runtime/joint.h"
#include "wirerig/runtime/rigid_body.h"
#include "wirerig/runtime/section.h"
#include "wirerig/runtime/skin_binding.h"

namespace wirerig {

struct ProfileModel {
  double spine_v = 0.0;  // where the profile sits on its part's spine, in [0, 1]
  bool closed = true;
  std::vector<Vec3> local_points;  // rest points in the spine frame at spine_v: (normal,
                                   // binormal, tangent) coordinates relative to the spine point
  WireStiffness stiffness;
};

enum class SpineKind : int { kRigid = 0, kDeformable = 1 };

struct PartModel {
  std::string name;
  int parent = -1;          // parents come first; -1 for the root
  double attachment = 0.0;  // v on the parent's spine where this part hangs
  SpineKind kind = SpineKind::kDeformable;
  std::vector<Vec3> spine_points;   // rest samples at v_k = k / (n - 1), equal arc length, n >= 2
  std::vector<Frame> spine_frames;  // rest rotation-minimizing frames at the samples
  double spine_length = 0.0;        // m
  WireStiffness spine_stiffness;
  MassProperties mass;  // of the part's enclosed volume (rigid parts), from its skin
  // In order along the spine, at least 2; none for a skinless bone (a clavicle: a rigid spine
  // with a joint and children but no skin or vertices of its own).
  std::vector<ProfileModel> profiles;
  double max_radius = 0.0;  // largest distance from the spine to a profile point at rest, m
  JointModel joint;         // how the part turns on its parent (parts with a parent)
};

// A vertex near a joint follows the joint's skin bridge (joint_bridge.h) by `weight`, on top of
// where its own part puts it: it moves by weight x (the bridge's image of it - its side's rigid
// motion of it), its side being the joint's child if the vertex belongs to the child or to a
// part below it (an arm's skin beside a chest's joint), else the parent (the parent's skin, and
// the skin of other parts near the joint that the joint's skin spreads over). Its own part's
// deformation is kept, and several joints' corrections add.
struct JointInfluence {
  std::int32_t joint = -1;   // the joint's child part; -1: none
  std::uint32_t sample = 0;  // the own part's spine sample nearest the vertex at rest
  double u = 0.0;            // bridge coordinate
  double weight = 0.0;       // in (0, 1]
  double bridge = 0.0;       // JointBinding::bridge
  double section = 1.0;      // JointBinding::section
};

// At most this many joint bridges move one vertex (the top of a chest beside the neck: the
// chest's own joint, the neck's, the head's, both shoulders' and both clavicles'; fewer slots
// drop one of them and its skin jumps where a neighbour kept it: with 6, human.zae's spread
// dropped 522 influences of up to 4.7% of a joint's motion, and a nipple stood still while the
// chest around it bent).
inline constexpr int kJointInfluences = 8;

struct VertexAttachment {
  std::uint32_t part = 0;
  std::uint32_t profile = 0;  // between profiles: the pair (profile, profile + 1); cap: the end
  bool cap = false;
  PairBinding pair;               // between profiles
  Vec3 cap_local = Vec3::Zero();  // cap: rest position in the end profile's spine frame
  std::array<JointInfluence, kJointInfluences> joints;  // the bridges the vertex lies on
  // Whether the vertex lies on the bridge of the joint of child part `joint`.
  bool OnJoint(int joint) const {
    for (const JointInfluence& j : joints)
      if (j.joint == joint) return true;
    return false;
  }
};

// Profile `profile` of `part` at rest in world axes (its spine frame at spine_v applied to its
// local points); *origin (if given) gets the spine point there.
std::vector<Vec3> RestProfilePoints(const PartModel& part, std::size_t profile,
                                    Vec3* origin = nullptr);

struct RigModel {
  std::vector<PartModel> parts;
  std::vector<VertexAttachment> vertices;  // one per welded mesh vertex
  std::vector<Triangle> triangles;         // welded triangles, for normals
};

inline bool IsSkinless(const PartModel& part) { return part.profiles.empty(); }

// The nearest ancestor of part `part` that has skin (its parent, unless that is a skinless
// bone): whose skin the part's joint bridge spreads over. -1 for the root.
inline int SkinParent(const RigModel& model, std::size_t part) {
  int p = model.parts[part].parent;
  while (p >= 0 && IsSkinless(model.parts[std::size_t(p)])) p = model.parts[std::size_t(p)].parent;
  return p;
}

// Whether part `part` lies strictly below part `ancestor` (its child, grandchild, ...).
inline bool IsBelowPart(const RigModel& model, std::size_t part, std::size_t ancestor) {
  for (std::int32_t p = model.parts[part].parent; p >= 0; p = model.parts[std::size_t(p)].parent)
    if (std::size_t(p) == ancestor) return true;
  return false;
}

}  // namespace wirerig
