// What modal wire dynamics adds to a rig's frame (issue 17, "Speed": 8 modes per wire add at most
// 20% to a frame's evaluation time on the octopus and the human). Per frame of 1/60 s, one
// thread, float engine buffers (interleaved positions and normals in the source asset's vertex
// order, as the bake writes them):
//   static  SampleClip at the frame's time + EvaluateRigJob
//   modal   SampleClip + WireDynamics::Step (8 modes per deformable wire, one step of the frame's
//           dt with the step table) + WireDynamics::Apply + EvaluateRigJob
//   ratio   both of the above, alternately in one loop, each timed on its own (thread CPU
//           time): the counters static_us, modal_us and ratio = modal / static. Alternating
//           frames see the same machine load, so the ratio is the figure to compare. Also
//           offset_mm: the largest distance between a vertex of the modal frame and of the
//           static frame at the same time after the loop (what the wires' motion changes).
// Scenes (loaded and built outside the timed loops):
//   octopus         samples/octopus/octopus.scene.json, its "swim" clip: 8 deformable
//                   tentacles stroked by line loads, hanging from the mantle, a rigid body moved
//                   by jet forces and drag. The mantle's motion is played once beforehand
//                   (Playback, at the frames' times): each frame takes the mantle's pose from
//                   it, and the modal path its support acceleration (the change of the
//                   tentacle root's velocity over the frame) and rotation, as Playback does.
//   human           samples/human/human_wave.scene.json (18 deformable spines, keyed joint
//                   angles: no support acceleration), plus a bending point load on every spine,
//                   0.05 EI / L^3 at v = 0.7 swinging at 1.3 Hz, so the wires move.
//   human_at_rest   the same clip as authored: no spine has bending loads, so the wires stay at
//                   their static shape (the modal residual is zero every frame).
//   wirerig_modal_frame_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "bench_setup.h"
#include "wirerig/anim/clip_sampling.h"
#include "wirerig/anim/playback.h"
#include "wirerig/anim/rigid_part.h"
#include "wirerig/anim/scene.h"
#include "wirerig/anim/wire_dynamics.h"
#include "wirerig/runtime/rig_evaluation.h"

#ifndef WIRERIG_SAMPLES_DIR
#error "the benchmarks need WIRERIG_SAMPLES_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {

using bench::Check;
using bench::ThreadSeconds;

constexpr double kFrame = 1.0 / 60.0;  // s
constexpr int kModes = 8;

struct SceneCase {
  const char* file;     // under samples/
  bool swinging_loads;  // add the swinging spine loads (the human)
};

const BuiltScene& Scene(const std::string& file) {
  static std::map<std::string, BuiltScene> scenes;
  auto it = scenes.find(file);
  if (it != scenes.end()) return it->second;
  return scenes
      .emplace(file, Check(LoadAndBuildScene(std::string(WIRERIG_SAMPLES_DIR) + "/" + file),
                           file.c_str()))
      .first->second;
}

// The rigid parts' motion over the clip's frames, played once per scene by Playback (whose
// rigid-body step is the same for both paths, so it is not timed): per frame, every rigid
// part's pose and every part's support acceleration, angular velocity and angular acceleration
// (world) and rotation (its parent's).
struct Motion {
  std::size_t frames = 0;
  std::vector<PartPose> poses;                     // frames x parts (rigid parts' are used)
  std::vector<Vec3> support_acceleration;          // frames x parts
  std::vector<Vec3> support_angular_velocity;      // frames x parts
  std::vector<Vec3> support_angular_acceleration;  // frames x parts
  std::vector<Mat3> support_rotation;              // frames x parts
};

const Motion& MotionOf(const std::string& file) {
  static std::map<std::string, Motion> motions;
  auto it = motions.find(file);
  if (it != motions.end()) return it->second;
  const BuiltScene& scene = Scene(file);
  const RigModel& model = scene.model;
  const std::size_t parts = model.parts.size();
  PlaybackOptions options = scene.description.playback;
  options.wires.modes = 0;  // the bodies do not depend on the wires
  Playback playback = Check(Playback::Make(model, scene.clips.front(), options), "playback");
  Motion motion;
  motion.frames = static_cast<std::size_t>(std::floor(scene.clips.front().duration / kFrame));
  motion.poses.resize(motion.frames * parts);
  motion.support_acceleration.assign(motion.frames * parts, Vec3::Zero());
  motion.support_angular_velocity.assign(motion.frames * parts, Vec3::Zero());
  motion.support_angular_acceleration.assign(motion.frames * parts, Vec3::Zero());
  motion.support_rotation.assign(motion.frames * parts, Mat3::Identity());
  std::vector<RigidPartBody> bodies(parts);
  for (std::size_t p = 0; p < parts; ++p)
    bodies[p] = MakeRigidPartBody(model.parts[p], model.parts[p].parent >= 0);
  // Playback's support velocity: of the part's root point, carried by its parent's body.
  auto support_velocity = [&](std::size_t p) {
    const auto parent = std::size_t(model.parts[p].parent);
    const RigidPartBody& body = bodies[parent];
    const RigidBodyState& state = playback.bodies()[parent];
    const Vec3 point = state.orientation * (body.axes.transpose() *
                                            (model.parts[p].spine_points.front() - body.reference));
    return Vec3(state.velocity + (state.orientation * state.angular_velocity).cross(point));
  };
  std::vector<Vec3> positions(model.vertices.size()), previous(parts, Vec3::Zero());
  std::vector<Vec3> previous_turn(parts, Vec3::Zero());
  for (std::size_t k = 0; k < motion.frames; ++k) {
    if (Status s = playback.Evaluate(double(k) * kFrame, positions, {}); !s) {
      std::cerr << file << ": " << ToString(s) << "\n";
      std::exit(1);
    }
    for (std::size_t p = 0; p < parts; ++p) {
      motion.poses[k * parts + p] = playback.sample().poses[p];
      const int parent = model.parts[p].parent;
      if (parent < 0 || model.parts[std::size_t(parent)].kind != SpineKind::kRigid) continue;
      const Vec3 velocity = support_velocity(p);
      if (k > 0) motion.support_acceleration[k * parts + p] = (velocity - previous[p]) / kFrame;
      previous[p] = velocity;
      const RigidBodyState& parent_state = playback.bodies()[std::size_t(parent)];
      const Vec3 turn = parent_state.orientation * parent_state.angular_velocity;
      motion.support_angular_velocity[k * parts + p] = turn;
      if (k > 0)
        motion.support_angular_acceleration[k * parts + p] = (turn - previous_turn[p]) / kFrame;
      previous_turn[p] = turn;
      motion.support_rotation[k * parts + p] =
          PoseOfRigidPart(bodies[std::size_t(parent)], model.parts[std::size_t(parent)],
                          playback.bodies()[std::size_t(parent)])
              .rotation.toRotationMatrix();
    }
  }
  return motions.emplace(file, std::move(motion)).first->second;
}

// One path's per-frame state: its clip sample, the swinging loads it points to and, for the
// modal path, its wires.
struct Path {
  ClipSample sample;
  std::vector<std::array<PointLoad, 1>> loads;  // per part: the swinging load
  WireDynamics wires;
};

class Frames {
 public:
  explicit Frames(const SceneCase& c)
      : scene_(Scene(c.file)),
        model_(scene_.model),
        clip_(scene_.clips.front()),
        motion_(MotionOf(c.file)),
        swinging_(c.swinging_loads),
        workspace_(MakeRigWorkspace(model_)),
        buffer_(6 * scene_.mesh.weld_map.size()) {
    for (Path* path : {&static_, &modal_}) {
      path->sample = MakeClipSample(clip_, model_);
      path->loads.resize(model_.parts.size());
    }
    WireDynamicsOptions options = scene_.description.playback.wires;
    options.modes = kModes;
    modal_.wires = Check(WireDynamics::Make(model_, clip_, options, kFrame), "wires");
    Sample(static_, 0);
    Sample(modal_, 0);
    if (Status s = modal_.wires.Reset(modal_.sample); !s) Fail(s);
    job_.model = &model_;
    job_.workspace = &workspace_;
    job_.preserve_volume = scene_.description.playback.preserve_volume;
    job_.float_positions = buffer_;
    job_.float_position_stride = 6;
    job_.float_normals = std::span<float>(buffer_).subspan(3);
    job_.float_normal_stride = 6;
    job_.float_vertex_order = scene_.mesh.weld_map;
  }

  std::size_t wires() const { return modal_.wires.size(); }
  std::size_t vertices() const { return scene_.mesh.weld_map.size(); }

  // The frame after the last one (the clip's frames over and over).
  void StaticFrame() {
    Sample(static_, static_frame_++ % motion_.frames);
    Evaluate(static_);
  }
  void ModalFrame() {
    const std::size_t frame = modal_frame_++ % motion_.frames, parts = model_.parts.size();
    Sample(modal_, frame);
    const auto at = [&](const auto& all) { return std::span(all).subspan(frame * parts, parts); };
    if (Status s = modal_.wires.Step(
            modal_.sample, at(motion_.support_acceleration), at(motion_.support_angular_velocity),
            at(motion_.support_angular_acceleration), at(motion_.support_rotation), kFrame);
        !s)
      Fail(s);
    if (Status s = modal_.wires.Apply(modal_.sample.poses); !s) Fail(s);
    Evaluate(modal_);
  }
  const std::vector<float>& buffer() const { return buffer_; }

 private:
  static void Fail(const Status& s) {
    std::cerr << ToString(s) << "\n";
    std::exit(1);
  }
  // The clip at the frame's time, the rigid parts posed by their motion.
  void Sample(Path& path, std::size_t frame) {
    const double t = double(frame) * kFrame;
    SampleClip(clip_, t, &path.sample);
    for (std::size_t p = 0; p < model_.parts.size(); ++p)
      if (model_.parts[p].kind == SpineKind::kRigid) {
        const PartPose& pose = motion_.poses[frame * model_.parts.size() + p];
        path.sample.poses[p].rotation = pose.rotation;
        path.sample.poses[p].translation = pose.translation;
      }
    if (!swinging_) return;
    const double swing = std::sin(2.0 * std::numbers::pi * 1.3 * t);
    for (std::size_t p = 0; p < model_.parts.size(); ++p) {
      const PartModel& part = model_.parts[p];
      SpineLoads& loads = path.sample.poses[p].loads;
      if (part.kind != SpineKind::kDeformable || !loads.bending_point_loads.empty()) continue;
      const double force =
          0.05 * part.spine_stiffness.bending / std::pow(part.spine_length, 3) * swing;
      path.loads[p] = {{{0.7, Vec3(force, 0.5 * force, 0.0)}}};
      loads.bending_point_loads = path.loads[p];
    }
  }
  void Evaluate(const Path& path) {
    job_.poses = path.sample.poses;
    job_.profile_loads = path.sample.profile_loads;
    if (Status s = job_.Run(); !s) Fail(s);
  }

  const BuiltScene& scene_;
  const RigModel& model_;
  const Clip& clip_;
  const Motion& motion_;
  bool swinging_;
  RigWorkspace workspace_;  // shared: an engine has one per thread
  std::vector<float> buffer_;
  EvaluateRigJob job_;
  Path static_, modal_;
  std::size_t static_frame_ = 0, modal_frame_ = 0;
};

void SetCounters(benchmark::State& state, const Frames& frames) {
  state.counters["wires"] = double(frames.wires());
  state.counters["vertices"] = double(frames.vertices());
}

void BM_Static(benchmark::State& state, SceneCase c) {
  Frames frames(c);
  for (auto _ : state) {
    frames.StaticFrame();
    benchmark::DoNotOptimize(frames.buffer().data());
    benchmark::ClobberMemory();
  }
  SetCounters(state, frames);
}

void BM_Modal(benchmark::State& state, SceneCase c) {
  Frames frames(c);
  for (auto _ : state) {
    frames.ModalFrame();
    benchmark::DoNotOptimize(frames.buffer().data());
    benchmark::ClobberMemory();
  }
  SetCounters(state, frames);
}

// Static and modal frames alternately (which goes first alternates too), each timed alone.
void BM_Ratio(benchmark::State& state, SceneCase c) {
  Frames frames(c);
  double static_seconds = 0.0, modal_seconds = 0.0;
  bool modal_first = false;
  for (auto _ : state) {
    for (int half = 0; half < 2; ++half) {
      const bool modal = (half == 0) == modal_first;
      const double start = ThreadSeconds();
      if (modal)
        frames.ModalFrame();
      else
        frames.StaticFrame();
      benchmark::DoNotOptimize(frames.buffer().data());
      benchmark::ClobberMemory();
      (modal ? modal_seconds : static_seconds) += ThreadSeconds() - start;
    }
    modal_first = !modal_first;
  }
  // Not timed: how far the wires' motion moves the skin, at the next frame of both paths.
  frames.StaticFrame();
  const std::vector<float> still = frames.buffer();
  frames.ModalFrame();
  double offset = 0.0;
  for (std::size_t i = 0; i < still.size(); i += 6)
    offset = std::max(offset, double(std::hypot(still[i] - frames.buffer()[i],
                                                still[i + 1] - frames.buffer()[i + 1],
                                                still[i + 2] - frames.buffer()[i + 2])));
  state.counters["offset_mm"] = 1e3 * offset;
  const double n = double(state.iterations());
  state.counters["static_us"] = 1e6 * static_seconds / n;
  state.counters["modal_us"] = 1e6 * modal_seconds / n;
  state.counters["ratio"] = static_seconds > 0.0 ? modal_seconds / static_seconds : 0.0;
  SetCounters(state, frames);
}

constexpr SceneCase kOctopus{"octopus/octopus.scene.json", false};
constexpr SceneCase kHuman{"human/human_wave.scene.json", true};
constexpr SceneCase kHumanAtRest{"human/human_wave.scene.json", false};

BENCHMARK_CAPTURE(BM_Static, octopus, kOctopus)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Modal, octopus, kOctopus)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Ratio, octopus, kOctopus)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Static, human, kHuman)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Modal, human, kHuman)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Ratio, human, kHuman)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Static, human_at_rest, kHumanAtRest)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Modal, human_at_rest, kHumanAtRest)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Ratio, human_at_rest, kHumanAtRest)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace wirerig

BENCHMARK_MAIN();
