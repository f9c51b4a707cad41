#include "wirerig/runtime/rig_evaluation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "wirerig/runtime/spine_interpolation.h"

namespace wirerig {
namespace {

// Vertices, triangles and vertex normals per parallel task: large enough that claiming a task
// costs nothing next to it, small enough that two threads share out a mesh evenly.
constexpr std::size_t kTaskSize = 2048;

// The fast path of ApplyPairBinding is used while squared lengths stay within these bounds:
// then no product below can overflow or underflow into the subnormals that matter.
constexpr double kMinSquared = 1e-140;
constexpr double kMaxSquared = 1e140;
// ApplyPairBinding's kDegenerateSine, squared.
constexpr double kDegenerateSine2 = 1e-16;

// PHYSICS.md section 6, step "apply", for a regular frame: with e = p2 - p1, d = c - p1 and
// n = e x d, the unit normal is n / |n|, |e| m_hat = n_hat x e, and the point is
// p1 + alpha e + beta (n_hat x e) + gamma |e| n_hat. Equal to ApplyPairBinding up to rounding
// (one square root and one division fewer: no normalisation of e or d). Returns false, writing
// nothing, where ApplyPairBinding's degenerate-frame handling (or its overflow-safe scaling)
// is needed.
inline bool ApplyPairFast(const RigEvaluationLayout::Pair& b, const Vec3* points,
                          const Vec3* centres, Vec3* out) {
  const Vec3 p1 = (1.0 - b.lambda1) * points[b.a0] + b.lambda1 * points[b.a1];
  const Vec3 p2 = (1.0 - b.lambda2) * points[b.b0] + b.lambda2 * points[b.b1];
  const Vec3 e = p2 - p1;
  const Vec3 d = centres[b.profile] - p1;
  const double ee = e.squaredNorm(), dd = d.squaredNorm();
  if (!(ee >= kMinSquared && ee <= kMaxSquared && dd >= kMinSquared && dd <= kMaxSquared))
    return false;
  const Vec3 n = e.cross(d);
  const double nn = n.squaredNorm();
  if (!(nn > kDegenerateSine2 * ee * dd)) return false;
  const Vec3 n_hat = n * (1.0 / std::sqrt(nn));
  *out = p1 + b.alpha * e + b.beta * n_hat.cross(e) + (b.gamma * std::sqrt(ee)) * n_hat;
  return true;
}

// The vertex and normal passes, as tasks over ranges of kTaskSize items.
struct VertexPass {
  const EvaluateRigJob* job;
  RigWorkspace* w;

  static std::size_t Tasks(std::size_t items) { return (items + kTaskSize - 1) / kTaskSize; }

  // Pair vertices [k kTaskSize, (k + 1) kTaskSize), then the caps in the same way.
  static void Vertices(const void* context, std::size_t k) {
    const auto& self = *static_cast<const VertexPass*>(context);
    const RigEvaluationLayout& layout = self.w->layout;
    const std::size_t pair_tasks = Tasks(layout.pairs.size());
    Vec3* positions = self.job->positions.data();
    if (k >= pair_tasks) {
      const std::size_t end = std::min(layout.caps.size(), (k - pair_tasks + 1) * kTaskSize);
      for (std::size_t c = (k - pair_tasks) * kTaskSize; c < end; ++c) {
        const RigEvaluationLayout::Cap& cap = layout.caps[c];
        positions[cap.vertex] =
            self.w->cap_origins[cap.profile] + self.w->cap_axes[cap.profile] * cap.local;
      }
      return;
    }
    const Vec3* points = self.w->wire_points.data();
    const Vec3* centres = self.w->pair_centres.data();
    const std::size_t end = std::min(layout.pairs.size(), (k + 1) * kTaskSize);
    for (std::size_t i = k * kTaskSize; i < end; ++i) {
      const RigEvaluationLayout::Pair& pair = layout.pairs[i];
      if (!ApplyPairFast(pair, points, centres, &positions[pair.vertex])) self.Slow(pair);
    }
  }

  // ApplyPairBinding itself, on the wires as spans.
  void Slow(const RigEvaluationLayout::Pair& pair) const {
    const VertexAttachment& a = job->model->vertices[pair.vertex];
    const PartModel& part = job->model->parts[a.part];
    const WirePolyline wire_i{w->profile_points[a.part][a.profile],
                              part.profiles[a.profile].closed};
    const WirePolyline wire_j{w->profile_points[a.part][a.profile + 1],
                              part.profiles[a.profile + 1].closed};
    job->positions[pair.vertex] =
        ApplyPairBinding(a.pair, wire_i, wire_j, w->profile_origins[a.part][a.profile],
                         w->profile_origins[a.part][a.profile + 1]);
  }

  static void TriangleNormals(const void* context, std::size_t k) {
    const auto& self = *static_cast<const VertexPass*>(context);
    const std::vector<Triangle>& triangles = self.job->model->triangles;
    const Vec3* p = self.job->positions.data();
    Vec3* out = self.w->triangle_normals.data();
    const std::size_t end = std::min(triangles.size(), (k + 1) * kTaskSize);
    for (std::size_t f = k * kTaskSize; f < end; ++f) {
      const Triangle& t = triangles[f];
      out[f] = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
    }
  }

  // Sums each vertex's triangle normals in increasing triangle order (as accumulating over the
  // triangles in order would) and normalises.
  static void VertexNormals(const void* context, std::size_t k) {
    const auto& self = *static_cast<const VertexPass*>(context);
    const RigEvaluationLayout& layout = self.w->layout;
    const std::uint32_t* offsets = layout.vertex_triangle_offsets.data();
    const std::uint32_t* triangles = layout.vertex_triangles.data();
    const Vec3* face = self.w->triangle_normals.data();
    Vec3* normals = self.job->normals.data();
    const std::uint32_t* order = layout.normal_order.data();
    const std::size_t end = std::min(self.job->normals.size(), (k + 1) * kTaskSize);
    for (std::size_t i = k * kTaskSize; i < end; ++i) {
      Vec3 sum = Vec3::Zero();
      for (std::uint32_t t = offsets[i]; t < offsets[i + 1]; ++t) sum += face[triangles[t]];
      const double length = sum.norm();
      normals[order[i]] = length > 0.0 ? Vec3(sum * (1.0 / length)) : Vec3::UnitY();
    }
  }
};

Frame RotateFrame(const Mat3& r, const Frame& f) {
  return {r * f.tangent, r * f.normal, r * f.binormal};
}

// The rotation a spine's frame at v has turned by (rest world axes -> world), and its point.
Mat3 SpineTurn(const PartModel& part, const RigWorkspace& w, std::size_t i, double v,
               Vec3* rest_point, Vec3* point, Vec3* rest_tangent, Vec3* tangent) {
  const Frame rest = InterpolateSpine(part.spine_points, part.spine_frames, v, rest_point);
  const Frame moved = InterpolateSpine(w.spine_points[i], w.spine_frames[i], v, point);
  if (rest_tangent) *rest_tangent = rest.tangent;
  if (tangent) *tangent = moved.tangent;
  return FrameAxes(moved) * FrameAxes(rest).transpose();
}

// Step 7 of Run(): each bridged joint's bridge for this frame, then every vertex on a bridge
// moved from where its own part put it towards the bridge's image of its rest-space point.
// The per-vertex part of step 7, over the entries of task k (whole vertices; see
// RigEvaluationLayout::joint_task_starts).
struct BridgePass {
  const RigModel* model;
  const RigWorkspace* w;
  Vec3* positions;

  static void Entries(const void* context, std::size_t k) {
    const auto& self = *static_cast<const BridgePass*>(context);
    const RigEvaluationLayout& layout = self.w->layout;
    const std::size_t end = layout.joint_task_starts[k + 1];
    for (std::size_t e = layout.joint_task_starts[k]; e < end;) {
      const std::uint32_t vertex = layout.joint_vertices[e].vertex;
      const Vec3 own = self.positions[vertex];
      // Every entry of a vertex undoes through its own part's same spine sample.
      const RigEvaluationLayout::JointVertex& first = layout.joint_vertices[e];
      const Vec3 rest = self.model->parts[first.part].spine_points[first.sample] +
                        self.w->spine_undo[first.part][first.sample] *
                            (own - self.w->spine_points[first.part][first.sample]);
      Vec3 sum = Vec3::Zero();
      for (; e < end && layout.joint_vertices[e].vertex == vertex; ++e) {
        const RigEvaluationLayout::JointVertex& j = layout.joint_vertices[e];
        const BridgeSamples& bridge = self.w->bridges[j.joint];
        const Vec3 base =
            j.child_side ? own : Vec3(bridge.parent_turn * rest + bridge.parent_offset);
        sum += j.weight * (ApplyJointBridge(bridge, j.u, j.bridge, rest, j.section) - base);
      }
      self.positions[vertex] = own + sum;
    }
  }
};

void FollowJointBridges(const RigModel& model, RigWorkspace& w, std::span<Vec3> positions,
                        const ParallelFor* parallel) {
  const RigEvaluationLayout& layout = w.layout;
  if (layout.joint_vertices.empty()) return;
  for (std::uint32_t c : layout.bridged_parts) {
    const PartModel& child = model.parts[c];
    const PartModel& parent = model.parts[child.parent];
    const double h = child.joint.blend_length;
    Vec3 unused;
    const Mat3 parent_turn =
        SpineTurn(parent, w, child.parent, child.attachment, &unused, &unused, nullptr, nullptr);
    const BridgeEnds rest = RestBridgeEnds(child);
    BridgeEnds posed;
    const double end_v = std::min(h / std::max(child.spine_length, 1e-12), 1.0);
    Vec3 rest_end, rest_end_tangent;
    const Mat3 child_turn =
        SpineTurn(child, w, c, end_v, &rest_end, &posed.end, &rest_end_tangent, &posed.end_tangent);
    posed.start_tangent = parent_turn * child.joint.parent_axis;
    posed.start = w.spine_points[c].front() - h * posed.start_tangent;
    SampleJointBridge(child.joint, rest, posed, parent_turn, child_turn, &w.bridges[c]);
  }
  for (const auto& [part, sample] : layout.undo_samples)
    w.spine_undo[part][sample] = FrameAxes(model.parts[part].spine_frames[sample]) *
                                 FrameAxes(w.spine_frames[part][sample]).transpose();
  const BridgePass pass{&model, &w, positions.data()};
  RunTasks(parallel, layout.joint_task_starts.size() - 1, &BridgePass::Entries, &pass);
}

Status ValidateLoads(const SpineLoads& loads) {
  for (const PointLoad& p : loads.bending_point_loads)
    if (!(std::isfinite(p.at) && std::isfinite(p.force.x()) && std::isfinite(p.force.y())))
      return Status::Invalid("poses", "spine bending loads must be finite");
  return Status::Ok();
}

}  // namespace

RigWorkspace MakeRigWorkspace(const RigModel& model) {
  RigWorkspace w;
  std::size_t longest = 2;
  for (const PartModel& part : model.parts) {
    w.strain.emplace_back(part.spine_points.size(), 0.0);
    w.profile_scale.emplace_back(part.profiles.size(), 1.0);
    w.spine_points.emplace_back(part.spine_points.size());
    w.spine_frames.emplace_back(part.spine_frames.size());
    std::vector<std::vector<Vec3>> profiles;
    for (const ProfileModel& profile : part.profiles)
      profiles.emplace_back(profile.local_points.size());
    w.profile_points.push_back(std::move(profiles));
    w.profile_origins.emplace_back(part.profiles.size());
    w.profile_normals.emplace_back(part.profiles.size());
    longest = std::max(longest, part.spine_points.size());
  }
  w.samples.resize(longest);
  w.bending.resize(longest);
  w.slope.resize(longest);
  w.axial.resize(longest);
  w.normal_accumulator.resize(model.vertices.size());
  std::size_t widest = 1;
  for (const PartModel& part : model.parts)
    for (const ProfileModel& profile : part.profiles)
      widest = std::max(widest, profile.local_points.size());
  w.profile_samples.resize(widest + 1);
  w.profile_displacement.resize(widest + 1);

  RigEvaluationLayout& layout = w.layout;
  std::uint32_t profiles = 0, points = 0;
  for (const PartModel& part : model.parts) {
    layout.profile_base.push_back(profiles);
    for (const ProfileModel& profile : part.profiles) {
      layout.point_base.push_back(points);
      points += static_cast<std::uint32_t>(profile.local_points.size());
      ++profiles;
    }
  }
  w.wire_points.resize(points);
  w.pair_centres.resize(profiles);
  w.cap_origins.resize(profiles);
  w.cap_axes.resize(profiles, Mat3::Identity());
  // PointOnWire's indices: segment k clamped to the wire, wrapping to point 0 after the last.
  auto ends = [&](std::uint32_t g, std::size_t count, std::uint32_t k, std::uint32_t* i0,
                  std::uint32_t* i1) {
    const std::size_t first = std::min<std::size_t>(k, count - 1);
    *i0 = layout.point_base[g] + static_cast<std::uint32_t>(first);
    *i1 = layout.point_base[g] + static_cast<std::uint32_t>(first + 1 < count ? first + 1 : 0);
  };
  for (std::size_t v = 0; v < model.vertices.size(); ++v) {
    const VertexAttachment& a = model.vertices[v];
    const std::uint32_t g = layout.profile_base[a.part] + a.profile;
    if (a.cap) {
      layout.caps.push_back({static_cast<std::uint32_t>(v), g, a.cap_local});
      continue;
    }
    const PartModel& part = model.parts[a.part];
    RigEvaluationLayout::Pair pair;
    pair.vertex = static_cast<std::uint32_t>(v);
    pair.profile = g;
    ends(g, part.profiles[a.profile].local_points.size(), a.pair.k1, &pair.a0, &pair.a1);
    ends(g + 1, part.profiles[a.profile + 1].local_points.size(), a.pair.k2, &pair.b0, &pair.b1);
    pair.lambda1 = a.pair.lambda1;
    pair.lambda2 = a.pair.lambda2;
    pair.alpha = a.pair.alpha;
    pair.beta = a.pair.beta;
    pair.gamma = a.pair.gamma;
    layout.pairs.push_back(pair);
  }
  for (std::size_t v = 0; v < model.vertices.size(); ++v)
    for (const JointInfluence& j : model.vertices[v].joints)
      if (j.joint >= 0)
        layout.joint_vertices.push_back(
            {static_cast<std::uint32_t>(v), static_cast<std::uint32_t>(j.joint),
             model.vertices[v].part, j.sample, j.u, j.weight, j.bridge, j.section,
             j.joint == std::int32_t(model.vertices[v].part)});
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const PartModel& part = model.parts[i];
    if (part.parent >= 0 && part.joint.blend_length > 0.0)
      layout.bridged_parts.push_back(static_cast<std::uint32_t>(i));
  }
  // Tasks of about kTaskSize entries, each ending with a whole vertex; the spine samples the
  // entries undo through.
  layout.joint_task_starts = {0};
  for (std::size_t e = 0; e < layout.joint_vertices.size(); ++e) {
    const bool full = e - layout.joint_task_starts.back() >= kTaskSize;
    if (full && layout.joint_vertices[e].vertex != layout.joint_vertices[e - 1].vertex)
      layout.joint_task_starts.push_back(static_cast<std::uint32_t>(e));
  }
  layout.joint_task_starts.push_back(static_cast<std::uint32_t>(layout.joint_vertices.size()));
  for (const RigEvaluationLayout::JointVertex& j : layout.joint_vertices)
    layout.undo_samples.emplace_back(j.part, j.sample);
  std::sort(layout.undo_samples.begin(), layout.undo_samples.end());
  layout.undo_samples.erase(std::unique(layout.undo_samples.begin(), layout.undo_samples.end()),
                            layout.undo_samples.end());
  w.bridges.resize(model.parts.size());
  for (const PartModel& part : model.parts)
    w.spine_undo.emplace_back(part.spine_points.size(), Mat3::Identity());
  // Normals: vertices in the order of their first triangle, so the pass reads the triangle
  // normals almost sequentially; each vertex's triangles in increasing order.
  const std::size_t vertex_count = model.vertices.size();
  std::vector<std::uint32_t> count(vertex_count, 0), first(vertex_count, UINT32_MAX);
  for (std::size_t f = 0; f < model.triangles.size(); ++f)
    for (std::uint32_t index : model.triangles[f]) {
      ++count[index];
      first[index] = std::min(first[index], static_cast<std::uint32_t>(f));
    }
  layout.normal_order.resize(vertex_count);
  for (std::size_t v = 0; v < vertex_count; ++v)
    layout.normal_order[v] = static_cast<std::uint32_t>(v);
  std::sort(layout.normal_order.begin(), layout.normal_order.end(),
            [&](std::uint32_t a, std::uint32_t b) {
              return first[a] < first[b] || (first[a] == first[b] && a < b);
            });
  layout.vertex_triangle_offsets.assign(vertex_count + 1, 0);
  std::vector<std::uint32_t> fill(vertex_count);
  for (std::size_t i = 0; i < vertex_count; ++i) {
    fill[layout.normal_order[i]] = layout.vertex_triangle_offsets[i];
    layout.vertex_triangle_offsets[i + 1] =
        layout.vertex_triangle_offsets[i] + count[layout.normal_order[i]];
  }
  layout.vertex_triangles.resize(layout.vertex_triangle_offsets.back());
  for (std::size_t f = 0; f < model.triangles.size(); ++f)
    for (std::uint32_t index : model.triangles[f])
      layout.vertex_triangles[fill[index]++] = static_cast<std::uint32_t>(f);
  w.triangle_normals.resize(model.triangles.size());
  return w;
}

BridgeEnds RestBridgeEnds(const PartModel& child) {
  const double h = child.joint.blend_length;
  BridgeEnds rest;
  const double end_v = std::min(h / std::max(child.spine_length, 1e-12), 1.0);
  rest.end_tangent =
      InterpolateSpine(child.spine_points, child.spine_frames, end_v, &rest.end).tangent;
  rest.start_tangent = child.joint.parent_axis;
  rest.start = child.spine_points.front() - h * rest.start_tangent;
  return rest;
}

RigidBodyState RestRigidBodyState(const PartModel& part) {
  RigidBodyState state;
  state.position = part.mass.center;
  state.orientation = Quat(part.mass.principal_axes);
  return state;
}

PartPose PoseFromRigidBody(const PartModel& part, const RigidBodyState& state) {
  PartPose pose;
  const Quat rest(part.mass.principal_axes);
  pose.rotation = (state.orientation * rest.conjugate()).normalized();
  // x_c = root + R (c0 - root) + t  =>  t = x_c - root - R (c0 - root)
  const Vec3 root = part.spine_points.front();
  pose.translation = state.position - root - pose.rotation * (part.mass.center - root);
  return pose;
}

Status EvaluateRigJob::Validate() const {
  if (!model) return Status::Invalid("model", "is required");
  if (!workspace) return Status::Invalid("workspace", "is required");
  if (poses.size() != model->parts.size())
    return Status::Invalid("poses", "needs one pose per part");
  if (positions.size() != model->vertices.size())
    return Status::Invalid("positions", "needs one element per vertex");
  if (!warnings.empty() && warnings.size() != model->parts.size())
    return Status::Invalid("warnings", "must be empty or have one element per part");
  if (!normals.empty() && normals.size() != model->vertices.size())
    return Status::Invalid("normals", "must be empty or have one element per vertex");
  if (workspace->spine_points.size() != model->parts.size() ||
      workspace->normal_accumulator.size() != model->vertices.size() ||
      workspace->layout.pairs.size() + workspace->layout.caps.size() != model->vertices.size() ||
      workspace->layout.profile_base.size() != model->parts.size() ||
      workspace->triangle_normals.size() != model->triangles.size())
    return Status::Invalid("workspace", "was made for another model");
  for (const PartPose& pose : poses) {
    const Eigen::Vector4d q = pose.rotation.coeffs();
    if (!(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]) &&
          std::isfinite(q[3]) && std::abs(q.squaredNorm() - 1.0) < 1e-6))
      return Status::Invalid("poses", "rotations must be finite unit quaternions");
    if (!(std::isfinite(pose.translation.x()) && std::isfinite(pose.translation.y()) &&
          std::isfinite(pose.translation.z())))
      return Status::Invalid("poses", "translations must be finite");
    if (Status s = ValidateLoads(pose.loads); !s) return s;
  }
  for (const ProfileLoads& loads : profile_loads) {
    if (loads.part >= model->parts.size() ||
        loads.profile >= model->parts[loads.part].profiles.size())
      return Status::Invalid("profile_loads", "names a profile the model does not have");
    if (!(loads.from >= 0.0 && loads.to <= 1.0 && loads.from < loads.to))
      return Status::Invalid("profile_loads", "needs 0 <= from < to <= 1");
  }
  return Status::Ok();
}

Status EvaluateRigJob::Run() const {
  if (Status s = Validate(); !s) return s;
  RigWorkspace& w = *workspace;
  for (std::size_t i = 0; i < model->parts.size(); ++i) {
    const PartModel& part = model->parts[i];
    const PartPose& pose = poses[i];
    const std::size_t n = part.spine_points.size();
    std::span<Vec3> points(w.spine_points[i]);
    std::span<Frame> frames(w.spine_frames[i]);
    std::copy(part.spine_points.begin(), part.spine_points.end(), points.begin());

    // 1. Deformation in the spine's rest local frames.
    if (part.kind == SpineKind::kDeformable) {
      for (std::size_t k = 0; k < n; ++k) w.samples[k] = double(k) / double(n - 1);
      const std::span<const double> samples(w.samples.data(), n);
      BendingJob bending;
      bending.boundary = pose.loads.boundary;
      bending.length = part.spine_length;
      bending.bending_stiffness = part.spine_stiffness.bending;
      bending.tip_force = pose.loads.tip_force;
      bending.start_displacement = pose.loads.start_displacement;
      bending.end_displacement = pose.loads.end_displacement;
      bending.point_loads = pose.loads.bending_point_loads;
      bending.line_loads = pose.loads.bending_line_loads;
      bending.samples = samples;
      bending.displacement = std::span<Vec3>(w.bending.data(), n);
      bending.slope = std::span<Vec3>(w.slope.data(), n);
      if (Status s = bending.Run(); !s) return Status::Invalid("poses", s.reason);
      AxialJob axial;
      axial.length = part.spine_length;
      axial.axial_stiffness = part.spine_stiffness.axial;
      axial.fixed_at = pose.loads.axial_fixed_at;
      axial.point_loads = pose.loads.axial_point_loads;
      axial.line_loads = pose.loads.axial_line_loads;
      axial.samples = samples;
      axial.displacement = std::span<double>(w.axial.data(), n);
      axial.normal_force = w.strain[i];
      if (Status s = axial.Run(); !s) return Status::Invalid("poses", s.reason);
      for (double& strain : w.strain[i]) strain /= part.spine_stiffness.axial;
      if (!warnings.empty()) {
        PartWarnings& warn = warnings[i];
        warn = PartWarnings{};
        for (std::size_t k = 0; k < n; ++k) {
          warn.max_slope = std::max(warn.max_slope, std::atan(w.slope[k].head<2>().norm()));
          warn.max_deflection_ratio = std::max(warn.max_deflection_ratio,
                                               w.bending[k].head<2>().norm() / part.spine_length);
        }
        warn.beyond_small_deflection = warn.max_slope > 0.3 || warn.max_deflection_ratio > 0.1;
      }
      // Each frame turns minimally onto the exact deformed tangent (closed-form slope).
      for (std::size_t k = 0; k < n; ++k) {
        const Frame& f = part.spine_frames[k];
        points[k] +=
            w.bending[k].x() * f.normal + w.bending[k].y() * f.binormal + w.axial[k] * f.tangent;
        const Vec3 tangent =
            (f.tangent + w.slope[k].x() * f.normal + w.slope[k].y() * f.binormal).normalized();
        frames[k] = RotateFrame(Quat::FromTwoVectors(f.tangent, tangent).toRotationMatrix(), f);
      }
    } else {
      std::copy(part.spine_frames.begin(), part.spine_frames.end(), frames.begin());
      if (!warnings.empty()) warnings[i] = PartWarnings{};
    }

    // 2. The part's own rigid pose, about its rest root point.
    const Mat3 rotation = pose.rotation.toRotationMatrix();
    const Vec3 root = part.spine_points.front();
    for (std::size_t k = 0; k < n; ++k) {
      points[k] = root + rotation * (points[k] - root) + pose.translation;
      frames[k] = RotateFrame(rotation, frames[k]);
    }

    // 3. Follow the parent: its deformed frame at the attachment replaces its rest frame there.
    if (part.parent >= 0) {
      const PartModel& parent = model->parts[part.parent];
      Vec3 rest_origin, moved_origin;
      const Frame rest =
          InterpolateSpine(parent.spine_points, parent.spine_frames, part.attachment, &rest_origin);
      const Frame moved = InterpolateSpine(w.spine_points[part.parent], w.spine_frames[part.parent],
                                           part.attachment, &moved_origin);
      const Mat3 follow = FrameAxes(moved) * FrameAxes(rest).transpose();
      for (std::size_t k = 0; k < n; ++k) {
        points[k] = moved_origin + follow * (points[k] - rest_origin);
        frames[k] = RotateFrame(follow, frames[k]);
      }
    }

    // 4. Profiles ride on the spine frames (scaled in their plane to keep the volume).
    for (std::size_t p = 0; p < part.profiles.size(); ++p) {
      const ProfileModel& profile = part.profiles[p];
      Vec3 origin;
      const Frame frame = InterpolateSpine(points, frames, profile.spine_v, &origin);
      Mat3 axes = FrameAxes(frame);
      w.profile_scale[i][p] = 1.0;
      if (preserve_volume && part.kind == SpineKind::kDeformable) {
        const double x = profile.spine_v * double(n - 1);
        const std::size_t k = std::min(static_cast<std::size_t>(x), n - 2);
        const double f = x - double(k);
        const double strain = (1.0 - f) * w.strain[i][k] + f * w.strain[i][k + 1];
        const double scale = 1.0 / std::sqrt(std::max(1.0 + strain, 1e-6));
        w.profile_scale[i][p] = scale;
        axes.col(0) *= scale;
        axes.col(1) *= scale;
      }
      w.profile_origins[i][p] = origin;
      w.profile_normals[i][p] = frame.tangent;
      // The end caps' frame: in-plane like the profile, and 1/scale^2 along the tangent, so a
      // cap keeps its volume and meets the profile's plane continuously.
      const std::size_t g = w.layout.profile_base[i] + p;
      w.cap_origins[g] = origin;
      w.cap_axes[g] = axes;
      w.cap_axes[g].col(2) /= w.profile_scale[i][p] * w.profile_scale[i][p];
      std::vector<Vec3>& out = w.profile_points[i][p];
      for (std::size_t q = 0; q < profile.local_points.size(); ++q)
        out[q] = origin + axes * profile.local_points[q];
    }
  }

  // 5. Profile wires bend under their own loads, in their spine frames.
  for (const ProfileLoads& loads : profile_loads) {
    const PartModel& part = model->parts[loads.part];
    const ProfileModel& profile = part.profiles[loads.profile];
    std::vector<Vec3>& points = w.profile_points[loads.part][loads.profile];
    const std::size_t m = profile.local_points.size();
    const double segments = double(profile.closed ? m : m - 1);
    // The stretch's points (and their parameter on the stretch) and its rest arc length.
    std::size_t count = 0;
    double length = 0.0;
    for (std::size_t q = 0; q <= (profile.closed ? m : m - 1); ++q) {
      const double u = double(q) / segments;
      if (q > 0 && u > loads.from && double(q - 1) / segments < loads.to)
        length += (profile.local_points[q % m] - profile.local_points[q - 1]).norm() *
                  (std::min(u, loads.to) - std::max(double(q - 1) / segments, loads.from)) *
                  segments;
      if (u >= loads.from && u <= loads.to && !(profile.closed && q == m && loads.from == 0.0))
        w.profile_samples[count++] = (u - loads.from) / (loads.to - loads.from);
    }
    if (count == 0 || !(length > 0.0)) continue;
    BendingJob bending;
    bending.boundary = loads.boundary;
    bending.length = length;
    bending.bending_stiffness = profile.stiffness.bending;
    bending.point_loads = loads.point_loads;
    bending.line_loads = loads.line_loads;
    bending.samples = std::span<const double>(w.profile_samples.data(), count);
    bending.displacement = std::span<Vec3>(w.profile_displacement.data(), count);
    if (Status s = bending.Run(); !s) return Status::Invalid("profile_loads", s.reason);
    Vec3 origin;
    const Mat3 axes = FrameAxes(InterpolateSpine(
        w.spine_points[loads.part], w.spine_frames[loads.part], profile.spine_v, &origin));
    std::size_t k = 0;
    for (std::size_t q = 0; q <= (profile.closed ? m : m - 1) && k < count; ++q) {
      const double u = double(q) / segments;
      if (u >= loads.from && u <= loads.to && !(profile.closed && q == m && loads.from == 0.0))
        points[q % m] += axes * w.profile_displacement[k++];
    }
  }

  // Warnings: tight bends (radius of curvature below the spine-to-surface distance) and
  // crossing adjacent profiles, on the final geometry.
  for (std::size_t i = 0; i < warnings.size(); ++i) {
    const PartModel& part = model->parts[i];
    const std::vector<Vec3>& points = w.spine_points[i];
    const std::vector<Frame>& frames = w.spine_frames[i];
    for (std::size_t k = 1; k < points.size(); ++k) {
      const double step = (points[k] - points[k - 1]).norm();
      const double turn =
          std::acos(std::clamp(frames[k].tangent.dot(frames[k - 1].tangent), -1.0, 1.0));
      if (turn * part.max_radius > step) ++warnings[i].tight_bends;
    }
    for (std::size_t p = 0; p + 1 < part.profiles.size(); ++p) {
      warnings[i].crossing_profiles += ProfilesCross(
          w.profile_points[i][p], w.profile_origins[i][p], w.profile_normals[i][p],
          w.profile_points[i][p + 1], w.profile_origins[i][p + 1], w.profile_normals[i][p + 1]);
    }
  }

  // 6. Vertices follow the profiles: the world wire points and pair centres laid out flat, then
  // every vertex from its flat binding.
  for (std::size_t i = 0; i < model->parts.size(); ++i) {
    const std::size_t profiles = model->parts[i].profiles.size();
    for (std::size_t p = 0; p < profiles; ++p) {
      const std::size_t g = w.layout.profile_base[i] + p;
      std::copy(w.profile_points[i][p].begin(), w.profile_points[i][p].end(),
                w.wire_points.begin() + w.layout.point_base[g]);
      if (p + 1 < profiles)
        w.pair_centres[g] = 0.5 * (w.profile_origins[i][p] + w.profile_origins[i][p + 1]);
    }
  }
  const VertexPass pass{this, workspace};
  RunTasks(parallel,
           VertexPass::Tasks(w.layout.pairs.size()) + VertexPass::Tasks(w.layout.caps.size()),
           &VertexPass::Vertices, &pass);

  // 7. Vertices near joints follow the skin bridges.
  FollowJointBridges(*model, w, positions, parallel);

  // 8. Area-weighted vertex normals.
  if (normals.empty()) return Status::Ok();
  // One thread: accumulate every triangle's normal into its vertices in one pass (the fewest
  // memory passes). Threads: every triangle's normal, then per vertex the sum of its triangles'
  // in increasing triangle order. Both add the same terms in the same order: identical sums.
  if (parallel == nullptr || parallel->concurrency() <= 1) {
    std::fill(w.normal_accumulator.begin(), w.normal_accumulator.end(), Vec3::Zero());
    for (const Triangle& t : model->triangles) {
      const Vec3 n = (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
      for (std::uint32_t index : t) w.normal_accumulator[index] += n;
    }
    for (std::size_t v = 0; v < normals.size(); ++v) {
      const double length = w.normal_accumulator[v].norm();
      normals[v] = length > 0.0 ? Vec3(w.normal_accumulator[v] * (1.0 / length)) : Vec3::UnitY();
    }
    return Status::Ok();
  }
  RunTasks(parallel, VertexPass::Tasks(model->triangles.size()), &VertexPass::TriangleNormals,
           &pass);
  RunTasks(parallel, VertexPass::Tasks(normals.size()), &VertexPass::VertexNormals, &pass);
  return Status::Ok();
}

}  // namespace wirerig
