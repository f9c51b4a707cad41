#include "wirerig/anim/clip_reach.h"

#include <algorithm>
#include <cmath>

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
  reach.kept_.assign(reach.parts_.size(), Vec3::Zero());
  reach.reports_.resize(reach.parts_.size());
  reach.rotations_.resize(model.parts.size());
  reach.translations_.resize(model.parts.size());
  return reach;
}

void ClipReach::Restore(std::span<const Vec3> forces) {
  std::copy(forces.begin(), forces.end(), kept_.begin());
}

Status ClipReach::Apply(double t, bool keep, ClipSample* sample) {
  if (parts_.empty()) return Status::Ok();
  // Every part's rigid placement x -> rotation x + translation (rest world -> world); parents
  // come before their children in a rig.
  for (std::size_t p = 0; p < model_->parts.size(); ++p) {
    const PartPose& pose = sample->poses[p];
    const Mat3 r = pose.rotation.toRotationMatrix();
    const Vec3 root = model_->parts[p].spine_points.front();
    rotations_[p] = r;
    translations_[p] = root - r * root + pose.translation;
    if (const int parent = model_->parts[p].parent; parent >= 0) {
      translations_[p] =
          rotations_[std::size_t(parent)] * translations_[p] + translations_[std::size_t(parent)];
      rotations_[p] = rotations_[std::size_t(parent)] * r;
    }
  }
  for (std::size_t j = 0; j < parts_.size(); ++j) {
    const std::size_t p = parts_[j];
    const ReachChannels<Track>& channels = clip_->parts[p].reach;
    ReachReport& report = reports_[j];
    report = ReachReport{};
    report.weight =
        channels.weight.IsEmpty() ? 1.0 : std::clamp(channels.weight.Sample(t), 0.0, 1.0);
    if (!(report.weight > 0.0)) continue;
    const PartModel& part = model_->parts[p];
    SpineLoads& loads = sample->poses[p].loads;
    // The target's offset from the rest tip, in the tip's rest local axes.
    const Vec3 rest_target =
        rotations_[p].transpose() * (channels.target.Sample(t) - translations_[p]);
    const Vec3 offset =
        FrameAxes(part.spine_frames.back()).transpose() * (rest_target - part.spine_points.back());
    const double length = part.spine_length, stiffness = part.spine_stiffness.bending;
    const double max_force =
        channels.max_force > 0.0 ? channels.max_force : 16.0 * stiffness / (length * length);
    // Large curls: chain segments turning at most half a radian under the largest force
    // (CorotationalWireJob::Validate's bound is 1).
    const int segments = int(std::clamp(std::ceil(2.0 * max_force * length * length / stiffness),
                                        16.0, double(CorotationalWireJob::kMaxSegments)));
    Vec3 force = Vec3::Zero();
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
      ik.forces = std::span<Vec3>(&force, 1);
      ik.result = &result;
      if (Status s = ik.Run(); !s) return s;
      report.miss = result.miss;
      report.reached_target = result.reached_target;
      report.force_limited = result.force_limited;
    } else {
      // The chain's plane: the rest tangent (X) and the target's lateral offset (Y).
      const Vec3 lateral(offset.x(), offset.y(), 0.0);
      const double across = lateral.norm();
      const Vec3 e1 = across > 1e-12 * length ? Vec3(lateral / across) : Vec3(Vec3::UnitX());
      CorotationalWireIkResult result;
      CorotationalWireIkJob ik;
      ik.wire.boundary = loads.boundary;
      ik.wire.length = length;
      ik.wire.bending_stiffness = stiffness;
      // Segments turning at most half a radian under the largest force (Validate's bound is 1).
      ik.wire.segments = segments;
      ik.wire.tip_force = Vec3(kept_[j].z(), kept_[j].dot(e1), 0.0);
      ik.target = Vec3(length + offset.z(), across, 0.0);
      ik.max_force = max_force;
      ik.result = &result;
      if (Status s = ik.Run(); !s) return s;
      force = result.tip_force.y() * e1 + result.tip_force.x() * Vec3::UnitZ();
      report.miss = result.miss;
      report.reached_target = result.reached_target;
      report.force_limited = result.force_limited;
      report.beyond_length = result.beyond_length;
    }
    if (keep) kept_[j] = force;
    // The evaluation's chain is the one the force was solved on.
    if (loads.large_deflection) loads.curl_segments = segments;
    ScaleBendingLoads(1.0 - report.weight, p, sample);
    loads.tip_force += report.weight * force;
  }
  return Status::Ok();
}

}  // namespace wirerig
