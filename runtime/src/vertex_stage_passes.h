// The vertex stage's passes (vertex_stage.h), written once against a pack type Wide and compiled
// twice: by vertex_stage.cpp for the baseline (one double lane; four floats with SSE2) and by
// vertex_stage_avx2.cpp inside an AVX2 target region (eight floats). Everything here lies in an
// unnamed namespace, so the two compilations share no symbol: no AVX2 code can stand in for
// baseline code at link time. Include only from those two files.
#pragma once

#include <algorithm>
#include <cmath>
#include <numeric>

#include "vertex_stage.h"
#include "wirerig/runtime/simd_pack.h"

namespace wirerig {
namespace {

// Vertices, entries and triangles per parallel task: large enough that claiming a task costs
// nothing next to it, small enough that two threads share out a mesh evenly. A multiple of
// every pack width (kBucketMultiple: eight floats with AVX2).
constexpr std::size_t kTaskSize = 2048;
constexpr std::uint32_t kBucketMultiple = 8;

// ApplyPairFast's bounds, per lane type: while squared lengths stay within them no product
// below overflows or underflows, and the frame is regular enough for the lane's precision
// (sine of the angle between e and d above 1e-8 in double, 1e-3 in float); outside them the
// vertex goes through ApplyPairBinding in double.
template <class Real>
struct PairBounds;
template <>
struct PairBounds<double> {
  static constexpr double kMinSquared = 1e-140, kMaxSquared = 1e140, kSine2 = 1e-16;
};
template <>
struct PairBounds<float> {
  static constexpr float kMinSquared = 1e-30f, kMaxSquared = 1e30f, kSine2 = 1e-6f;
};

std::size_t Tasks(std::size_t items) { return (items + kTaskSize - 1) / kTaskSize; }

// Lanes of a 3-vector from one array per coordinate, at c[index[l]]. Always inlined: called
// per vertex in every pass (a call per gather cost a quarter of a frame).
template <class P, class Coordinates>
[[gnu::always_inline]] inline simd::V3<typename P::Value> GatherV3(const Coordinates& c,
                                                                   const std::uint32_t* index) {
  return {P::Gather(c.x.data(), index), P::Gather(c.y.data(), index), P::Gather(c.z.data(), index)};
}

template <class Real, class Wide>
struct StagePasses {
  using S = VertexStage<Real>;
  using One = simd::OneLane<Real>;

  const RigModel* model;
  const RigWorkspace* w;
  S* s;
  const BasicBridgeSamples<Real>* bridges;  // by part
  StageOutput<Real> out;

  // Whether the normals are the rest normals turned (NormalMode::kRotated).
  bool Rotating() const { return out.normals && out.normal_mode == NormalMode::kRotated; }

  // PHYSICS.md section 6, step "apply", for regular frames: with e = p2 - p1, d = c - p1,
  // n = e x d and the section unit s = sqrt(|d|^2 + kEdgeInSectionUnit2 |e|^2), the point is
  // p1 + alpha e + (beta s / |e|) (n_hat x e) + gamma s n_hat (ApplyPairBinding up to
  // rounding). kRotate: also the rest normal turned with the frame, |e| (a e_hat + b m_hat +
  // c n_hat) for its components (a, b, c) in the rest frame (m_hat = n_hat x e_hat; the length
  // is normalised away by Output). Returns the lanes (bits) whose frame needs ApplyPairBinding
  // itself.
  template <class P, bool kRotate>
  int PairPack(std::size_t i) const {
    using Value = typename P::Value;
    using V = simd::V3<Value>;
    const S& st = *s;
    auto gather = [](const typename S::Coordinates& c, const std::uint32_t* index) {
      return GatherV3<P>(c, index);
    };
    const Value one = P::Broadcast(Real(1));
    const Value l1 = P::Load(&st.plan->lambda1[i]), l2 = P::Load(&st.plan->lambda2[i]);
    const V p1 =
        (one - l1) * gather(st.wire, &st.plan->a0[i]) + l1 * gather(st.wire, &st.plan->a1[i]);
    const V p2 =
        (one - l2) * gather(st.wire, &st.plan->b0[i]) + l2 * gather(st.wire, &st.plan->b1[i]);
    const V e = p2 - p1;
    const V d = gather(st.pair_centre, &st.plan->profile[i]) - p1;
    const Value ee = simd::Dot(e, e), dd = simd::Dot(d, d);
    const V n = simd::Cross(e, d);
    const Value nn = simd::Dot(n, n);
    using B = PairBounds<Real>;
    const Value lo = P::Broadcast(B::kMinSquared), hi = P::Broadcast(B::kMaxSquared);
    const auto ok = P::And(P::And(P::And(P::Greater(ee, lo), P::Greater(hi, ee)),
                                  P::And(P::Greater(dd, lo), P::Greater(hi, dd))),
                           P::Greater(nn, P::Broadcast(B::kSine2) * ee * dd));
    const Value safe_nn = P::Select(ok, nn, one), safe_ee = P::Select(ok, ee, one);
    const V n_hat = (one / P::Sqrt(safe_nn)) * n;
    const Value section =
        P::Sqrt(P::Select(ok, dd + P::Broadcast(Real(kEdgeInSectionUnit2)) * ee, one));
    const Value length = P::Sqrt(safe_ee);
    const V m = simd::Cross(n_hat, e);
    const V p = p1 + P::Load(&st.plan->alpha[i]) * e +
                (P::Load(&st.plan->beta[i]) * section / length) * m +
                (P::Load(&st.plan->gamma[i]) * section) * n_hat;
    P::Store(&s->position.x[i], p.x);
    P::Store(&s->position.y[i], p.y);
    P::Store(&s->position.z[i], p.z);
    if constexpr (kRotate) {
      const typename S::Coordinates& rest = st.plan->rest_normal_local;
      const V normal = P::Load(&rest.x[i]) * e + P::Load(&rest.y[i]) * m +
                       (P::Load(&rest.z[i]) * length) * n_hat;
      P::Store(&s->rotated_normal.x[i], normal.x);
      P::Store(&s->rotated_normal.y[i], normal.y);
      P::Store(&s->rotated_normal.z[i], normal.z);
    }
    return ~P::Bits(ok) & ((1 << P::kWidth) - 1);
  }

  // ApplyPairBinding itself (double), on the wires as spans; rotating, the rest normal turned
  // by ApplyPairFrame (zero, so +Y out of Output, where the wires meet and no frame exists).
  void SlowPair(std::size_t slot) const {
    const std::uint32_t vertex = s->plan->vertex_of_slot[slot];
    const VertexAttachment& a = model->vertices[vertex];
    const PartModel& part = model->parts[a.part];
    const WirePolyline wire_i{w->profile_points[a.part][a.profile],
                              part.profiles[a.profile].closed};
    const WirePolyline wire_j{w->profile_points[a.part][a.profile + 1],
                              part.profiles[a.profile + 1].closed};
    const Vec3 p = ApplyPairBinding(a.pair, wire_i, wire_j, w->profile_origins[a.part][a.profile],
                                    w->profile_origins[a.part][a.profile + 1]);
    s->position.x[slot] = Real(p.x()), s->position.y[slot] = Real(p.y());
    s->position.z[slot] = Real(p.z());
    if (!Rotating()) return;
    const typename S::Coordinates& rest = s->plan->rest_normal_local;
    Mat3 axes;
    Vec3 normal = Vec3::Zero();
    if (ApplyPairFrame(a.pair, wire_i, wire_j, w->profile_origins[a.part][a.profile],
                       w->profile_origins[a.part][a.profile + 1], &axes))
      normal = axes * Vec3(rest.x[slot], rest.y[slot], rest.z[slot]);
    s->rotated_normal.x[slot] = Real(normal.x()), s->rotated_normal.y[slot] = Real(normal.y());
    s->rotated_normal.z[slot] = Real(normal.z());
  }

  template <class P, bool kRotate>
  void Pairs(std::size_t begin, std::size_t end) const {
    std::size_t i = begin;
    for (; i + P::kWidth <= end; i += P::kWidth)
      if (const int failed = PairPack<P, kRotate>(i))
        for (int l = 0; l < P::kWidth; ++l)
          if (failed & (1 << l)) SlowPair(i + std::size_t(l));
    for (; i < end; ++i)
      if (PairPack<One, kRotate>(i)) SlowPair(i);
  }

  // Task k: pair slots [k kTaskSize, (k + 1) kTaskSize), then the cap slots likewise.
  static void Vertices(const void* context, std::size_t k) {
    const auto& self = *static_cast<const StagePasses*>(context);
    S& st = *self.s;
    const std::size_t pair_tasks = Tasks(st.plan->pair_count);
    const bool rotate = self.Rotating();
    if (k < pair_tasks) {
      const std::size_t begin = k * kTaskSize;
      const std::size_t end = std::min(st.plan->pair_count, (k + 1) * kTaskSize);
      if (rotate)
        self.template Pairs<Wide, true>(begin, end);
      else
        self.template Pairs<Wide, false>(begin, end);
      return;
    }
    const std::size_t caps = st.plan->cap_profile.size();
    const std::size_t end = std::min(caps, (k - pair_tasks + 1) * kTaskSize);
    for (std::size_t c = (k - pair_tasks) * kTaskSize; c < end; ++c) {
      const std::uint32_t g = st.plan->cap_profile[c];
      const typename S::V local(st.plan->cap_local.x[c], st.plan->cap_local.y[c],
                                st.plan->cap_local.z[c]);
      const typename S::V p =
          typename S::V(st.cap_origin.x[g], st.cap_origin.y[g], st.cap_origin.z[g]) +
          st.cap_axes[g] * local;
      const std::size_t slot = st.plan->pair_count + c;
      st.position.x[slot] = p.x(), st.position.y[slot] = p.y(), st.position.z[slot] = p.z();
      if (!rotate) continue;
      const typename S::Coordinates& rest = st.plan->rest_normal_local;
      const typename S::V n =
          st.cap_normal_axes[g] * typename S::V(rest.x[slot], rest.y[slot], rest.z[slot]);
      st.rotated_normal.x[slot] = n.x(), st.rotated_normal.y[slot] = n.y();
      st.rotated_normal.z[slot] = n.z();
    }
  }

  // Bridged vertices [k kTaskSize, ...): where their own part put them, undone into rest space.
  static void Undo(const void* context, std::size_t k) {
    const auto& self = *static_cast<const StagePasses*>(context);
    S& st = *self.s;
    const std::size_t end = std::min(st.plan->bridged_slot.size(), (k + 1) * kTaskSize);
    for (std::size_t b = k * kTaskSize; b < end; ++b) {
      const std::uint32_t slot = st.plan->bridged_slot[b], u = st.plan->bridged_undo[b];
      const typename S::V own(st.position.x[slot], st.position.y[slot], st.position.z[slot]);
      const typename S::V rest = st.undo_rest_point[u] + st.undo[u] * (own - st.undo_point[u]);
      st.rest.x[b] = rest.x(), st.rest.y[b] = rest.y(), st.rest.z[b] = rest.z();
    }
  }

  // The buckets of task k: each entry's correction, weight * (the bridge's image of its rest
  // point - the rigid motion of its own side: its own position for the child's skin, the
  // child's motion of its rest point for the skin of parts below the child, the parent's
  // otherwise).
  template <class P>
  void Bucket(const typename S::Bucket& bucket) const {
    using Value = typename P::Value;
    using V = simd::V3<Value>;
    S& st = *s;
    const BridgeSegment<P> segment(bridges[bucket.joint], bucket.segment);
    for (std::size_t e = bucket.begin; e < bucket.end; e += P::kWidth) {
      const std::uint32_t* bridged = &st.plan->entry_bridged[e];
      const std::uint32_t* slot = &st.plan->entry_slot[e];
      const V q = GatherV3<P>(st.rest, bridged);
      V parent, child;
      const V image = segment.Image(P::Load(&st.plan->entry_f[e]), P::Load(&st.plan->entry_u[e]),
                                    P::Load(&st.plan->entry_fraction[e]),
                                    P::Load(&st.plan->entry_section[e]), q, &parent, &child);
      const Value side = P::Load(&st.plan->entry_base[e]);
      const auto is_own = P::Greater(side, P::Broadcast(Real(0.5)));
      const auto is_child = P::Greater(side, P::Broadcast(Real(1.5)));
      const V own = GatherV3<P>(st.position, slot);
      const V base{P::Select(is_child, child.x, P::Select(is_own, own.x, parent.x)),
                   P::Select(is_child, child.y, P::Select(is_own, own.y, parent.y)),
                   P::Select(is_child, child.z, P::Select(is_own, own.z, parent.z))};
      const V correction = P::Load(&st.plan->entry_weight[e]) * (image - base);
      P::Store(&st.correction.x[e], correction.x);
      P::Store(&st.correction.y[e], correction.y);
      P::Store(&st.correction.z[e], correction.z);
    }
  }

  static void Buckets(const void* context, std::size_t k) {
    const auto& self = *static_cast<const StagePasses*>(context);
    const S& st = *self.s;
    for (std::uint32_t b = st.plan->bucket_task_starts[k]; b < st.plan->bucket_task_starts[k + 1];
         ++b)
      self.template Bucket<Wide>(st.plan->buckets[b]);
  }

  // Bridged vertices: their own position plus their entries' corrections, in entry order.
  static void Sums(const void* context, std::size_t k) {
    const auto& self = *static_cast<const StagePasses*>(context);
    S& st = *self.s;
    const std::size_t end = std::min(st.plan->bridged_slot.size(), (k + 1) * kTaskSize);
    for (std::size_t b = k * kTaskSize; b < end; ++b) {
      Real x = 0, y = 0, z = 0;
      for (std::uint32_t j = st.plan->entry_offsets[b]; j < st.plan->entry_offsets[b + 1]; ++j) {
        const std::uint32_t e = st.plan->entry_of[j];
        x += st.correction.x[e], y += st.correction.y[e], z += st.correction.z[e];
      }
      const std::uint32_t slot = st.plan->bridged_slot[b];
      st.position.x[slot] += x, st.position.y[slot] += y, st.position.z[slot] += z;
    }
  }

  // Triangles of corners (i0[l], i1[l], i2[l]) (slots), l < P::kWidth: (p1 - p0) x (p2 - p0).
  template <class P>
  simd::V3<typename P::Value> FaceNormalOf(const std::uint32_t* i0, const std::uint32_t* i1,
                                           const std::uint32_t* i2) const {
    const S& st = *s;
    const auto p0 = GatherV3<P>(st.position, i0);
    return simd::Cross(GatherV3<P>(st.position, i1) - p0, GatherV3<P>(st.position, i2) - p0);
  }

  // Triangles [k kTaskSize, ...) of corner lists c0, c1, c2: their normals into face_normal at
  // the same indices, packs at a time.
  void FaceNormalTask(std::size_t k, const std::vector<std::uint32_t>& c0,
                      const std::vector<std::uint32_t>& c1,
                      const std::vector<std::uint32_t>& c2) const {
    auto store = [&](auto pack, std::size_t f) {
      using P = decltype(pack);
      const auto n = FaceNormalOf<P>(&c0[f], &c1[f], &c2[f]);
      P::Store(&s->face_normal.x[f], n.x);
      P::Store(&s->face_normal.y[f], n.y);
      P::Store(&s->face_normal.z[f], n.z);
    };
    const std::size_t end = std::min(c0.size(), (k + 1) * kTaskSize);
    std::size_t f = k * kTaskSize;
    for (; f + Wide::kWidth <= end; f += Wide::kWidth) store(Wide{}, f);
    for (; f < end; ++f) store(One{}, f);
  }

  static void FaceNormals(const void* context, std::size_t k) {
    const auto& self = *static_cast<const StagePasses*>(context);
    const VertexStagePlan<Real>& plan = *self.s->plan;
    self.FaceNormalTask(k, plan.t0, plan.t1, plan.t2);
  }

  // Triangles [0, c0.size()) of corner lists c0, c1, c2: each normal added into its corners'
  // sums (normal_sum) in triangle order, packs at a time.
  void ScatterFaceNormals(const std::vector<std::uint32_t>& c0,
                          const std::vector<std::uint32_t>& c1,
                          const std::vector<std::uint32_t>& c2) const {
    auto scatter = [&](auto pack, std::size_t f) {
      using P = decltype(pack);
      const auto n = FaceNormalOf<P>(&c0[f], &c1[f], &c2[f]);
      P::ScatterAdd4(s->normal_sum.data(), n.x, n.y, n.z, &c0[f], &c1[f], &c2[f]);
    };
    std::size_t f = 0;
    for (; f + Wide::kWidth <= c0.size(); f += Wide::kWidth) scatter(Wide{}, f);
    for (; f < c0.size(); ++f) scatter(One{}, f);
  }

  // One thread: every triangle's normal added into its vertices' sums in triangle order.
  void ScatterNormals() const {
    S& st = *s;
    std::fill(st.normal_sum.begin(), st.normal_sum.end(), Real(0));
    ScatterFaceNormals(st.plan->t0, st.plan->t1, st.plan->t2);
  }

  // One thread, rotating: the triangles with a bridged vertex scattered into their corners'
  // sums (those zeroed first), the bridged vertices' sums then taken as their normals: the
  // same terms in the same order as ScatterNormals.
  void ScatterBridgedNormals() const {
    S& st = *s;
    const VertexStagePlan<Real>& plan = *st.plan;
    for (const std::uint32_t slot : plan.bridged_corners)
      std::fill_n(&st.normal_sum[4 * std::size_t(slot)], 4, Real(0));
    ScatterFaceNormals(plan.bt0, plan.bt1, plan.bt2);
    for (const std::uint32_t slot : plan.bridged_slot) {
      const Real* sum = &st.normal_sum[4 * std::size_t(slot)];
      st.rotated_normal.x[slot] = sum[0], st.rotated_normal.y[slot] = sum[1];
      st.rotated_normal.z[slot] = sum[2];
    }
  }

  // face_normal[faces[t]] summed for t in [begin, end): over a slot's triangles in increasing
  // order, the same terms in the same order as ScatterNormals, so identical sums.
  simd::V3<Real> SumOfFaceNormals(const std::vector<std::uint32_t>& faces, std::uint32_t begin,
                                  std::uint32_t end) const {
    const S& st = *s;
    Real x = 0, y = 0, z = 0;
    for (std::uint32_t t = begin; t < end; ++t) {
      const std::uint32_t f = faces[t];
      x += st.face_normal.x[f], y += st.face_normal.y[f], z += st.face_normal.z[f];
    }
    return {x, y, z};
  }

  // Rotating, after the bridges: the triangles with a bridged vertex [k kTaskSize, ...) (plan
  // corners bt0, bt1, bt2) get their face normals, at their index in that list ...
  static void BridgedFaceNormals(const void* context, std::size_t k) {
    const auto& self = *static_cast<const StagePasses*>(context);
    const VertexStagePlan<Real>& plan = *self.s->plan;
    self.FaceNormalTask(k, plan.bt0, plan.bt1, plan.bt2);
  }

  // ... and the bridged vertices [k kTaskSize, ...) their triangles' sums as normals (the
  // triangle mode's sums, bit for bit).
  static void BridgedNormals(const void* context, std::size_t k) {
    const auto& self = *static_cast<const StagePasses*>(context);
    S& st = *self.s;
    const VertexStagePlan<Real>& plan = *st.plan;
    const std::size_t end = std::min(plan.bridged_slot.size(), (k + 1) * kTaskSize);
    for (std::size_t b = k * kTaskSize; b < end; ++b) {
      const std::uint32_t slot = plan.bridged_slot[b];
      const simd::V3<Real> n =
          self.SumOfFaceNormals(plan.bridged_triangles, plan.bridged_triangle_offsets[b],
                                plan.bridged_triangle_offsets[b + 1]);
      st.rotated_normal.x[slot] = n.x, st.rotated_normal.y[slot] = n.y;
      st.rotated_normal.z[slot] = n.z;
    }
  }

  // Where Output takes a slot's normal before normalisation: normal_sum (one thread: the
  // scatter's sums), rotated_normal (rotating), or the sum of its triangles' face_normal
  // (threads, after FaceNormals: the same terms in the same order as the scatter's, so the
  // same bits, summed here rather than in a pass of their own).
  enum class NormalSource { kSums, kRotated, kFaceNormals };

  // Slots [k kTaskSize, ...) into the output: positions, and the normals (NormalSource)
  // normalised (+Y where a sum vanishes), packs at a time (the stage's per-slot arrays are
  // padded to whole packs). With an output order, the unit normals go to the stage
  // (OrderedOutput copies them out).
  template <NormalSource kSource>
  void OutputTask(std::size_t k) const {
    S& st = *s;
    const bool direct = out.order == nullptr;
    const VertexStagePlan<Real>& plan = *st.plan;
    const std::size_t slots = plan.vertex_of_slot.size();
    const std::size_t begin = k * kTaskSize, end = std::min(slots, (k + 1) * kTaskSize);
    for (std::size_t i = begin; i < end && direct; ++i) {
      Real* p = out.positions + plan.vertex_of_slot[i] * out.position_stride;
      p[0] = st.position.x[i], p[1] = st.position.y[i], p[2] = st.position.z[i];
    }
    if (!out.normals) return;
    using P = Wide;
    using Value = typename P::Value;
    const Value zero = P::Broadcast(Real(0)), one = P::Broadcast(Real(1));
    alignas(16) Real unit[3][P::kWidth];
    for (std::size_t i = begin; i < end; i += P::kWidth) {
      simd::V3<Value> n;
      if constexpr (kSource == NormalSource::kRotated) {
        n = {P::Load(&st.rotated_normal.x[i]), P::Load(&st.rotated_normal.y[i]),
             P::Load(&st.rotated_normal.z[i])};
      } else if constexpr (kSource == NormalSource::kSums) {
        P::Load4(&st.normal_sum[4 * i], &n.x, &n.y, &n.z);
      } else {
        for (std::size_t l = 0; l < std::size_t(P::kWidth); ++l) {
          const simd::V3<Real> sum =
              i + l < end ? SumOfFaceNormals(plan.slot_triangles, plan.slot_triangle_offsets[i + l],
                                             plan.slot_triangle_offsets[i + l + 1])
                          : simd::V3<Real>{0, 0, 0};
          unit[0][l] = sum.x, unit[1][l] = sum.y, unit[2][l] = sum.z;
        }
        n = {P::Load(unit[0]), P::Load(unit[1]), P::Load(unit[2])};
      }
      const Value length = P::Sqrt(simd::Dot(n, n));
      const auto regular = P::Greater(length, zero);
      const Value inverse = one / P::Select(regular, length, one);
      const Value x = P::Select(regular, inverse * n.x, zero);
      const Value y = P::Select(regular, inverse * n.y, one);
      const Value z = P::Select(regular, inverse * n.z, zero);
      if (!direct) {
        P::Store(&st.unit_normal.x[i], x);
        P::Store(&st.unit_normal.y[i], y);
        P::Store(&st.unit_normal.z[i], z);
        continue;
      }
      P::Store(unit[0], x);
      P::Store(unit[1], y);
      P::Store(unit[2], z);
      for (std::size_t l = 0; l < std::size_t(P::kWidth) && i + l < end; ++l) {
        Real* o = out.normals + plan.vertex_of_slot[i + l] * out.normal_stride;
        o[0] = unit[0][l], o[1] = unit[1][l], o[2] = unit[2][l];
      }
    }
  }

  static void Output(const void* context, std::size_t k) {
    const auto& self = *static_cast<const StagePasses*>(context);
    if (self.Rotating())
      self.template OutputTask<NormalSource::kRotated>(k);
    else
      self.template OutputTask<NormalSource::kSums>(k);
  }

  // Threads, after FaceNormals: Output with each slot's normal summed from its triangles.
  static void GatherOutput(const void* context, std::size_t k) {
    static_cast<const StagePasses*>(context)->template OutputTask<NormalSource::kFaceNormals>(k);
  }

  // Output vertices [k kTaskSize, ...) of an output order: each a copy of its welded vertex.
  static void OrderedOutput(const void* context, std::size_t k) {
    const auto& self = *static_cast<const StagePasses*>(context);
    const S& st = *self.s;
    const StageOutput<Real>& out = self.out;
    const std::size_t end = std::min(out.order_size, (k + 1) * kTaskSize);
    for (std::size_t i = k * kTaskSize; i < end; ++i) {
      const std::uint32_t slot = st.plan->slot_of_vertex[out.order[i]];
      Real* p = out.positions + i * out.position_stride;
      p[0] = st.position.x[slot], p[1] = st.position.y[slot], p[2] = st.position.z[slot];
      if (!out.normals) continue;
      Real* n = out.normals + i * out.normal_stride;
      n[0] = st.unit_normal.x[slot], n[1] = st.unit_normal.y[slot], n[2] = st.unit_normal.z[slot];
    }
  }
};

template <class Real>
const BasicBridgeSamples<Real>* StageBridges(RigWorkspace& w, VertexStage<Real>& stage) {
  if constexpr (std::is_same_v<Real, double>) {
    (void)stage;
    return w.bridges.data();
  } else {
    for (std::uint32_t part : w.plan->layout.bridged_parts)
      stage.bridges[part] = w.bridges[part].template Cast<Real>();
    return stage.bridges.data();
  }
}

// RunVertexStage with packs of type Wide.
template <class Real, class Wide>
void RunStage(const RigModel& model, RigWorkspace& w, VertexStage<Real>& s,
              const StageOutput<Real>& output, const ParallelFor* parallel) {
  const RigEvaluationLayout& layout = w.plan->layout;
  const bool rotate = output.normals && output.normal_mode == NormalMode::kRotated;
  // The frame's wires, pair centres and cap frames, in Real.
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const std::size_t profiles = model.parts[i].profiles.size();
    for (std::size_t p = 0; p < profiles; ++p) {
      const std::size_t g = layout.profile_base[i] + p;
      std::size_t point = layout.point_base[g];
      for (const Vec3& q : w.profile_points[i][p]) {
        s.wire.x[point] = Real(q.x()), s.wire.y[point] = Real(q.y());
        s.wire.z[point] = Real(q.z());
        ++point;
      }
      const Vec3& origin = w.profile_origins[i][p];
      if (p + 1 < profiles) {
        const Vec3 centre = 0.5 * (origin + w.profile_origins[i][p + 1]);
        s.pair_centre.x[g] = Real(centre.x()), s.pair_centre.y[g] = Real(centre.y());
        s.pair_centre.z[g] = Real(centre.z());
      }
      s.cap_origin.x[g] = Real(origin.x()), s.cap_origin.y[g] = Real(origin.y());
      s.cap_origin.z[g] = Real(origin.z());
      s.cap_axes[g] = w.cap_axes[g].template cast<Real>();
      if (rotate) s.cap_normal_axes[g] = Cofactors(w.cap_axes[g]).template cast<Real>();
    }
  }
  for (std::size_t u = 0; u < layout.undo_samples.size(); ++u) {
    const auto [part, sample] = layout.undo_samples[u];
    s.undo[u] = w.spine_undo[part][sample].template cast<Real>();
    s.undo_rest_point[u] = model.parts[part].spine_points[sample].template cast<Real>();
    s.undo_point[u] = w.spine_points[part][sample].template cast<Real>();
  }
  const StagePasses<Real, Wide> passes{&model, &w, &s, StageBridges(w, s), output};
  using Passes = StagePasses<Real, Wide>;
  RunTasks(parallel, Tasks(s.plan->pair_count) + Tasks(s.plan->cap_profile.size()),
           &Passes::Vertices, &passes);
  if (!s.plan->bridged_slot.empty()) {
    RunTasks(parallel, Tasks(s.plan->bridged_slot.size()), &Passes::Undo, &passes);
    RunTasks(parallel, s.plan->bucket_task_starts.size() - 1, &Passes::Buckets, &passes);
    RunTasks(parallel, Tasks(s.plan->bridged_slot.size()), &Passes::Sums, &passes);
  }
  const bool one_thread = parallel == nullptr || parallel->concurrency() <= 1;
  void (*output_pass)(const void*, std::size_t) = &Passes::Output;
  if (rotate && one_thread) {
    // The rest normals turned with the vertices; the bridged vertices' from their triangles.
    passes.ScatterBridgedNormals();
  } else if (rotate) {
    RunTasks(parallel, Tasks(s.plan->bt0.size()), &Passes::BridgedFaceNormals, &passes);
    RunTasks(parallel, Tasks(s.plan->bridged_slot.size()), &Passes::BridgedNormals, &passes);
  } else if (output.normals) {
    if (one_thread) {
      passes.ScatterNormals();
    } else {
      RunTasks(parallel, Tasks(s.plan->t0.size()), &Passes::FaceNormals, &passes);
      output_pass = &Passes::GatherOutput;
    }
  }
  RunTasks(parallel, Tasks(s.plan->vertex_of_slot.size()), output_pass, &passes);
  if (output.order) RunTasks(parallel, Tasks(output.order_size), &Passes::OrderedOutput, &passes);
}

}  // namespace
}  // namespace wirerig
