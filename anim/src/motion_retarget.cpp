// Retargeting a BVH motion capture onto a rig through a mapping file (motion_import.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "motion_floor.h"
#include "motion_limits.h"
#include "motion_rotation.h"
#include "wirerig/anim/motion_import.h"
#include "wirerig/io/name_hint.h"

namespace wirerig {
namespace {

// Where a part's bone ends in the capture: joint `joint`'s position plus its world rotation
// times `offset` (an End Site), or nothing (`joint` < 0).
struct Tip {
  int joint = -1;
  Vec3 offset = Vec3::Zero();
};

struct PartSource {
  int joint = -1;  // the capture's joint driving the part, or -1
  Tip tip;
  std::string mapping_key;  // the mapping's key, for messages
};

bool IsBelow(const MotionCapture& motion, int joint, int ancestor) {
  for (int j = motion.joints[std::size_t(joint)].parent; j >= 0;
       j = motion.joints[std::size_t(j)].parent)
    if (j == ancestor) return true;
  return false;
}

// The end of the capture's chain below `joint`: down the child with the largest subtree (the
// first on ties) to a leaf, and its End Site if it has one.
Tip ChainEnd(const MotionCapture& motion, int joint) {
  const std::size_t n = motion.joints.size();
  std::vector<std::size_t> size(n, 1);
  for (std::size_t j = n; j-- > 1;)
    if (motion.joints[j].parent >= 0) size[std::size_t(motion.joints[j].parent)] += size[j];
  int at = joint;
  for (;;) {
    int best = -1;
    for (std::size_t c = std::size_t(at) + 1; c < n; ++c)
      if (motion.joints[c].parent == at && (best < 0 || size[c] > size[std::size_t(best)]))
        best = static_cast<int>(c);
    if (best < 0) break;
    at = best;
  }
  const BvhJoint& leaf = motion.joints[std::size_t(at)];
  return Tip{at, leaf.end_site.value_or(Vec3::Zero())};
}

Vec3 TipPosition(const Tip& tip, const std::vector<BvhPose>& poses) {
  const BvhPose& pose = poses[std::size_t(tip.joint)];
  return pose.position + pose.rotation * tip.offset;
}

Vec3 RestTipPosition(const Tip& tip, const std::vector<Vec3>& rest) {
  return rest[std::size_t(tip.joint)] + tip.offset;
}

// The part's rest bone: its spine's chord, unit; zero when degenerate.
Vec3 RestBone(const PartModel& part) {
  const Vec3 chord = part.spine_points.back() - part.spine_points.front();
  const double length = chord.norm();
  return length > 1e-12 ? Vec3(chord / length) : Vec3::Zero();
}

}  // namespace

Result<RetargetedMotion> RetargetMotion(const MotionCapture& motion, const MotionMapping& mapping,
                                        const RigModel& model, const RetargetOptions& options) {
  const std::string mapping_name =
      mapping.source_file.empty() ? std::string("mapping") : mapping.source_file;
  auto fail = [&](const std::string& pointer, const std::string& reason) {
    return Error{mapping_name + ": " + pointer + ": " + reason};
  };
  if (motion.joints.empty() || motion.frame_count == 0)
    return Error{motion.source + ": holds no motion"};
  const std::size_t first = options.first_frame;
  const std::size_t last = options.last_frame.value_or(motion.frame_count - 1);
  if (first > last || last >= motion.frame_count)
    return Error{"frames: [" + std::to_string(first) + ", " + std::to_string(last) +
                 "] must be first <= last within the capture's frames 0.." +
                 std::to_string(motion.frame_count - 1) + " (" + motion.source + ")"};
  if (const double duration = double(last - first) * motion.frame_time;
      !(duration <= kMaxClipDuration)) {
    char seconds[64];
    std::snprintf(seconds, sizeof seconds, "%.6g s at its Frame Time of %.6g s", duration,
                  motion.frame_time);
    return Error{"frames: [" + std::to_string(first) + ", " + std::to_string(last) + "] of " +
                 motion.source + " last " + seconds + ", more than a clip may (1e6 s)"};
  }

  // Names to indices.
  const std::size_t part_count = model.parts.size();
  std::vector<PartSource> sources(part_count);
  for (const JointMapping& entry : mapping.joints) {
    const std::string pointer = "/joints/" + entry.joint;
    const int joint = motion.FindJoint(entry.joint);
    if (joint < 0) return fail(pointer, motion.source + " has no joint of this name");
    int part = -1;
    for (std::size_t p = 0; p < part_count; ++p)
      if (model.parts[p].name == entry.part) part = static_cast<int>(p);
    if (part < 0) {
      std::vector<std::string> names;
      for (const PartModel& p : model.parts) names.push_back(p.name);
      return fail(pointer + "/part", "the rig has no part \"" + entry.part + "\"" +
                                         NameHint(entry.part, names, "parts"));
    }
    if (sources[std::size_t(part)].joint >= 0)
      return fail(pointer, "part \"" + entry.part + "\" is already driven by joint \"" +
                               sources[std::size_t(part)].mapping_key + "\"");
    PartSource& source = sources[std::size_t(part)];
    source.joint = joint;
    source.mapping_key = entry.joint;
    if (!entry.tip.empty()) {
      const int tip = motion.FindJoint(entry.tip);
      if (tip < 0)
        return fail(pointer + "/tip", motion.source + " has no joint \"" + entry.tip + "\"");
      if (!IsBelow(motion, tip, joint))
        return fail(pointer + "/tip", "\"" + entry.tip + "\" is not below joint \"" + entry.joint +
                                          "\" in " + motion.source);
      source.tip = Tip{tip, Vec3::Zero()};
    }
  }

  const Mat3 axes = SourceUpRotation(mapping.up_axis);  // capture axes -> wirerig axes
  const std::vector<Vec3> rest = BvhRestPositions(motion);
  double extent = 0.0;
  for (const Vec3& p : rest) extent = std::max(extent, (p - rest.front()).norm());
  const double tiny = 1e-9 * std::max(extent, 1e-12);

  // Bones: the rig's at rest, and where each mapped part's bone ends in the capture.
  std::vector<Vec3> rig_bone(part_count), source_bone(part_count, Vec3::Zero());
  std::vector<int> chain_child(part_count, -1);  // the mapped child continuing the chain
  for (std::size_t p = 0; p < part_count; ++p) rig_bone[p] = RestBone(model.parts[p]);
  for (std::size_t p = 0; p < part_count; ++p) {
    PartSource& source = sources[p];
    if (source.joint < 0) continue;
    double best = -2.0;
    for (std::size_t c = p + 1; c < part_count; ++c) {
      if (model.parts[c].parent != static_cast<int>(p) || sources[c].joint < 0) continue;
      const double aligned = rig_bone[c].dot(rig_bone[p]);
      if (aligned > best) {
        best = aligned;
        chain_child[p] = static_cast<int>(c);
      }
    }
    if (source.tip.joint < 0) {
      if (chain_child[p] >= 0) {
        const int tip = sources[std::size_t(chain_child[p])].joint;
        if (IsBelow(motion, tip, source.joint)) source.tip = Tip{tip, Vec3::Zero()};
      } else {
        source.tip = ChainEnd(motion, source.joint);
      }
    }
    if (source.tip.joint >= 0 &&
        (RestTipPosition(source.tip, rest) - rest[std::size_t(source.joint)]).norm() <= tiny)
      source.tip = Tip{};  // a zero-length bone: no direction to match
    if (source.tip.joint >= 0)
      source_bone[p] =
          (axes * (RestTipPosition(source.tip, rest) - rest[std::size_t(source.joint)]))
              .normalized();
  }

  // How the capture bends each hinge below a mapped part (an elbow below its upper arm, a knee
  // below its thigh): the child's bone seen from the part's capture frame, its component across
  // the part's bone summed over every frame (so deeper bends weigh more).
  std::vector<Vec3> capture_bend(part_count, Vec3::Zero());
  std::vector<std::size_t> hinge_parents;
  for (std::size_t p = 1; p < part_count; ++p) {
    const int c = chain_child[p];
    if (c < 0 || model.parts[std::size_t(c)].joint.type != JointType::kHinge) continue;
    if (sources[p].tip.joint < 0 || sources[std::size_t(c)].tip.joint < 0) continue;
    hinge_parents.push_back(p);
  }
  if (!hinge_parents.empty()) {
    std::vector<BvhPose> poses;
    for (std::size_t f = 0; f < motion.frame_count; ++f) {
      PoseBvhFrame(motion, f, poses);
      for (std::size_t p : hinge_parents) {
        const PartSource& child = sources[std::size_t(chain_child[p])];
        const Vec3 bone =
            axes * (TipPosition(child.tip, poses) - poses[std::size_t(child.joint)].position);
        if (!(bone.norm() > tiny)) continue;
        const Mat3 parent_rotation =
            axes * poses[std::size_t(sources[p].joint)].rotation * axes.transpose();
        const Vec3 seen = parent_rotation.transpose() * bone.normalized();
        capture_bend[p] += seen - seen.dot(source_bone[p]) * source_bone[p];
      }
    }
  }

  // Rest alignments: the root's the identity; a child's its parent's, then the least rotation
  // onto the capture's bone; a part above a hinge also turns about its own bone so that the
  // capture's bends fall in the hinge's plane, on its side (flexion is about the hinge axis).
  std::vector<Mat3> alignment(part_count, Mat3::Identity());
  for (std::size_t p = 0; p < part_count; ++p) {
    const PartModel& part = model.parts[p];
    const Mat3 parent_alignment =
        part.parent < 0 ? Mat3::Identity() : alignment[std::size_t(part.parent)];
    alignment[p] = parent_alignment;
    const PartSource& source = sources[p];
    if (part.parent < 0 || source.joint < 0 || source.tip.joint < 0 ||
        !(rig_bone[p].squaredNorm() > 0.0))
      continue;
    alignment[p] = parent_alignment *
                   LeastRotation(rig_bone[p], parent_alignment.transpose() * source_bone[p]);
    if (chain_child[p] < 0 || capture_bend[p].norm() < 1e-3 * double(motion.frame_count)) continue;
    const Vec3 bend = alignment[p].transpose() * capture_bend[p];  // rig rest axes, across
    const JointModel& hinge = model.parts[std::size_t(chain_child[p])].joint;
    // Where flexing about the hinge axis (+X) moves the child bone, across the part's bone.
    Vec3 want = hinge.axes.col(0).cross(rig_bone[p]);
    want -= want.dot(rig_bone[p]) * rig_bone[p];
    if (!(want.norm() > 1e-6)) continue;
    const double twist = std::atan2(want.normalized().cross(bend.normalized()).dot(rig_bone[p]),
                                    want.normalized().dot(bend.normalized()));
    alignment[p] = alignment[p] * Mat3(Eigen::AngleAxisd(twist, rig_bone[p]));
  }

  // The root's translation scale.
  RetargetedMotion out;
  const int root_joint = part_count > 0 ? sources[0].joint : -1;
  if (root_joint >= 0 && mapping.root_scale == RootScale::kLegLength) {
    int lowest = -1;
    for (std::size_t p = 1; p < part_count; ++p)
      if (sources[p].joint >= 0 &&
          (lowest < 0 || model.parts[p].spine_points.front().y() <
                             model.parts[std::size_t(lowest)].spine_points.front().y()))
        lowest = static_cast<int>(p);
    std::vector<int> path;
    for (int p = lowest; p >= 0; p = model.parts[std::size_t(p)].parent) path.push_back(p);
    bool usable = path.size() >= 3;
    for (std::size_t i = 0; usable && i + 2 < path.size(); ++i) {
      const std::size_t a = std::size_t(path[i]), b = std::size_t(path[i + 1]);
      if (sources[a].joint < 0 || sources[b].joint < 0) {
        usable = false;
        break;
      }
      out.rig_leg_length +=
          (model.parts[a].spine_points.front() - model.parts[b].spine_points.front()).norm();
      out.source_leg_length +=
          (rest[std::size_t(sources[a].joint)] - rest[std::size_t(sources[b].joint)]).norm();
    }
    if (!usable || !(out.rig_leg_length > 0.0) || !(out.source_leg_length > tiny))
      return fail("/root_scale",
                  "\"leg_length\" needs the lowest mapped part to hang from the root through at "
                  "least two mapped parts of non-zero length (a thigh and a shin); use \"unit\"");
    out.root_scale = out.rig_leg_length / out.source_leg_length;
  } else {
    out.root_scale = mapping.unit_scale;
  }

  // Every frame: the wanted world rotations, fitted to the joints' limits, then each part's
  // own turn.
  RawClip& clip = out.clip;
  clip.name = options.clip_name;
  clip.duration = first == last ? motion.frame_time : double(last - first) * motion.frame_time;
  std::vector<RawPartTracks> tracks(part_count);
  for (std::size_t p = 0; p < part_count; ++p) tracks[p].part = model.parts[p].name;
  std::vector<char> driven(part_count);
  for (std::size_t p = 0; p < part_count; ++p) driven[p] = sources[p].joint >= 0;
  std::vector<char> hands_up(part_count, 0);
  if (mapping.limits == RetargetLimits::kPassToParents)
    hands_up = HandsUpToParent(model, chain_child, driven);
  JointLimitFit fit(model, driven, std::move(hands_up), mapping.limits != RetargetLimits::kIgnore);
  std::vector<BvhPose> poses;
  std::vector<Mat3> wanted(part_count, Mat3::Identity());
  std::vector<std::optional<Vec3>> previous(part_count);
  Vec3 root_start = Vec3::Zero();
  for (std::size_t f = first; f <= last; ++f) {
    PoseBvhFrame(motion, f, poses);
    const double time = double(f - first) * motion.frame_time;
    for (std::size_t p = 0; p < part_count; ++p) {
      const PartSource& source = sources[p];
      if (source.joint < 0) continue;
      const BvhPose& pose = poses[std::size_t(source.joint)];
      Mat3 rotation = axes * pose.rotation * axes.transpose() * alignment[p];
      if (model.parts[p].parent >= 0 && source.tip.joint >= 0 && rig_bone[p].squaredNorm() > 0.0) {
        const Vec3 bone = axes * (TipPosition(source.tip, poses) - pose.position);
        if (bone.norm() > tiny)
          rotation = LeastRotation(rotation * rig_bone[p], bone.normalized()) * rotation;
      }
      wanted[p] = rotation;
    }
    fit.Fit(wanted);
    for (std::size_t p = 0; p < part_count; ++p) {
      const PartModel& part = model.parts[p];
      if (!driven[p]) continue;
      const Mat3& turn = fit.turns()[p];
      if (part.parent >= 0 && mapping.channels == RetargetChannels::kJointAngles) {
        const Vec3 angles = ClampJointAngles(part.joint, JointAnglesOf(part.joint, turn));
        tracks[p].channels.joint_angles.keys.push_back({time, angles, Interpolation::kLinear});
      } else {
        const Vec3 vector = ContinuousRotationVector(turn, previous[p]);
        previous[p] = vector;
        tracks[p].channels.rotation.keys.push_back({time, vector, Interpolation::kLinear});
      }
      if (part.parent < 0) {
        const Vec3& position = poses[std::size_t(sources[p].joint)].position;
        if (f == first) root_start = position;
        const Vec3 shift = out.root_scale * (axes * (position - root_start));
        tracks[p].channels.translation.keys.push_back({time, shift, Interpolation::kLinear});
      }
    }
  }
  for (RawPartTracks& t : tracks)
    if (!t.channels.rotation.keys.empty() || !t.channels.joint_angles.keys.empty())
      clip.parts.push_back(std::move(t));
  if (std::string error = ValidateRawClip(clip); !error.empty())
    return Error{motion.source + ": the retargeted clip is not valid: " + error};
  if (mapping.floor == RetargetFloor::kAbove && root_joint >= 0) {
    Result<double> lift = LiftAboveFloor(model, model.parts[0].name, &clip);
    if (!lift) return Error{motion.source + ": " + lift.error()};
    out.floor_lift = lift.value();
  }
  return out;
}

}  // namespace wirerig
