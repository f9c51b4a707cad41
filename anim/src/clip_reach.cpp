#include "wirerig/anim/clip_reach.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "wirerig/runtime/corotational_wire_ik.h"
#include "wirerig/runtime/spine_interpolation.h"
#include "wirerig/runtime/wire_ik.h"

namespace wirerig {
namespace {

// Scales every bending load of a part (its sampled loads live in the sample's buffers).
void ScaleBendingLoads(double factor, std::size_t part, ClipSample* sample) {
  SpineLoads& loads = sample->poses[part].loads;
  std::vector<PointLoad>& points = sample->point_loads[part];
  for (std::size_t i = 0; i < loads.bending_point_loads.size(); ++i) points[i].force *= factor;
  std::vector<LineLoad>& lines = sample->line_loads[part];
  for (std::size_t i = 0; i < loads.bending_line_loads.size(); ++i)
    lines[i].force_per_length *= factor;
  loads.tip_force *= factor;
  loads.tip_couple *= factor;
}

}  // namespace

ClipReach ClipReach::Make(const RigModel& model, const Clip& clip) {
  ClipReach reach;
  reach.model_ = &model;
  reach.clip_ = &clip;
  for (std::size_t p = 0; p < clip.parts.size(); ++p)
    if (!clip.parts[p].reach.target.IsEmpty()) reach.parts_.push_back(p);
  reach.kept_.resize(reach.parts_.size());
  reach.reports_.resize(reach.parts_.size());
  reach.rotations_.resize(model.parts.size());
  reach.translations_.resize(model.parts.size());
  return reach;
}

void ClipReach::Restore(std::span<const Kept> kept) {
  std::copy(kept.begin(), kept.end(), kept_.begin());
}

Status ClipReach::SolveOne(std::size_t j, double t, const SpineLoads& loads, Kept* out) const {
  const std::size_t p = parts_[j];
  const ReachChannels<Track>& channels = clip_->parts[p].reach;
  const PartModel& part = model_->parts[p];
  // The target in rest world coordinates of the part, then its offset from the rest tip in the
  // tip's rest local axes.
  Vec3 target = channels.target.Sample(t);
  if (const int parent = part.parent; channels.parent_frame && parent >= 0)
    target = rotations_[std::size_t(parent)] * target + translations_[std::size_t(parent)];
  const Vec3 rest_target = rotations_[p].transpose() * (target - translations_[p]);
  const Vec3 offset =
      FrameAxes(part.spine_frames.back()).transpose() * (rest_target - part.spine_points.back());
  const double length = part.spine_length, stiffness = part.spine_stiffness.bending;
  const double max_force =
      channels.max_force > 0.0 ? channels.max_force : 16.0 * stiffness / (length * length);
  ReachReport& report = out->report;
  report = ReachReport{};
  out->time = t;
  if (!loads.large_deflection) {
    WireIkResult result;
    WireIkJob ik;
    ik.boundary = loads.boundary;
    ik.length = length;
    ik.bending_stiffness = stiffness;
    ik.axis = Vec3::UnitZ();
    ik.start_displacement = loads.start_displacement;
    ik.target = Vec3(offset.x(), offset.y(), 0.0);
    ik.max_force = max_force;
    ik.forces = std::span<Vec3>(&out->force, 1);
    ik.result = &result;
    if (Status s = ik.Run(); !s) return s;
    report.miss = result.miss;
    report.reached_target = result.reached_target;
    report.force_limited = result.force_limited;
    return Status::Ok();
  }
  // Large curls: the chain's plane holds the rest tangent (X) and the target's lateral offset
  // (Y); its segments turn at most half a radian under the largest force (Validate's bound: 1).
  out->segments = int(std::clamp(std::ceil(2.0 * max_force * length * length / stiffness), 16.0,
                                 double(CorotationalWireJob::kMaxSegments)));
  const Vec3 lateral(offset.x(), offset.y(), 0.0);
  const double across = lateral.norm();
  const Vec3 e1 = across > 1e-12 * length ? Vec3(lateral / across) : Vec3(Vec3::UnitX());
  CorotationalWireIkJob ik;
  ik.wire.boundary = loads.boundary;
  ik.wire.length = length;
  ik.wire.bending_stiffness = stiffness;
  ik.wire.segments = out->segments;
  ik.target = Vec3(length + offset.z(), across, 0.0);
  ik.max_force = max_force;
  // From the small-deflection force for the offset, never the last solve's: a dead tip force
  // reaching a point is not unique, and a search starting from the last one drifts along the
  // solutions (into compression, and on to buckled shapes). The natural one stays put.
  CorotationalWireIkResult result;
  ik.result = &result;
  if (Status s = ik.Run(); !s) return s;
  // Missing a target it cannot reach, the search may end pushing along the wire past its
  // buckling load with (almost) nothing across it: a buckled shape whose side rounding picks,
  // one the evaluation need not reproduce. The push is then held below the buckling load and
  // the closest point is that force's tip.
  const double buckling =
      0.25 * std::numbers::pi * std::numbers::pi * stiffness / (length * length);
  if (!result.reached_target && result.tip_force.x() < -0.9 * buckling &&
      std::abs(result.tip_force.y()) < 1e-3 * std::abs(result.tip_force.x())) {
    CorotationalWireJob wire = ik.wire;
    wire.tip_force = Vec3(-0.9 * buckling, result.tip_force.y(), 0.0);
    CorotationalWireResult tip;
    wire.result = &tip;
    if (Status s = wire.Run(); !s) return s;
    result.tip_force = wire.tip_force;
    result.miss = (tip.tip_position - ik.target).norm();
    result.force_limited = false;
  }
  out->force = result.tip_force.y() * e1 + result.tip_force.x() * Vec3::UnitZ();
  report.miss = result.miss;
  report.reached_target = result.reached_target;
  report.force_limited = result.force_limited;
  report.beyond_length = result.beyond_length;
  return Status::Ok();
}

Status ClipReach::Apply(double t, Solve solve, ClipSample* sample) {
  if (parts_.empty()) return Status::Ok();
  ComposePlacements(*model_, sample->poses, rotations_, translations_);
  for (std::size_t j = 0; j < parts_.size(); ++j) {
    const std::size_t p = parts_[j];
    const ReachChannels<Track>& channels = clip_->parts[p].reach;
    const double weight =
        channels.weight.IsEmpty() ? 1.0 : std::clamp(channels.weight.Sample(t), 0.0, 1.0);
    SpineLoads& loads = sample->poses[p].loads;
    Kept& kept = kept_[j];
    if (!(weight > 0.0)) {
      reports_[j] = ReachReport{};
      if (solve == Solve::kStep) kept.time = -1.0;  // the next reach starts afresh
      continue;
    }
    Kept now = kept;
    const bool due = kept.time < 0.0 || !(t - kept.time < kSolveInterval * (1.0 - 1e-9));
    if (solve == Solve::kFresh || (solve == Solve::kStep && due))
      if (Status s = SolveOne(j, t, loads, &now); !s) return s;
    if (solve == Solve::kStep) kept = now;
    reports_[j] = now.report;
    reports_[j].weight = weight;
    ScaleBendingLoads(1.0 - weight, p, sample);
    loads.tip_force += weight * now.force;
    // The evaluation's chain is the one the force was solved on.
    if (loads.large_deflection) loads.curl_segments = now.segments;
  }
  return Status::Ok();
}

}  // namespace wirerig
