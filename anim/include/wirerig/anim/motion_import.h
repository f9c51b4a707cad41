// Real motion as clips (docs/motion-import.md): a BVH motion capture retargeted onto a rig
// through a mapping file, and the animations stored in skinned assets played through the rig
// built from the asset's own skeleton. Both give a RawClip of per-part `rotation` tracks (or
// clamped `joint_angles`) and `translation` tracks keyed at the motion's own frames, linear in
// between, which BuildClip builds against the same model and Playback plays.
//
// The composition the clips rely on (clip.h, joint.h): part p's own turn T_p (its rotation
// track, then its joint angles) acts about its spine's root point r_p in rest world axes, with
// its translation track s_p; its parent's motion carries the result. Its world rotation is
// therefore P_p = P_parent T_p, and for a rigid motion M_p wanted in the world,
// T_p = rotation of (M_parent^-1 M_p) and s_p = (M_parent^-1 M_p)(r_p) - r_p.
//
// Retargeting a capture (RetargetMotion), rest-pose aware:
//   * axes: the capture's up axis is turned to +Y (as mesh import does); A is that rotation.
//   * D_j(t) = A W_j(t) A^T: joint j's world rotation away from its rest, in wirerig axes (a
//     BVH joint's rest frame is the world's, motion_capture.h).
//   * each mapped part gets a rest alignment C_p: the root's is the identity (the capture and
//     the rig stand upright facing +Z); a child's is its parent's followed by the least
//     rotation taking the part's rest bone (spine root to tip, d_p) onto the capture's rest bone
//     seen from the parent's alignment: C_p = C_parent S(d_p -> C_parent^T b_j). So a T-pose
//     capture lifts an A-pose rig's arms with no twist relative to the shoulder.
//   * a part above a hinge (an upper arm above an elbow, a thigh above a knee) also turns about
//     its own bone so that the capture's bends of the hinge (the child's capture bone seen from
//     the part's capture frame, its component across the part's bone summed over every frame)
//     fall where flexing the hinge about its +X axis moves the child.
//   * the part's world rotation is P_p(t) = D_j(t) C_p, then turned by the least rotation that
//     takes its bone P_p d_p onto the capture's bone at t (exact already unless zero-length
//     joints sit between the joint and its tip), so every mapped bone points where the
//     capture's does. T_p = P_parent^T P_p; unmapped parts ride on their parent (T_p = I).
//   * a part's bone in the capture runs from its joint to its tip: the mapping's "tip", else the
//     joint mapped to the part's child that continues its chain (the child whose rest bone is
//     most aligned with the part's), else for a part without mapped children the end of the
//     capture's chain below the joint (down the largest subtree, to its End Site).
//   * the root part's translation is s x A (p_root(t) - p_root(first frame)): it starts where
//     the rig stands. s is metres per capture unit: the rig's leg length over the capture's
//     (RootScale::kLegLength), or the mapping's unit_scale. Leg length: from the lowest mapped
//     part (by its rest root point) up to the root part, the sum of the distances between the
//     root points of consecutive parts, leaving out the root's own segment (hip width); for the
//     capture, between the mapped joints' rest positions.
//   * the turns are then fitted to the joints' limits as the mapping's "limits" says
//     (motion_limits.h; by default a spine, neck or head turn beyond three quarters of its range
//     is shared with the joints above it, the limbs clamped), so "every mapped bone points where
//     the capture's does" holds where no limit binds, or everywhere with "limits": "ignore".
//   * rotation vectors are kept continuous from frame to frame (the angle may pass pi).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "wirerig/anim/clip.h"
#include "wirerig/anim/motion_capture.h"
#include "wirerig/anim/motion_mapping.h"
#include "wirerig/io/json_fields.h"
#include "wirerig/io/result.h"
#include "wirerig/rig/mesh.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/runtime/rig_model.h"

namespace wirerig {

struct RetargetOptions {
  std::string clip_name = "motion";
  std::size_t first_frame = 0;
  std::optional<std::size_t> last_frame;  // inclusive; default the last
};

struct RetargetedMotion {
  RawClip clip;                    // duration (last - first) x frame_time (one frame: frame_time)
  double root_scale = 1.0;         // metres per capture unit applied to the root's translation
  double rig_leg_length = 0.0;     // m; 0 when the scale came from unit_scale
  double source_leg_length = 0.0;  // capture units; 0 likewise
  double floor_lift = 0.0;         // m: the most the root was raised to keep the skin above
                                   // the floor (RetargetFloor::kAbove)
};

// Errors name the mapping file and field ("<mapping>: /joints/LeftArm: <capture> has no joint
// of this name", ".../part: the rig has no part \"x\"", ".../tip: \"y\" is not below joint
// \"LeftArm\" in <capture>") or the frame range.
Result<RetargetedMotion> RetargetMotion(const MotionCapture& motion, const MotionMapping& mapping,
                                        const RigModel& model, const RetargetOptions& options = {});

// An animation of a skinned asset (Assimp), played through the rig built from the asset's
// skeleton (skeleton_description.h: one part per kept bone, named after its joint).
struct AssetAnimationOptions {
  std::string clip_name = "motion";
  // Which animation: by name when not empty, else by index.
  std::string animation_name;
  int animation_index = 0;
  // How the asset was imported for the scene's mesh (up axis, unit scale): the animation's
  // transforms are converted the same way.
  ImportOptions import;
};

// Per part: its joint (by name: the part's name, "bone_<j>" for a nameless joint j, or
// "<name>_<k>" for the k-th joint of a repeated name), that joint's node in the animated file
// (by name), and the node's animated world transform G(t) (Assimp's keys: positions and scales
// linear, rotations slerp, held before the first and after the last key). Its motion is
// M_p(t) = rigid(G(t)) bind_p^-1 (Mesh::Joint::bind_global), and its tracks follow the
// composition above. A part whose joint has no node rides on its parent. Keys sit at every key
// time of the animation's channels, from the first (clip time 0) to the last.
//
// Errors: "<file>: holds no animation", "<file>: animation index 3 is out of range: it holds 1
// animation (cylinder_test)", "<file>: no animation named \"x\" (it holds: a, b)", "<file>: no
// node of animation ... matches a part of the rig", a non-finite or absurd key.
Result<RawClip> ClipFromAssetAnimation(const std::filesystem::path& file, const Mesh& mesh,
                                       const RigModel& model,
                                       const AssetAnimationOptions& options = {});

// A scene clip's motion (docs/scene-format.md): {"file": PATH, "mapping": PATH, "frames":
// [first, last]} for a BVH capture, {"file": PATH, "animation": index or name} for an asset.
// Paths are relative to the scene's folder.
struct MotionSource {
  std::filesystem::path file;
  std::filesystem::path mapping;                       // BVH only; required there
  std::optional<std::size_t> first_frame, last_frame;  // BVH only
  std::string animation_name;                          // assets only
  std::optional<int> animation_index;                  // assets only
};

// JSON form, as scene files hold it: ReadMotionSource throws FieldError naming the field (unknown
// fields, a BVH without "mapping", "animation" on a BVH or "mapping"/"frames" on an asset, a
// negative or non-whole index, frames with first > last); MotionSourceToJson writes what
// ReadMotionSource reads back.
MotionSource ReadMotionSource(const JsonObject& object);
nlohmann::json MotionSourceToJson(const MotionSource& source);

// Whether a motion file is read as BVH (by its extension, case-insensitive).
bool IsBvhFile(const std::filesystem::path& file);

// The clip a scene clip with a motion plays: the motion's tracks (the clip named after `clip`,
// with its loop mode) merged with `clip`'s own part and profile tracks (loads, boundaries; a
// part's rotation, translation or joint angles that the motion drives are refused). `folder`
// resolves relative paths; `mesh_file` and `mesh_import` are the scene's mesh, whose import
// options apply when the motion file is that same file (and whose isolation, if set, imports
// any motion file Assimp reads in a child process). Errors are relative to the clip's path:
// a field of its motion object ("/motion/file: ...", "/motion/mapping: ...",
// "/motion/animation: ...", "/motion/frames: ..."), one of its own parts ("/parts/2/...") or a
// track of its own checked against the motion's duration (": parts[0]....").
Result<RawClip> MakeMotionClip(const MotionSource& source, const RawClip& clip,
                               const std::filesystem::path& folder, const Mesh& mesh,
                               const std::filesystem::path& mesh_file,
                               const ImportOptions& mesh_import, const RigModel& model);

}  // namespace wirerig
