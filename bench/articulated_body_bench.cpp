// One step of the articulated-body solver (articulated_body.h) for a 20-body humanoid-like tree:
// a floating pelvis, a three-segment spine, neck and head, two arms (clavicle, upper arm,
// forearm on a hinge, hand) and two legs (thigh, shin on a hinge, foot), 55 degrees of freedom.
// Every step has gravity, passive damping, PD tracking of a pose on every joint and active
// limits (the knees and elbows start against theirs), and an external push on the neck. Both
// integrators, one thread. The state is reset to its start every half second of simulated time
// (a copy into the same buffers: no allocation) so the figure does not fall for the whole run.
// Report the median of repetitions:
//   wirerig_articulated_body_bench --benchmark_repetitions=10 --benchmark_report_aggregates_only
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <iostream>
#include <vector>

#include "wirerig/runtime/articulated_body.h"

namespace wirerig {
namespace {

// A solid cylinder along the body's Z axis (JointModel's bone axis), about its centre.
Mat3 Segment(double mass, double radius, double length) {
  const double across = mass * (3.0 * radius * radius + length * length) / 12.0;
  return Vec3(across, across, 0.5 * mass * radius * radius).asDiagonal();
}

// Joint axes with Z along `bone` (world), X as close to world X as possible.
Quat BoneAxes(const Vec3& bone) {
  const Vec3 z = bone.normalized();
  Vec3 x = Vec3::UnitX() - Vec3::UnitX().dot(z) * z;
  if (x.norm() < 1e-6) x = Vec3::UnitZ() - Vec3::UnitZ().dot(z) * z;
  x.normalize();
  Mat3 axes;
  axes.col(0) = x;
  axes.col(1) = z.cross(x);
  axes.col(2) = z;
  return Quat(axes);
}

struct Humanoid {
  std::vector<ArticulatedBodyDesc> bodies;
  std::vector<Quat> world_axes;  // rest axes of each body in the world
  std::vector<Vec3> origins;     // rest origin (joint) of each body in the world

  // Adds a segment of `length` along `bone` (world), jointed at `at` (world) to `parent`.
  int Add(int parent, ArticulatedJointType joint, const Vec3& at, const Vec3& bone, double length,
          double mass, double radius, Vec3 min_degrees = Vec3::Constant(-180.0),
          Vec3 max_degrees = Vec3::Constant(180.0)) {
    ArticulatedBodyDesc b;
    b.parent = parent;
    b.joint = joint;
    const Quat axes = BoneAxes(bone);
    if (parent < 0) {
      b.joint_position = at;
      b.joint_rotation = axes;
    } else {
      // In the parent's body frame at rest: its origin (joint) and axes in the world.
      b.joint_position = world_axes[parent].conjugate() * (at - origins[parent]);
      b.joint_rotation = world_axes[parent].conjugate() * axes;
    }
    b.mass = mass;
    b.center_of_mass = Vec3(0.0, 0.0, 0.5 * length);
    b.inertia = Segment(mass, radius, length);
    b.damping = 0.02 * mass;
    b.min_degrees = min_degrees;
    b.max_degrees = max_degrees;
    bodies.push_back(b);
    world_axes.push_back(axes);
    origins.push_back(at);
    return static_cast<int>(bodies.size()) - 1;
  }
};

Humanoid MakeHumanoid() {
  using J = ArticulatedJointType;
  Humanoid h;
  const Vec3 up = Vec3::UnitY(), down = -Vec3::UnitY();
  const int pelvis = h.Add(-1, J::kFloating, Vec3(0, 1.0, 0), up, 0.15, 10.0, 0.15);
  const Vec3 bend(-20, -20, -15), bend_max(20, 20, 15);
  const int spine1 = h.Add(pelvis, J::kBall, Vec3(0, 1.15, 0), up, 0.15, 6.0, 0.13, bend, bend_max);
  const int spine2 = h.Add(spine1, J::kBall, Vec3(0, 1.30, 0), up, 0.15, 6.0, 0.14, bend, bend_max);
  const int chest = h.Add(spine2, J::kBall, Vec3(0, 1.45, 0), up, 0.2, 8.0, 0.15, bend, bend_max);
  const int neck = h.Add(chest, J::kBall, Vec3(0, 1.65, 0), up, 0.1, 1.0, 0.05, bend, bend_max);
  h.Add(neck, J::kBall, Vec3(0, 1.75, 0), up, 0.22, 5.0, 0.1, Vec3(-40, -40, -70),
        Vec3(40, 40, 70));
  for (double side : {-1.0, 1.0}) {
    const Vec3 out(side, 0, 0);
    const int clavicle = h.Add(chest, J::kBall, Vec3(0.05 * side, 1.6, 0), out, 0.15, 1.5, 0.04,
                               Vec3(-10, -10, -10), Vec3(10, 10, 10));
    const int upper = h.Add(clavicle, J::kBall, Vec3(0.2 * side, 1.6, 0), down, 0.3, 2.0, 0.05,
                            Vec3(-90, -90, -80), Vec3(90, 90, 80));
    const int fore = h.Add(upper, J::kHinge, Vec3(0.2 * side, 1.3, 0), down, 0.27, 1.2, 0.04,
                           Vec3(0, 0, 0), Vec3(150, 0, 0));
    h.Add(fore, J::kBall, Vec3(0.2 * side, 1.03, 0), down, 0.18, 0.4, 0.03, Vec3(-60, -30, -80),
          Vec3(60, 30, 80));
    const int thigh = h.Add(pelvis, J::kBall, Vec3(0.1 * side, 0.95, 0), down, 0.45, 8.0, 0.08,
                            Vec3(-30, -45, -40), Vec3(110, 45, 40));
    const int shin = h.Add(thigh, J::kHinge, Vec3(0.1 * side, 0.5, 0), down, 0.42, 3.5, 0.05,
                           Vec3(0, 0, 0), Vec3(150, 0, 0));
    h.Add(shin, J::kBall, Vec3(0.1 * side, 0.08, 0), Vec3(0, 0, 1), 0.2, 1.0, 0.04,
          Vec3(-40, -20, -20), Vec3(40, 20, 20));
  }
  return h;
}

void BM_HumanoidStep(benchmark::State& bench, ArticulatedIntegrator integrator, double rate) {
  const Humanoid humanoid = MakeHumanoid();
  ArticulatedModel model;
  if (Status s = ArticulatedModel::Build(humanoid.bodies, &model); !s) {
    std::cerr << "humanoid: " << ToString(s) << "\n";
    std::exit(1);
  }
  // A waving pose to track: every ball joint 0.3 rad about its X axis, hinges at 0.5 rad.
  std::vector<JointTarget> targets(model.body_count());
  for (int i = 0; i < model.body_count(); ++i) {
    JointTarget& t = targets[i];
    t.rotation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitX()));
    t.angle = 0.5;
    t.stiffness = 50.0 * model.body(i).mass * 0.01;
    t.damping = 0.1 * t.stiffness * 0.1;
  }
  ArticulatedState start = MakeArticulatedState(model);
  start.joints[0].angular_velocity = Vec3(0.2, 0.5, -0.1);
  for (int i = 1; i < model.body_count(); ++i)
    start.joints[i].angular_velocity = Vec3(1.0, -0.5, 0.3) * (i % 3 == 0 ? -1.0 : 1.0);
  ArticulatedState state = start;
  ArticulatedWorkspace workspace = MakeArticulatedWorkspace(model);
  const std::vector<ExternalWrench> wrenches = {
      {4, Vec3(5.0, 0.0, 0.0), Vec3(0.0, 1.85, 0.1), Vec3::Zero()}};
  ArticulatedStepJob job;
  job.model = &model;
  job.integrator = integrator;
  job.dt = 1.0 / rate;
  job.targets = targets;
  job.wrenches = wrenches;
  job.workspace = &workspace;
  job.state = &state;
  // Reset every half second of simulated time: the wrench acts at a world-fixed point, and a
  // figure falling away from it for seconds would be spun up by an ever longer moment arm.
  const int reset_every = static_cast<int>(0.5 * rate);
  int steps = 0;
  for (auto _ : bench) {
    if (++steps == reset_every) {
      steps = 0;
      state = start;  // same sizes: copies, no allocation
    }
    if (const Status s = job.Run(); !s) {
      bench.SkipWithError(ToString(s).c_str());
      break;
    }
    benchmark::DoNotOptimize(state.bodies.data());
    benchmark::ClobberMemory();
  }
  bench.counters["bodies"] = model.body_count();
  bench.counters["dofs"] = model.dof_count();
  bench.counters["time/body"] =
      benchmark::Counter(double(bench.iterations()) * model.body_count(),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The semi-implicit step at a character's 240 Hz and 60 Hz; RK4 at 1 kHz (at 240 Hz the
// clavicles, light parents of heavy arms, ring against their limits faster than RK4 can follow).
BENCHMARK_CAPTURE(BM_HumanoidStep, semi_implicit_euler_240hz,
                  ArticulatedIntegrator::kSemiImplicitEuler, 240.0)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_HumanoidStep, semi_implicit_euler_60hz,
                  ArticulatedIntegrator::kSemiImplicitEuler, 60.0)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_HumanoidStep, rk4_1000hz, ArticulatedIntegrator::kRk4, 1000.0)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace wirerig

BENCHMARK_MAIN();
