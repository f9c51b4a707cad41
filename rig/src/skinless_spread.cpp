#include "skinless_spread.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <limits>
#include <queue>
#include <vector>

#include "joint_skin_spread.h"

namespace wirerig {
namespace {

// One skinless part c; see the header.
LostInfluences SpreadSkinlessJoint(const Adjacency& adjacency,
                                   std::span<const std::uint32_t> own_samples, std::size_t c,
                                   RigModel* model) {
  const std::size_t n = model->vertices.size();
  std::vector<bool> below(model->parts.size(), false);  // c and its descendants
  below[c] = true;
  for (std::size_t p = c + 1; p < model->parts.size(); ++p)
    below[p] = model->parts[p].parent >= 0 && below[std::size_t(model->parts[p].parent)];
  // Carried: the skin of parts below c (the bone's children move it by their own motion).
  std::vector<bool> carried(n, false);
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  std::vector<double> distance(n, std::numeric_limits<double>::infinity());
  for (std::uint32_t v = 0; v < n; ++v) {
    if (!below[model->vertices[v].part]) continue;
    carried[v] = true;
    distance[v] = 0.0;
    queue.push({0.0, v});
  }
  // Free: the other skin within reach of the carried skin along the surface.
  const double reach = kSkinlessSpreadLengths * model->parts[c].spine_length;
  std::vector<std::uint32_t> free;
  std::vector<std::int32_t> index(n, -1);
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v]) continue;
    if (!carried[v]) {
      index[v] = std::int32_t(free.size());
      free.push_back(v);
    }
    for (const Neighbour& nb : adjacency[v]) {
      const double next = d + nb.length;
      if (next >= reach || next >= distance[nb.vertex] || carried[nb.vertex]) continue;
      distance[nb.vertex] = next;
      queue.push({next, nb.vertex});
    }
  }
  // Harmonic u over the free skin: 1 on carried neighbours, 0 beyond the reach.
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(Eigen::Index(free.size()));
  for (std::size_t i = 0; i < free.size(); ++i) {
    double diagonal = 0.0;
    for (const Neighbour& nb : adjacency[free[i]]) {
      diagonal += nb.weight;
      if (index[nb.vertex] >= 0)
        entries.emplace_back(Eigen::Index(i), index[nb.vertex], -nb.weight);
      else if (carried[nb.vertex])
        rhs[Eigen::Index(i)] += nb.weight;
    }
    entries.emplace_back(Eigen::Index(i), Eigen::Index(i), diagonal);
  }
  Eigen::VectorXd u;
  if (!free.empty()) {
    Eigen::SparseMatrix<double> matrix(Eigen::Index(free.size()), Eigen::Index(free.size()));
    matrix.setFromTriplets(entries.begin(), entries.end());
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(matrix);
    if (solver.info() == Eigen::Success) u = solver.solve(rhs);
  }
  LostInfluences lost;
  for (std::size_t i = 0; i < free.size() && u.size() == Eigen::Index(free.size()); ++i) {
    const double value = std::min(u[Eigen::Index(i)], 1.0);
    // Below kSkinlessLeastBlend of the bone's motion the vertex keeps its own side's: no slot.
    if (!(value * value * (3.0 - 2.0 * value) >= kSkinlessLeastBlend)) continue;
    const JointInfluence influence{int(c), own_samples[free[i]], value, 1.0, 0.0, 1.0};
    lost += AddJointInfluence(*model, influence, &model->vertices[free[i]]);
  }
  return lost;
}

}  // namespace

LostInfluences SpreadSkinlessJoints(const Adjacency& adjacency,
                                    std::span<const std::uint32_t> own_samples, RigModel* model) {
  LostInfluences lost;
  for (std::size_t c = 1; c < model->parts.size(); ++c)
    if (IsSkinless(model->parts[c]) && model->parts[c].joint.blend_length > 0.0)
      lost += SpreadSkinlessJoint(adjacency, own_samples, c, model);
  return lost;
}

}  // namespace wirerig
