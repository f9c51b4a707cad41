#include "joint_skin_spread.h"

#include "mesh_adjacency.h"
#include "skinless_spread.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <limits>
#include <queue>
#include <vector>

namespace wirerig {
namespace {

// in_subtree[p]: part p is `root` or one of its descendants (parents precede children).
std::vector<bool> Subtree(const RigModel& model, std::size_t root) {
  std::vector<bool> out(model.parts.size(), false);
  out[root] = true;
  for (std::size_t p = root + 1; p < model.parts.size(); ++p)
    if (model.parts[p].parent >= 0 && out[std::size_t(model.parts[p].parent)]) out[p] = true;
  return out;
}

// ancestor[p]: part p is `part` or one of its ancestors.
std::vector<bool> AncestorsOf(const RigModel& model, int part) {
  std::vector<bool> out(model.parts.size(), false);
  for (int p = part; p >= 0; p = model.parts[std::size_t(p)].parent) out[std::size_t(p)] = true;
  return out;
}

JointInfluence* InfluenceOf(VertexAttachment& a, int joint) {
  for (JointInfluence& j : a.joints)
    if (j.joint == joint) return &j;
  return nullptr;
}

constexpr double kFixedBridge = 1.0 - 1e-9;

// Whether `a` holds an influence of a sibling of `joint` (a joint of the same parent).
bool OnSiblingJoint(const RigModel& model, const VertexAttachment& a, int joint) {
  const int parent = SkinParent(model, std::size_t(joint));
  for (const JointInfluence& other : a.joints)
    if (other.joint >= 0 && other.joint != joint &&
        !IsSkinless(model.parts[std::size_t(other.joint)]) &&
        SkinParent(model, std::size_t(other.joint)) == parent)
      return true;
  return false;
}

// Whether the vertex's u on `joint` is its own: it rides on the bridge as a cross-section
// (bridge 1) and lies on no sibling joint's bridge or spread (skin between two legs is no
// section of either). `reached`: the vertex as every joint's spread left it (the first pass of
// SpreadJointBindings), or null.
bool Fixed(const RigModel& model, const VertexAttachment& a, const JointInfluence& j,
           const VertexAttachment* reached) {
  if (j.bridge < kFixedBridge) return false;
  if (OnSiblingJoint(model, a, j.joint)) return false;
  return reached == nullptr || !OnSiblingJoint(model, *reached, j.joint);
}

// Per-vertex buffers shared by the joints (reset where a joint touched them).
struct Scratch {
  std::vector<double> distance;     // along the surface from the joint's blended skin
  std::vector<std::int32_t> index;  // in the free set, or -1
};

// One joint: see the header. `bound`: the vertices bound to it when the spread began (some may
// have lost it to a stronger joint since); `reached`: per vertex, as the first pass left it
// (empty in the first pass). Returns the joint influences lost for want of a slot.
LostInfluences SpreadJoint(const Adjacency& adjacency, std::span<const std::uint32_t> own_samples,
                           std::size_t c, std::span<const std::uint32_t> bound,
                           std::span<const VertexAttachment> reached, Scratch& scratch,
                           RigModel* model) {
  auto fixed_at = [&](std::uint32_t v, const JointInfluence& j) {
    return Fixed(*model, model->vertices[v], j, reached.empty() ? nullptr : &reached[v]);
  };
  const PartModel& child = model->parts[c];
  const std::vector<bool> child_side = Subtree(*model, c);
  const std::vector<bool> parent_side = AncestorsOf(*model, child.parent);
  const int joint = int(c);
  std::vector<double>& distance = scratch.distance;
  std::vector<std::int32_t>& index = scratch.index;

  // Free vertices: blended by the bridge, then the parent side's skin within reach of them, and
  // the skin of parts below the child within reach of any bound vertex (fixed ones too: an
  // arm's skin beside the chest's bridge).
  std::vector<std::uint32_t> free, fixed_seeds;
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  bool any_free = false;
  for (std::uint32_t v : bound) {
    const JointInfluence* j = InfluenceOf(model->vertices[v], joint);
    if (j == nullptr) continue;
    distance[v] = 0.0;
    queue.push({0.0, v});
    if (fixed_at(v, *j))
      fixed_seeds.push_back(v);
    else
      any_free = true;
  }
  auto reset_seeds = [&] {
    for (std::uint32_t v : fixed_seeds) distance[v] = std::numeric_limits<double>::infinity();
  };
  const bool parts_below = std::count(child_side.begin(), child_side.end(), true) > 1;
  if (!any_free && !parts_below) {
    reset_seeds();
    return {};
  }
  // A joint hung from skinless bones (a shoulder from its clavicle) meets its skin parent's
  // skin across their length: its spread reaches that much further.
  double skinless_length = 0.0;
  for (int p = child.parent; p >= 0 && IsSkinless(model->parts[std::size_t(p)]);
       p = model->parts[std::size_t(p)].parent)
    skinless_length += model->parts[std::size_t(p)].spine_length;
  const double reach = kSpreadRadii * child.joint.radius + kSkinlessSpreadShare * skinless_length;
  const double sibling_reach = kSiblingSpreadRadii * child.joint.radius;
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v]) continue;
    const JointInfluence* own = InfluenceOf(model->vertices[v], joint);
    const bool fixed = own != nullptr && fixed_at(v, *own);
    if (!fixed && index[v] < 0) {
      index[v] = std::int32_t(free.size());
      free.push_back(v);
    }
    for (const Neighbour& nb : adjacency[v]) {
      const double next = d + nb.length;
      if (next > reach || next >= distance[nb.vertex]) continue;
      const VertexAttachment& a = model->vertices[nb.vertex];
      const JointInfluence* j = InfluenceOf(model->vertices[nb.vertex], joint);
      const bool sibling = SkinParent(*model, a.part) == SkinParent(*model, c) && a.part != c;
      const bool below_child = child_side[a.part] && a.part != c;
      if (fixed && !(below_child && j == nullptr)) continue;  // a fixed seed: only those
      if (j == nullptr && !parent_side[a.part] && !(below_child && next <= sibling_reach) &&
          !(sibling && next <= sibling_reach))
        continue;  // the child's skin, or another limb's beyond its reach
      if (j != nullptr && fixed_at(nb.vertex, *j)) continue;
      distance[nb.vertex] = next;
      queue.push({next, nb.vertex});
    }
  }

  if (free.empty()) {
    reset_seeds();
    return {};
  }
  // The value a vertex outside the free set holds: its bridge coordinate on the joint, else
  // 0 on the parent's side and 1 on the child's.
  // The fields solved for: u, JointInfluence::bridge and JointInfluence::section.
  using Fields = Eigen::RowVector3d;
  auto fixed_value = [&](std::uint32_t v) -> Fields {
    const JointInfluence* j = InfluenceOf(model->vertices[v], joint);
    if (j != nullptr) return {j->u, j->bridge, j->section};
    return {child_side[model->vertices[v].part] ? 1.0 : 0.0, 0.0, 0.0};
  };
  // Harmonic u over the free vertices; a tiny pull to the bound value keeps every block
  // definite (a free patch with no fixed neighbour keeps its values).
  constexpr double kPull = 1e-6;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(Eigen::Index(free.size()), 3);
  for (std::size_t i = 0; i < free.size(); ++i) {
    const std::uint32_t v = free[i];
    const JointInfluence* j = InfluenceOf(model->vertices[v], joint);
    double diagonal = 0.0;
    for (const Neighbour& nb : adjacency[v]) {
      diagonal += nb.weight;
      if (index[nb.vertex] >= 0)
        entries.emplace_back(Eigen::Index(i), index[nb.vertex], -nb.weight);
      else
        rhs.row(Eigen::Index(i)) += nb.weight * fixed_value(nb.vertex);
    }
    const double pull = kPull * std::max(diagonal, 1.0);
    entries.emplace_back(Eigen::Index(i), Eigen::Index(i), diagonal + pull);
    if (j != nullptr) rhs.row(Eigen::Index(i)) += pull * Fields(j->u, j->bridge, j->section);
  }
  Eigen::SparseMatrix<double> matrix(Eigen::Index(free.size()), Eigen::Index(free.size()));
  matrix.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(matrix);
  const Eigen::MatrixX3d solved =
      solver.info() == Eigen::Success ? Eigen::MatrixX3d(solver.solve(rhs)) : Eigen::MatrixX3d();
  for (std::uint32_t v : free) {
    distance[v] = std::numeric_limits<double>::infinity();
    index[v] = -1;
  }
  reset_seeds();
  if (solver.info() != Eigen::Success) return {};  // keep the per-vertex binding

  LostInfluences lost;
  for (std::size_t i = 0; i < free.size(); ++i) {
    VertexAttachment& a = model->vertices[free[i]];
    const double value = std::clamp(solved(Eigen::Index(i), 0), 0.0, 1.0);
    const double bridge = std::clamp(solved(Eigen::Index(i), 1), 0.0, 1.0);
    const double section = std::clamp(solved(Eigen::Index(i), 2), 0.0, 1.0);
    if (JointInfluence* j = InfluenceOf(a, joint)) {
      j->u = value;
      j->bridge = bridge;
      j->section = section;
      continue;
    }
    if (!(value > 0.0)) continue;
    const JointInfluence spread{joint, own_samples[free[i]], value, 1.0, bridge, section};
    lost += AddJointInfluence(*model, spread, &a);
  }
  return lost;
}

}  // namespace

LostInfluences AddJointInfluence(const RigModel& model, const JointInfluence& influence,
                                 VertexAttachment* a) {
  auto strength = [&](const JointInfluence& j) {
    if (j.joint < 0) return -1.0;
    const bool child_side =
        j.joint == int(a->part) || IsBelowPart(model, a->part, std::size_t(j.joint));
    return j.weight * (child_side ? 1.0 - j.u : j.u);
  };
  JointInfluence* weakest = &a->joints[0];
  for (JointInfluence& j : a->joints)
    if (strength(j) < strength(*weakest)) weakest = &j;
  if (weakest->joint >= 0 && strength(*weakest) >= strength(influence))
    return {1, strength(influence)};
  const LostInfluences lost =
      weakest->joint >= 0 ? LostInfluences{1, strength(*weakest)} : LostInfluences{};
  *weakest = influence;
  return lost;
}

LostInfluences SpreadJointBindings(std::span<const Vec3> rest,
                                   std::span<const std::uint32_t> own_samples, RigModel* model) {
  const Adjacency adjacency = MakeAdjacency(rest, model->triangles);
  std::vector<std::vector<std::uint32_t>> bound(model->parts.size());
  for (std::uint32_t v = 0; v < model->vertices.size(); ++v)
    for (const JointInfluence& j : model->vertices[v].joints)
      if (j.joint >= 0) bound[std::size_t(j.joint)].push_back(v);
  Scratch scratch{std::vector<double>(rest.size(), std::numeric_limits<double>::infinity()),
                  std::vector<std::int32_t>(rest.size(), -1)};
  // Two passes, so that a joint spread early knows, as one spread late does, which siblings'
  // spreads reach each vertex: the first spreads every joint to learn that (in one pass a leg
  // spread first kept as its own cross-sections the skin between the legs that the other
  // leg's spread reaches, and the mirror-image hips differed: 15 folded edges against 3); the
  // second spreads every joint again from the per-vertex binding, knowing it.
  const std::vector<VertexAttachment> binding = model->vertices;
  auto spread_all = [&](std::span<const VertexAttachment> reached) {
    LostInfluences lost;
    for (std::size_t c = 1; c < model->parts.size(); ++c)
      if (model->parts[c].parent >= 0 && model->parts[c].joint.blend_length > 0.0 &&
          !IsSkinless(model->parts[c]))
        lost += SpreadJoint(adjacency, own_samples, c, bound[c], reached, scratch, model);
    return lost;
  };
  spread_all({});
  const std::vector<VertexAttachment> reached = std::move(model->vertices);
  model->vertices = binding;
  LostInfluences lost = spread_all(reached);
  lost += SpreadSkinlessJoints(adjacency, own_samples, model);
  return lost;
}

}  // namespace wirerig
