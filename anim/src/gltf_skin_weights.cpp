#include "gltf_skin_weights.h"

#include <algorithm>
#include <cstdint>
#include <utility>

#include <Eigen/Cholesky>

namespace wirerig::gltf {
namespace {

// Lawson-Hanson non-negative least squares on the normal equations: the w >= 0 minimising
// w^T G w - 2 g^T w (G symmetric positive definite).
Eigen::VectorXd NonNegative(const Eigen::MatrixXd& gram, const Eigen::VectorXd& g) {
  const Eigen::Index n = g.size();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
  std::vector<bool> passive(static_cast<std::size_t>(n), false);
  const double tolerance = 1e-12 * std::max(1.0, g.cwiseAbs().maxCoeff());
  for (Eigen::Index round = 0; round < 3 * n; ++round) {
    const Eigen::VectorXd descent = g - gram * w;
    Eigen::Index best = -1;
    for (Eigen::Index i = 0; i < n; ++i)
      if (!passive[std::size_t(i)] && descent(i) > tolerance &&
          (best < 0 || descent(i) > descent(best)))
        best = i;
    if (best < 0) break;
    passive[std::size_t(best)] = true;
    for (Eigen::Index inner = 0; inner < 3 * n; ++inner) {
      std::vector<Eigen::Index> set;
      for (Eigen::Index i = 0; i < n; ++i)
        if (passive[std::size_t(i)]) set.push_back(i);
      const auto m = static_cast<Eigen::Index>(set.size());
      Eigen::MatrixXd sub(m, m);
      Eigen::VectorXd rhs(m);
      for (Eigen::Index a = 0; a < m; ++a) {
        rhs(a) = g(set[std::size_t(a)]);
        for (Eigen::Index b = 0; b < m; ++b)
          sub(a, b) = gram(set[std::size_t(a)], set[std::size_t(b)]);
      }
      const Eigen::VectorXd solved = sub.ldlt().solve(rhs);
      Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
      for (Eigen::Index a = 0; a < m; ++a) z(set[std::size_t(a)]) = solved(a);
      bool feasible = true;
      double step = 1.0;
      for (Eigen::Index i : set) {
        if (z(i) > 0.0) continue;
        feasible = false;
        step = std::min(step, w(i) / std::max(w(i) - z(i), 1e-300));
      }
      if (feasible) {
        w = z;
        break;
      }
      w += step * (z - w);
      for (Eigen::Index i : set)
        if (w(i) <= 1e-15) passive[std::size_t(i)] = false, w(i) = 0.0;
    }
  }
  return w;
}

struct WeightProblem {
  const SkinInfluences* start;
  const std::vector<int>* parent;
  const BaseVertices* base;
  const BakedAnimation* bake;
  std::span<const Mat3> rotation;
  std::span<const Vec3> translation;
  std::vector<std::vector<std::uint32_t>> children;                    // #J
  std::vector<std::vector<std::pair<std::uint32_t, double>>>* solved;  // #V (joint, weight)

  static constexpr std::size_t kTaskSize = 256;  // vertices per task

  // Vertex v's weights: see the header.
  void Solve(std::size_t v) const {
    const std::size_t joints = parent->size(), keys = bake->KeyCount(), vertices = base->Count();
    const std::size_t slots = start->slots;
    const auto kept_count = static_cast<Eigen::Index>(slots);
    std::vector<std::uint32_t> candidates;
    auto add = [&candidates](std::uint32_t j) {
      if (std::find(candidates.begin(), candidates.end(), j) == candidates.end())
        candidates.push_back(j);
    };
    for (std::size_t c = 0; c < slots; ++c) {
      if (start->weights[v * slots + c] <= 0.0f) continue;
      const std::uint32_t j = start->joints[v * slots + c];
      add(j);
      if ((*parent)[j] >= 0) {
        add(std::uint32_t((*parent)[j]));
        for (std::uint32_t sibling : children[std::size_t((*parent)[j])]) add(sibling);
      }
      for (std::uint32_t child : children[j]) add(child);
    }
    const auto n = static_cast<Eigen::Index>(candidates.size());
    Eigen::VectorXd start_weights = Eigen::VectorXd::Zero(n);
    for (std::size_t c = 0; c < slots; ++c) {
      if (start->weights[v * slots + c] <= 0.0f) continue;  // unused slots name joint 0
      const auto at = std::find(candidates.begin(), candidates.end(), start->joints[v * slots + c]);
      start_weights(at - candidates.begin()) += start->weights[v * slots + c];
    }
    // Normal equations of sum over keys |sum_j w_j (R_jk r + t_jk) - p_k|^2.
    const Vec3 r = Eigen::Map<const Eigen::Vector3f>(&base->positions[v * 3]).cast<double>();
    Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
    Eigen::Matrix<double, 3, Eigen::Dynamic> moved(3, n);
    for (std::size_t k = 0; k < keys; ++k) {
      for (Eigen::Index a = 0; a < n; ++a) {
        const std::size_t j = k * joints + candidates[std::size_t(a)];
        moved.col(a) = rotation[j] * r + translation[j];
      }
      gram.noalias() += moved.transpose() * moved;
      g.noalias() += moved.transpose() * bake->positions[k * vertices + v].cast<double>();
    }
    // Sum held to 1 by a stiff penalty; a faint pull to the start where keys cannot decide.
    const double scale = gram.trace() / double(n) + 1e-30;
    const double stiff = 1e3 * scale, faint = 1e-7 * scale;
    gram.array() += stiff;
    g.array() += stiff;
    gram.diagonal().array() += faint;
    g += faint * start_weights;
    Eigen::VectorXd w = NonNegative(gram, g);
    if ((w.array() > 0.0).count() > kept_count) {  // the largest, solved again on their own
      std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
      for (Eigen::Index a = 0; a < n; ++a) order[std::size_t(a)] = a;
      std::partial_sort(order.begin(), order.begin() + kept_count, order.end(),
                        [&w](Eigen::Index a, Eigen::Index b) { return w(a) > w(b); });
      order.resize(slots);
      Eigen::MatrixXd sub(kept_count, kept_count);
      Eigen::VectorXd rhs(kept_count);
      for (Eigen::Index a = 0; a < kept_count; ++a) {
        rhs(a) = g(order[std::size_t(a)]);
        for (Eigen::Index b = 0; b < kept_count; ++b)
          sub(a, b) = gram(order[std::size_t(a)], order[std::size_t(b)]);
      }
      const Eigen::VectorXd kept = NonNegative(sub, rhs);
      w.setZero();
      for (Eigen::Index a = 0; a < kept_count; ++a) w(order[std::size_t(a)]) = kept(a);
    }
    std::vector<std::pair<std::uint32_t, double>>& pairs = (*solved)[v];
    pairs.clear();
    for (Eigen::Index a = 0; a < n; ++a)
      if (w(a) > 0.0) pairs.emplace_back(candidates[std::size_t(a)], w(a));
    if (pairs.empty()) {  // cannot happen with the penalty; keep the start if it does
      for (Eigen::Index a = 0; a < n; ++a)
        if (start_weights(a) > 0.0)
          pairs.emplace_back(candidates[std::size_t(a)], start_weights(a));
    }
  }

  static void Task(const void* context, std::size_t task) {
    const auto& self = *static_cast<const WeightProblem*>(context);
    const std::size_t end = std::min(self.base->Count(), (task + 1) * kTaskSize);
    for (std::size_t v = task * kTaskSize; v < end; ++v) self.Solve(v);
  }
};

}  // namespace

SkinInfluences FitWeights(const SkinInfluences& start, const std::vector<int>& parent,
                          const BaseVertices& base, const BakedAnimation& bake,
                          std::span<const Mat3> rotation, std::span<const Vec3> translation,
                          const ParallelFor* parallel) {
  const std::size_t joints = parent.size(), vertices = base.Count();
  std::vector<std::vector<std::pair<std::uint32_t, double>>> solved(vertices);
  WeightProblem problem{&start,
                        &parent,
                        &base,
                        &bake,
                        rotation,
                        translation,
                        std::vector<std::vector<std::uint32_t>>(joints),
                        &solved};
  for (std::size_t j = 0; j < joints; ++j)
    if (parent[j] >= 0) problem.children[std::size_t(parent[j])].push_back(std::uint32_t(j));
  RunTasks(parallel, (vertices + WeightProblem::kTaskSize - 1) / WeightProblem::kTaskSize,
           &WeightProblem::Task, &problem);
  SkinInfluences fitted;
  fitted.slots = start.slots;
  fitted.byte_weights = start.byte_weights;
  for (auto& pairs : solved) AppendInfluences(std::move(pairs), &fitted);
  return fitted;
}

Vec3 SkinnedByTransforms(const SkinInfluences& influences, std::size_t v, const Vec3& r,
                         std::span<const Mat3> rotation, std::span<const Vec3> translation) {
  const std::size_t slots = influences.slots;
  Vec3 skinned = Vec3::Zero();
  for (std::size_t c = 0; c < slots; ++c) {
    const double w = influences.weights[v * slots + c];
    if (w == 0.0) continue;
    const std::size_t j = influences.joints[v * slots + c];
    skinned += w * (rotation[j] * r + translation[j]);
  }
  return skinned;
}

double SquaredSkinError(const SkinInfluences& influences, const BaseVertices& base,
                        const BakedAnimation& bake, std::span<const Mat3> rotation,
                        std::span<const Vec3> translation) {
  const std::size_t keys = bake.KeyCount(), vertices = base.Count();
  const std::size_t joints = keys == 0 ? 0 : rotation.size() / keys;
  double sum = 0.0;
  for (std::size_t k = 0; k < keys; ++k) {
    for (std::size_t v = 0; v < vertices; ++v) {
      const Vec3 r = Eigen::Map<const Eigen::Vector3f>(&base.positions[v * 3]).cast<double>();
      const Vec3 skinned =
          SkinnedByTransforms(influences, v, r, rotation.subspan(k * joints, joints),
                              translation.subspan(k * joints, joints));
      sum += (bake.positions[k * vertices + v].cast<double>() - skinned).squaredNorm();
    }
  }
  return sum;
}

}  // namespace wirerig::gltf
