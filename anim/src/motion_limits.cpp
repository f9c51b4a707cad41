#include "motion_limits.h"

#include <utility>

#include "motion_rotation.h"

namespace wirerig {

Mat3 ClampTurn(const JointModel& joint, const Mat3& turn, bool* bound) {
  const Vec3 angles = JointAnglesOf(joint, turn);
  const Vec3 clamped = ClampJointAngles(joint, angles);
  *bound = (clamped - angles).cwiseAbs().maxCoeff() > 1e-9;
  return *bound ? Mat3(JointRotation(joint, clamped).toRotationMatrix()) : turn;
}

JointModel ComfortableRange(const JointModel& joint) {
  JointModel out = joint;
  const Vec3 rest = ClampJointAngles(joint, Vec3::Zero());
  out.min_degrees = rest + kComfortableRange * (joint.min_degrees - rest);
  out.max_degrees = rest + kComfortableRange * (joint.max_degrees - rest);
  return out;
}

std::vector<char> HandsUpToParent(const RigModel& model, const std::vector<int>& chain_child,
                                  const std::vector<char>& driven) {
  std::vector<char> out(model.parts.size(), 0);
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const int parent = model.parts[p].parent;
    if (parent < 0 || model.parts[std::size_t(parent)].parent < 0) continue;
    const PartModel& up = model.parts[std::size_t(parent)];
    out[p] = driven[std::size_t(parent)] && up.joint.type == JointType::kBall &&
             model.parts[p].joint.type == JointType::kBall &&
             chain_child[std::size_t(parent)] == static_cast<int>(p);
  }
  return out;
}

JointLimitFit::JointLimitFit(const RigModel& model, std::vector<char> driven,
                             std::vector<char> hands_up, bool clamp)
    : model_(model),
      driven_(std::move(driven)),
      hands_up_(std::move(hands_up)),
      clamp_(clamp),
      turns_(model.parts.size(), Mat3::Identity()),
      world_(model.parts.size(), Mat3::Identity()) {}

void JointLimitFit::Fit(const std::vector<Mat3>& wanted) {
  for (std::size_t p = 0; p < model_.parts.size(); ++p) {
    const PartModel& part = model_.parts[p];
    const Mat3 above = part.parent < 0 ? Mat3::Identity() : world_[std::size_t(part.parent)];
    if (!driven_[p]) {
      turns_[p] = Mat3::Identity();
    } else if (part.parent < 0 || !clamp_) {
      turns_[p] = above.transpose() * wanted[p];
    } else {
      bool bound = false;
      const Mat3 want = above.transpose() * wanted[p];
      turns_[p] = ClampTurn(hands_up_[p] ? ComfortableRange(part.joint) : part.joint, want, &bound);
      if (bound && hands_up_[p]) {
        // Beyond its comfortable range: the chain takes that within its own comfortable
        // ranges, the part takes back what is left up to its limits, the chain the rest up to
        // theirs.
        HandUp(static_cast<int>(p), wanted[p], true);
        const Mat3& moved = world_[std::size_t(part.parent)];
        turns_[p] = ClampTurn(part.joint, moved.transpose() * wanted[p], &bound);
        if (bound) {
          HandUp(static_cast<int>(p), wanted[p], false);
        } else {
          world_[p] = moved * turns_[p];
        }
        continue;
      }
    }
    world_[p] = above * turns_[p];
  }
}

void JointLimitFit::HandUp(int part, const Mat3& wanted, bool comfortable) {
  // W_part = W_a * below, below the turns from a's chain child down to `part`: each ancestor a
  // takes what it can of W_a' = wanted below^T, seen from its own parent.
  Mat3 below = turns_[std::size_t(part)];
  int top = part;
  for (int c = part; hands_up_[std::size_t(c)];) {
    const int a = model_.parts[std::size_t(c)].parent;
    const int above = model_.parts[std::size_t(a)].parent;  // >= 0: a is not the root
    bool bound = false;
    turns_[std::size_t(a)] =
        ClampTurn(comfortable ? ComfortableRange(model_.parts[std::size_t(a)].joint)
                              : model_.parts[std::size_t(a)].joint,
                  world_[std::size_t(above)].transpose() * wanted * below.transpose(), &bound);
    below = turns_[std::size_t(a)] * below;
    top = c = a;
    if (!bound) break;  // the rest taken whole
  }
  // The worlds from the topmost moved ancestor on (parents first; parts before it unchanged).
  for (int q = top; q <= part; ++q) {
    const int parent = model_.parts[std::size_t(q)].parent;
    world_[std::size_t(q)] = parent < 0
                                 ? turns_[std::size_t(q)]
                                 : Mat3(world_[std::size_t(parent)] * turns_[std::size_t(q)]);
  }
}

}  // namespace wirerig
