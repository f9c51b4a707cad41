// Wire IK in playback ("reach this point", clip.h ReachChannels): for every part whose clip has
// a reach target, the tip force that puts its spine's tip on the target, blended into the
// part's loads by the reach's weight. Small-deflection parts solve WireIkJob (one linear solve,
// exact to round-off); parts with large_deflection solve CorotationalWireIkJob in the plane of
// the rest tangent and the target (Levenberg-Marquardt from the small-deflection force: the
// natural solution, the same whatever was solved before).
//
// Where the target lies for the part: its support is placed by its own pose and its parents'
// poses, each a rigid motion of the rest rig (a parent's own bending is not followed, so the
// placement is exact under rigid parents such as a body moved by dynamics). The target's offset
// from the rest tip, in the tip's rest local axes (x normal, y binormal, z tangent), is what the
// wire must reach: laterally for small deflections (the axial part is out of reach of a lateral
// force), in its plane for large ones.
#pragma once

#include <span>
#include <vector>

#include "wirerig/anim/clip.h"
#include "wirerig/anim/clip_sampling.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

// What the last solve of one reach found.
struct ReachReport {
  double weight = 0.0;          // the blend at that time, in [0, 1]
  double miss = 0.0;            // |tip - target| of the static shape at full weight, m
  bool reached_target = false;  // within the solver's tolerance
  bool force_limited = false;   // the closest point needs more than max_force
  bool beyond_length = false;   // the target is further from the support than the wire is long
};

class ClipReach {
 public:
  // The parts of `clip` with a reach target (model and clip outlive the reach).
  static ClipReach Make(const RigModel& model, const Clip& clip);
  bool empty() const { return parts_.empty(); }

  // How Apply gets each reach's force.
  enum class Solve : int {
    kStep,   // a playback step: solves when kSolveInterval has passed since the kept solve
             // (or the weight just became positive) and keeps it; the force holds in between
    kFresh,  // a frame: solves, keeps nothing
  };
  // The reach solve's rate in playback steps (clip time, s): the force holds in between.
  static constexpr double kSolveInterval = 1.0 / 60.0;

  // Solves (by `solve`) every reach active at clip time t (weight > 0) for the poses in
  // `sample` (rigid parts already posed by the caller) and blends it into those parts' loads:
  // at weight w the part's bending loads scale by 1 - w and the solved tip force adds with w.
  // Frames never change what the steps keep. Never allocates.
  Status Apply(double t, Solve solve, ClipSample* sample);

  std::span<const std::size_t> parts() const { return parts_; }
  std::span<const ReachReport> reports() const { return reports_; }
  // What the steps keep per reach part: its force and when it was solved (for checkpoints:
  // copy out, copy back in).
  struct Kept {
    Vec3 force = Vec3::Zero();  // local axes of the part's tip, N
    double time = -1.0;         // clip time of the solve, s; < 0: none
    int segments = 0;           // the chain's K it was solved on (large curls)
    ReachReport report;
  };
  std::span<const Kept> kept() const { return kept_; }
  void Restore(std::span<const Kept> kept);

 private:
  // Solves reach j at clip time t for the part's sampled loads into *out; the placements are
  // this Apply's.
  Status SolveOne(std::size_t j, double t, const SpineLoads& loads, Kept* out) const;

  const RigModel* model_ = nullptr;
  const Clip* clip_ = nullptr;
  std::vector<std::size_t> parts_;
  std::vector<Kept> kept_;
  std::vector<ReachReport> reports_;
  std::vector<Mat3> rotations_;     // per part: rest world -> world, of the rigid placement
  std::vector<Vec3> translations_;  // per part
};

}  // namespace wirerig
