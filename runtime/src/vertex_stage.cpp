#include "vertex_stage.h"

#include "vertex_stage_passes.h"

namespace wirerig {
namespace {

// The layout's undo samples, as an index: (part, sample) -> position in the sorted list.
std::uint32_t UndoIndex(const RigEvaluationLayout& layout, std::uint32_t part,
                        std::uint32_t sample) {
  const auto it = std::lower_bound(layout.undo_samples.begin(), layout.undo_samples.end(),
                                   std::make_pair(part, sample));
  return static_cast<std::uint32_t>(it - layout.undo_samples.begin());
}

}  // namespace

template <class Real>
void MakeVertexStagePlan(const RigModel& model, const RigEvaluationLayout& layout,
                         VertexStagePlan<Real>* plan) {
  VertexStagePlan<Real>& s = *plan;
  const std::size_t n = model.vertices.size();
  s.slot_of_vertex.assign(n, 0);
  s.vertex_of_slot.clear();
  for (int caps = 0; caps < 2; ++caps)
    for (std::size_t v = 0; v < n; ++v)
      if (model.vertices[v].cap == (caps == 1)) {
        s.slot_of_vertex[v] = static_cast<std::uint32_t>(s.vertex_of_slot.size());
        s.vertex_of_slot.push_back(static_cast<std::uint32_t>(v));
      }
  // PointOnWire's indices: segment k clamped to the wire, wrapping to point 0 after the last.
  auto ends = [&](std::uint32_t g, std::size_t count, std::uint32_t k,
                  std::vector<std::uint32_t>* i0, std::vector<std::uint32_t>* i1) {
    const std::size_t first = std::min<std::size_t>(k, count - 1);
    i0->push_back(layout.point_base[g] + static_cast<std::uint32_t>(first));
    i1->push_back(layout.point_base[g] +
                  static_cast<std::uint32_t>(first + 1 < count ? first + 1 : 0));
  };
  for (std::uint32_t v : s.vertex_of_slot) {
    const VertexAttachment& a = model.vertices[v];
    const std::uint32_t g = layout.profile_base[a.part] + a.profile;
    if (a.cap) {
      s.cap_profile.push_back(g);
      s.cap_local.x.push_back(Real(a.cap_local.x()));
      s.cap_local.y.push_back(Real(a.cap_local.y()));
      s.cap_local.z.push_back(Real(a.cap_local.z()));
      continue;
    }
    const PartModel& part = model.parts[a.part];
    s.profile.push_back(g);
    ends(g, part.profiles[a.profile].local_points.size(), a.pair.k1, &s.a0, &s.a1);
    ends(g + 1, part.profiles[a.profile + 1].local_points.size(), a.pair.k2, &s.b0, &s.b1);
    s.lambda1.push_back(Real(a.pair.lambda1));
    s.lambda2.push_back(Real(a.pair.lambda2));
    s.alpha.push_back(Real(a.pair.alpha));
    s.beta.push_back(Real(a.pair.beta));
    s.gamma.push_back(Real(a.pair.gamma));
  }
  s.pair_count = s.profile.size();

  // Bridged vertices and their entries; the entries sorted into (joint, segment) buckets.
  const std::vector<RigEvaluationLayout::JointVertex>& entries = layout.joint_vertices;
  std::vector<std::uint32_t> entry_bridged(entries.size());
  std::vector<int> segment(entries.size());
  std::vector<double> fraction_in(entries.size());
  for (std::size_t e = 0; e < entries.size(); ++e) {
    const RigEvaluationLayout::JointVertex& j = entries[e];
    if (e == 0 || entries[e - 1].vertex != j.vertex) {
      s.bridged_slot.push_back(s.slot_of_vertex[j.vertex]);
      s.bridged_undo.push_back(UndoIndex(layout, j.part, j.sample));
    }
    entry_bridged[e] = static_cast<std::uint32_t>(s.bridged_slot.size() - 1);
    BridgeSegmentOf(j.u, &segment[e], &fraction_in[e]);
  }
  std::vector<std::uint32_t> order(entries.size());
  std::iota(order.begin(), order.end(), 0u);
  // By joint, then segment, then entry (a total order: no temporary buffer, as stable_sort takes).
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (entries[a].joint != entries[b].joint) return entries[a].joint < entries[b].joint;
    if (segment[a] != segment[b]) return segment[a] < segment[b];
    return a < b;
  });
  std::vector<std::uint32_t> sorted_position(entries.size());
  auto push_entry = [&](std::uint32_t bridged, std::uint32_t slot, double f, double u,
                        double fraction, double section, double weight,
                        RigEvaluationLayout::JointBase base) {
    s.entry_bridged.push_back(bridged);
    s.entry_slot.push_back(slot);
    s.entry_f.push_back(Real(f));
    s.entry_u.push_back(Real(std::clamp(u, 0.0, 1.0)));
    s.entry_fraction.push_back(Real(fraction));
    s.entry_section.push_back(Real(section));
    s.entry_weight.push_back(Real(weight));
    s.entry_base.push_back(Real(static_cast<int>(base)));
  };
  for (std::size_t i = 0; i < order.size();) {
    typename VertexStagePlan<Real>::Bucket bucket;
    bucket.joint = entries[order[i]].joint;
    bucket.segment = segment[order[i]];
    bucket.begin = static_cast<std::uint32_t>(s.entry_bridged.size());
    for (; i < order.size() && entries[order[i]].joint == bucket.joint &&
           segment[order[i]] == bucket.segment;
         ++i) {
      const std::uint32_t e = order[i];
      const RigEvaluationLayout::JointVertex& j = entries[e];
      sorted_position[e] = static_cast<std::uint32_t>(s.entry_bridged.size());
      push_entry(entry_bridged[e], s.bridged_slot[entry_bridged[e]], fraction_in[e], j.u, j.bridge,
                 j.section, j.weight, j.base);
    }
    while (s.entry_bridged.size() % kBucketMultiple != 0)
      push_entry(0, s.bridged_slot[0], 0.0, 0.0, 1.0, 1.0, 0.0,
                 RigEvaluationLayout::JointBase::kParent);
    bucket.end = static_cast<std::uint32_t>(s.entry_bridged.size());
    s.buckets.push_back(bucket);
  }
  s.entry_offsets = {0};
  for (std::size_t e = 0; e < entries.size(); ++e) {
    s.entry_of.push_back(sorted_position[e]);
    if (e + 1 == entries.size() || entries[e + 1].vertex != entries[e].vertex)
      s.entry_offsets.push_back(static_cast<std::uint32_t>(s.entry_of.size()));
  }
  s.bucket_task_starts = {0};
  std::uint32_t in_task = 0;
  for (std::size_t b = 0; b < s.buckets.size(); ++b) {
    in_task += s.buckets[b].end - s.buckets[b].begin;
    if (in_task >= kTaskSize && b + 1 < s.buckets.size()) {
      s.bucket_task_starts.push_back(static_cast<std::uint32_t>(b + 1));
      in_task = 0;
    }
  }
  s.bucket_task_starts.push_back(static_cast<std::uint32_t>(s.buckets.size()));

  // Triangles by slot; each slot's triangles in increasing order.
  std::vector<std::uint32_t> count(n, 0);
  for (const Triangle& t : model.triangles) {
    s.t0.push_back(s.slot_of_vertex[t[0]]);
    s.t1.push_back(s.slot_of_vertex[t[1]]);
    s.t2.push_back(s.slot_of_vertex[t[2]]);
    for (std::uint32_t index : t) ++count[s.slot_of_vertex[index]];
  }
  s.slot_triangle_offsets.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
    s.slot_triangle_offsets[i + 1] = s.slot_triangle_offsets[i] + count[i];
  s.slot_triangles.resize(s.slot_triangle_offsets.back());
  std::vector<std::uint32_t> fill(s.slot_triangle_offsets.begin(),
                                  s.slot_triangle_offsets.end() - 1);
  for (std::size_t f = 0; f < model.triangles.size(); ++f)
    for (std::uint32_t index : model.triangles[f])
      s.slot_triangles[fill[s.slot_of_vertex[index]]++] = static_cast<std::uint32_t>(f);

  // Rotated normals: the rest normals in the slots' frames; the bridged slots' triangles.
  const std::vector<Vec3> local = RestNormalsInSlotFrames(model, layout, s.vertex_of_slot);
  s.rest_normal_local.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.rest_normal_local.x[i] = Real(local[i].x()), s.rest_normal_local.y[i] = Real(local[i].y());
    s.rest_normal_local.z[i] = Real(local[i].z());
  }
  std::vector<bool> bridged(n, false);
  for (const std::uint32_t slot : s.bridged_slot) bridged[slot] = true;
  std::vector<std::uint32_t> compact(s.t0.size(), 0);  // triangle -> bridged triangle j
  for (std::size_t f = 0; f < s.t0.size(); ++f)
    if (bridged[s.t0[f]] || bridged[s.t1[f]] || bridged[s.t2[f]]) {
      compact[f] = static_cast<std::uint32_t>(s.bt0.size());
      s.bt0.push_back(s.t0[f]), s.bt1.push_back(s.t1[f]), s.bt2.push_back(s.t2[f]);
    }
  std::vector<bool> corner(n, false);
  for (const std::vector<std::uint32_t>* c : {&s.bt0, &s.bt1, &s.bt2})
    for (const std::uint32_t slot : *c) corner[slot] = true;
  for (std::size_t i = 0; i < n; ++i)
    if (corner[i]) s.bridged_corners.push_back(static_cast<std::uint32_t>(i));
  s.bridged_triangle_offsets = {0};
  for (const std::uint32_t slot : s.bridged_slot) {
    for (std::uint32_t t = s.slot_triangle_offsets[slot]; t < s.slot_triangle_offsets[slot + 1];
         ++t)
      s.bridged_triangles.push_back(compact[s.slot_triangles[t]]);
    s.bridged_triangle_offsets.push_back(static_cast<std::uint32_t>(s.bridged_triangles.size()));
  }
}

template <class Real>
void MakeVertexStage(const RigModel& model, const RigEvaluationLayout& layout,
                     const VertexStagePlan<Real>& plan, VertexStage<Real>* stage) {
  VertexStage<Real>& s = *stage;
  s.plan = &plan;
  const std::size_t n = model.vertices.size();
  const std::size_t profiles = layout.point_base.size();
  std::size_t points = 0;
  for (const PartModel& part : model.parts)
    for (const ProfileModel& profile : part.profiles) points += profile.local_points.size();
  s.position.resize(n);
  s.wire.resize(points);
  s.pair_centre.resize(profiles);
  s.cap_origin.resize(profiles);
  s.cap_axes.assign(profiles, VertexStage<Real>::M::Identity());
  s.rest.resize(plan.bridged_slot.size());
  s.correction.resize(plan.entry_bridged.size());
  s.face_normal.resize(model.triangles.size());
  const std::size_t padded = (n + kBucketMultiple - 1) / kBucketMultiple * kBucketMultiple;
  s.normal_sum.assign(4 * padded, Real(0));
  s.unit_normal.resize(padded);
  s.rotated_normal.resize(padded);
  s.cap_normal_axes.assign(profiles, VertexStage<Real>::M::Identity());
  s.undo.assign(layout.undo_samples.size(), VertexStage<Real>::M::Identity());
  s.undo_rest_point.assign(layout.undo_samples.size(), VertexStage<Real>::V::Zero());
  s.undo_point.assign(layout.undo_samples.size(), VertexStage<Real>::V::Zero());
  if constexpr (!std::is_same_v<Real, double>) s.bridges.resize(model.parts.size());
}

template <class Real>
void RunVertexStage(const RigModel& model, RigWorkspace& w, VertexStage<Real>& s,
                    const StageOutput<Real>& output, const ParallelFor* parallel) {
  if constexpr (std::is_same_v<Real, float>) {
#if WIRERIG_HAVE_AVX2_STAGE
    if (output.allow_avx2 && CpuHasAvx2()) return RunVertexStageAvx2(model, w, s, output, parallel);
#endif
#if WIRERIG_HAVE_SSE2
    RunStage<float, simd::Float4>(model, w, s, output, parallel);
#else
    RunStage<float, simd::OneLane<float>>(model, w, s, output, parallel);
#endif
  } else {
    RunStage<double, simd::OneLane<double>>(model, w, s, output, parallel);
  }
}

template void MakeVertexStagePlan(const RigModel&, const RigEvaluationLayout&,
                                  VertexStagePlan<double>*);
template void MakeVertexStagePlan(const RigModel&, const RigEvaluationLayout&,
                                  VertexStagePlan<float>*);
template void MakeVertexStage(const RigModel&, const RigEvaluationLayout&,
                              const VertexStagePlan<double>&, VertexStage<double>*);
template void MakeVertexStage(const RigModel&, const RigEvaluationLayout&,
                              const VertexStagePlan<float>&, VertexStage<float>*);
template void RunVertexStage(const RigModel&, RigWorkspace&, VertexStage<double>&,
                             const StageOutput<double>&, const ParallelFor*);
template void RunVertexStage(const RigModel&, RigWorkspace&, VertexStage<float>&,
                             const StageOutput<float>&, const ParallelFor*);

}  // namespace wirerig
