// wirerig_viewer_demo: a capsule clamped at its base, its spine a cantilever wire (pink) and
// five profile rings (blue). Drag the spine: a point force at the grabbed parameter bends it
// (BendingJob, cantilever with a free end) and the mesh and rings follow the bent spine. The
// timeline plays a keyed tip force (sway).
//
// Headless check, as the ctests run it:
//   wirerig_viewer_demo --no-window --frames 40 --input drag.input --screenshot demo.png
// prints a summary line "demo: picks=1 force=yes spine_moved=yes mesh_moved=yes ...".
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include <Eigen/Geometry>

#include "wirerig/procedural/shapes.h"
#include "wirerig/runtime/bending_job.h"
#include "wirerig/viewer/application.h"

namespace wirerig {
namespace {

constexpr double kLength = 1.0;      // m, spine length (capsule cylinder height)
constexpr double kRadius = 0.08;     // m
constexpr double kStiffness = 30.0;  // EI, N m^2
constexpr int kSpineSamples = 101;   // samples of the bending solution along the spine
constexpr int kRingPoints = 48;
constexpr std::array<double, 5> kRingParameters = {0.1, 0.3, 0.5, 0.7, 0.9};
constexpr std::uint32_t kSpineId = 0;

class CantileverDemo : public Application {
 protected:
  Result<bool> OnInitialize() override {
    const Mesh capsule = MakeCapsule(kRadius, kLength, 48, 40, 10);
    for (const Vec3& p : capsule.positions) rest_.push_back(p.cast<float>());
    triangles_ = capsule.triangles;
    positions_ = rest_;
    normals_.resize(rest_.size());
    scalars_.resize(rest_.size());
    samples_.resize(kSpineSamples);
    for (int i = 0; i < kSpineSamples; ++i) samples_[i] = double(i) / (kSpineSamples - 1);
    displacement_.resize(kSpineSamples, Vec3::Zero());
    slope_.resize(kSpineSamples, Vec3::Zero());
    curvature_.resize(kSpineSamples, Vec3::Zero());
    spine_.resize(kSpineSamples);
    rings_.assign(kRingParameters.size(), std::vector<Vec3f>(kRingPoints));
    polylines_.resize(1 + kRingParameters.size());
    // A keyed tip force for the timeline: sway along z.
    timeline().duration = 4.0;
    timeline().keys = {0.0, 1.0, 2.0, 3.0, 4.0};
    Deform();
    return true;
  }

  void OnUpdate(double dt) override {
    (void)dt;
    Deform();
  }

  void OnDisplay(RenderFrame& frame) override {
    mesh_view_.positions = positions_;
    mesh_view_.normals = normals_;
    mesh_view_.triangles = triangles_;
    mesh_view_.scalars = scalars_;
    mesh_view_.cull_back_faces = true;  // a closed procedural capsule
    polylines_[0].points = spine_;
    polylines_[0].kind = WireKind::kSpine;
    polylines_[0].id = kSpineId;
    polylines_[0].width = 4.0f;
    for (std::size_t r = 0; r < rings_.size(); ++r) {
      polylines_[r + 1].points = rings_[r];
      polylines_[r + 1].kind = WireKind::kProfile;
      polylines_[r + 1].closed = true;
      polylines_[r + 1].pickable = false;
      polylines_[r + 1].id = std::uint32_t(r + 1);
    }
    arrow_count_ = 0;
    if (drag_force_.norm() > 1e-6) {
      arrows_[arrow_count_++] = {SpinePoint(drag_at_), drag_force_.cast<float>(),
                                 Vec3f(0.9f, 0.1f, 0.02f)};
    }
    if (tip_force_.norm() > 1e-6) {
      arrows_[arrow_count_++] = {SpinePoint(1.0), tip_force_.cast<float>(),
                                 Vec3f(0.95f, 0.6f, 0.05f)};
    }
    frame.meshes = {&mesh_view_, 1};
    frame.polylines = polylines_;
    frame.arrows = {arrows_.data(), arrow_count_};
    frame.arrow_length_per_newton = 0.01f;
    frame.legend.min = 0.0f;
    // The range follows the largest moment, in steps of 10 N m, so colours never saturate.
    const float peak = *std::max_element(scalars_.begin(), scalars_.end());
    frame.legend.max = std::max(10.0f, 10.0f * std::ceil(peak / 10.0f));
    frame.legend.map = ColorMap::kViridis;
    frame.legend.label = "bending moment |M| (N m)";
    std::snprintf(caption_, sizeof(caption_), "t = %.2f s", timeline().time);
    frame.caption = caption_;
  }

  void OnWireGrab(const WirePick& pick) override {
    drag_at_ = std::clamp(double(pick.parameter), 0.15, 1.0);
    grab_rest_ = Vec3(0.0, drag_at_ * kLength, 0.0);
    ++picks_;
    std::printf("demo: grabbed wire %u at v = %.3f\n", pick.id, pick.parameter);
  }

  void OnWireDrag(const WirePick& grab, const Vec3f& target) override {
    (void)grab;
    // The load that puts a cantilever's point at `a` where the mouse is: w(a) = P a^3 / (3 EI).
    const double a = drag_at_ * kLength;
    Vec3 offset = target.cast<double>() - grab_rest_;
    offset.y() = 0.0;  // lateral only
    drag_force_ = 3.0 * kStiffness * offset / (a * a * a);
    peak_force_ = std::max(peak_force_, drag_force_.norm());
  }

  void OnWireRelease() override { drag_force_.setZero(); }

  void OnShutdown() override {
    const bool spine_moved = max_tip_motion_ > 0.01;
    const bool mesh_moved = max_mesh_motion_ > 0.01;
    std::printf(
        "demo: picks=%d force=%s spine_moved=%s mesh_moved=%s peak_force=%.2f N "
        "max_tip_motion=%.4f m max_mesh_motion=%.4f m frames=%d\n",
        picks_, peak_force_ > 0.0 ? "yes" : "no", spine_moved ? "yes" : "no",
        mesh_moved ? "yes" : "no", peak_force_, max_tip_motion_, max_mesh_motion_,
        statistics().frame);
  }

  void OnGui() override {}

 private:
  // Keyed tip force along z (linear between keys at whole seconds).
  Vec3 TipForce(double t) const {
    static constexpr std::array<double, 5> kValues = {0.0, 12.0, 0.0, -12.0, 0.0};
    const double x = std::clamp(t, 0.0, 4.0);
    const int i = std::min(int(x), 3);
    const double f = x - i;
    return Vec3(0.0, 0.0, (1.0 - f) * kValues[i] + f * kValues[i + 1]);
  }

  static Vec3 Lerp(const Vec3& a, const Vec3& b, double f) {
    return Vec3(a.x() + f * (b.x() - a.x()), a.y() + f * (b.y() - a.y()),
                a.z() + f * (b.z() - a.z()));
  }

  Vec3f SpinePoint(double v) const {
    const double x = std::clamp(v, 0.0, 1.0) * (kSpineSamples - 1);
    const int i = std::min(int(x), kSpineSamples - 2);
    const float f = float(x - i);
    return (1.0f - f) * spine_[i] + f * spine_[i + 1];
  }

  void Deform() {
    const auto start = std::chrono::steady_clock::now();
    tip_force_ =
        timeline().playing || timeline().time > 0.0 ? TipForce(timeline().time) : Vec3::Zero();
    PointLoad load{drag_at_, drag_force_};
    BendingJob job;
    job.boundary = BoundaryCondition::kCantileverFree;
    job.length = kLength;
    job.bending_stiffness = kStiffness;
    job.tip_force = tip_force_;
    job.point_loads = {&load, drag_force_.norm() > 0.0 ? 1u : 0u};
    job.samples = samples_;
    job.displacement = displacement_;
    job.slope = slope_;
    job.curvature = curvature_;
    if (Status s = job.Run(); !s) {
      std::fprintf(stderr, "demo: %s\n", ToString(s).c_str());
      return;
    }
    for (int i = 0; i < kSpineSamples; ++i) {
      const Vec3& d = displacement_[i];
      spine_[i] = Vec3f(float(d.x()), float(samples_[i] * kLength + d.y()), float(d.z()));
    }
    // Each rest point follows the spine sample at its height: translated with it and turned
    // from +Y to the bent tangent.
    auto follow = [this](const Vec3f& p, float* moment) {
      const double v = std::clamp(double(p.y()) / kLength, 0.0, 1.0);
      const double x = v * (kSpineSamples - 1);
      const int i = std::min(int(x), kSpineSamples - 2);
      const double f = x - i;
      // Written component-wise: GCC 12 reports Eigen's sums here as maybe-uninitialized.
      const Vec3 d = Lerp(displacement_[i], displacement_[i + 1], f);
      const Vec3 s = Lerp(slope_[i], slope_[i + 1], f);
      const Vec3 k = Lerp(curvature_[i], curvature_[i + 1], f);
      if (moment != nullptr) *moment = float(kStiffness * k.norm());
      const Vec3 tangent(s.x(), 1.0 + s.y(), s.z());
      const Eigen::Quaterniond turn =
          Eigen::Quaterniond::FromTwoVectors(Vec3::UnitY(), tangent.normalized());
      const double height = v * kLength;
      const Vec3 turned = turn * Vec3(double(p.x()), double(p.y()) - height, double(p.z()));
      return Vec3f(float(d.x() + turned.x()), float(height + d.y() + turned.y()),
                   float(d.z() + turned.z()));
    };
    for (std::size_t i = 0; i < rest_.size(); ++i) {
      positions_[i] = follow(rest_[i], &scalars_[i]);
      max_mesh_motion_ = std::max(max_mesh_motion_, double((positions_[i] - rest_[i]).norm()));
    }
    ComputeVertexNormals(positions_, triangles_, normals_);
    for (std::size_t r = 0; r < rings_.size(); ++r) {
      for (int k = 0; k < kRingPoints; ++k) {
        const double a = 2.0 * 3.14159265358979 * k / kRingPoints;
        const Vec3f rest(float(1.04 * kRadius * std::cos(a)), float(kRingParameters[r] * kLength),
                         float(1.04 * kRadius * std::sin(a)));
        rings_[r][k] = follow(rest, nullptr);
      }
    }
    max_tip_motion_ = std::max(max_tip_motion_, displacement_.back().norm());
    evaluation_ms_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

  std::vector<Vec3f> rest_, positions_, normals_;
  std::vector<float> scalars_;
  std::vector<Triangle> triangles_;
  std::vector<double> samples_;
  std::vector<Vec3> displacement_, slope_, curvature_;
  std::vector<Vec3f> spine_;
  std::vector<std::vector<Vec3f>> rings_;
  std::vector<RenderPolyline> polylines_;
  RenderMesh mesh_view_;
  std::array<RenderArrow, 2> arrows_;
  std::size_t arrow_count_ = 0;
  char caption_[64] = {};

  double drag_at_ = 1.0;
  Vec3 grab_rest_ = Vec3::Zero();
  Vec3 drag_force_ = Vec3::Zero();
  Vec3 tip_force_ = Vec3::Zero();
  int picks_ = 0;
  double peak_force_ = 0.0;
  double max_tip_motion_ = 0.0;
  double max_mesh_motion_ = 0.0;
  double evaluation_ms_ = 0.0;
};

}  // namespace
}  // namespace wirerig

int main(int argc, char** argv) {
  wirerig::CantileverDemo demo;
  return demo.Run(argc, argv);
}
