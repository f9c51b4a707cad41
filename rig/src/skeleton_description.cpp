#include "wirerig/rig/skeleton_description.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace wirerig {
namespace {

// A bone shorter than this fraction of the mesh's diagonal has no length.
constexpr double kMinBoneFraction = 1e-3;
// A bind axis within 45 degrees of the bone runs along it and is no bend axis.
constexpr double kAlongBoneCos = 0.7071;

Vec3 JointPosition(const Joint& joint) { return joint.bind_global.block<3, 1>(0, 3); }
Mat3 JointRotation(const Joint& joint) { return joint.bind_global.topLeftCorner<3, 3>(); }

double DistanceToPolyline(const std::vector<Vec3>& curve, const Vec3& p) {
  double best = (p - curve.front()).norm();
  for (std::size_t k = 0; k + 1 < curve.size(); ++k) {
    const Vec3 a = curve[k], ab = curve[k + 1] - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (a + t * ab)).norm());
  }
  return best;
}

class SkeletonDescriber {
 public:
  explicit SkeletonDescriber(const Mesh& mesh) : mesh_(mesh), joint_count_(mesh.joints.size()) {}

  Result<RigDescription> Describe() {
    if (joint_count_ == 0) return Error{"the mesh has no skeleton"};
    if (mesh_.skin_joints.size() != mesh_.positions.size() ||
        mesh_.skin_weights.size() != mesh_.positions.size())
      return Error{"the mesh's skeleton has no skin weights"};
    for (std::size_t j = 0; j < joint_count_; ++j) {
      const int parent = mesh_.joints[j].parent;
      if (parent >= int(j) || parent < -1)
        return Error{"joint " + std::to_string(j) + " ('" + mesh_.joints[j].name +
                     "'): its parent must come before it"};
      if (!mesh_.joints[j].bind_global.allFinite())
        return Error{"joint " + std::to_string(j) + " ('" + mesh_.joints[j].name +
                     "'): its bind transform is not finite"};
    }
    Prepare();
    DecideBones();
    return Assemble();
  }

 private:
  // Welded vertices (render vertices when the mesh is not welded), each with its joint of
  // largest weight; joints' children, positions, own vertices and subtree sizes.
  void Prepare() {
    const bool welded = !mesh_.welded_positions.empty();
    points_ = welded ? &mesh_.welded_positions : &mesh_.positions;
    dominant_.assign(points_->size(), -1);
    std::vector<bool> set(points_->size(), false);
    for (std::size_t v = 0; v < mesh_.positions.size(); ++v) {
      const std::size_t w = welded && v < mesh_.weld_map.size() ? mesh_.weld_map[v] : v;
      if (w >= points_->size() || set[w]) continue;
      set[w] = true;
      double best_weight = 0.0;
      for (int k = 0; k < 4; ++k) {
        const int joint = mesh_.skin_joints[v][k];
        if (joint >= 0 && joint < int(joint_count_) && mesh_.skin_weights[v][k] > best_weight) {
          dominant_[w] = joint;
          best_weight = mesh_.skin_weights[v][k];
        }
      }
    }
    children_.assign(joint_count_, {});
    position_.resize(joint_count_);
    own_vertices_.assign(joint_count_, {});
    for (std::size_t j = 0; j < joint_count_; ++j) {
      position_[j] = JointPosition(mesh_.joints[j]);
      if (mesh_.joints[j].parent >= 0) children_[mesh_.joints[j].parent].push_back(int(j));
    }
    for (std::size_t w = 0; w < dominant_.size(); ++w)
      if (dominant_[w] >= 0) own_vertices_[dominant_[w]].push_back(std::uint32_t(w));
    // Subtree sizes, children before parents (parents come first).
    subtree_joints_.assign(joint_count_, 1);
    subtree_vertices_.assign(joint_count_, 0);
    for (std::size_t j = joint_count_; j-- > 0;) {
      subtree_vertices_[j] += own_vertices_[j].size();
      if (const int parent = mesh_.joints[j].parent; parent >= 0) {
        subtree_joints_[parent] += subtree_joints_[j];
        subtree_vertices_[parent] += subtree_vertices_[j];
      }
    }
    Bounds bounds;
    if (!points_->empty()) {
      bounds.min = bounds.max = points_->front();
      for (const Vec3& p : *points_) {
        bounds.min = bounds.min.cwiseMin(p);
        bounds.max = bounds.max.cwiseMax(p);
      }
    }
    for (const Vec3& p : position_) {
      if (points_->empty()) bounds.min = bounds.max = p;
      bounds.min = bounds.min.cwiseMin(p);
      bounds.max = bounds.max.cwiseMax(p);
    }
    min_length_ = std::max(kMinBoneFraction * bounds.Diagonal(), 1e-9);
    bone_axis_ = LearnBoneAxis();
  }

  // The local axis (+-X, +-Y or +-Z of the bind rotation) along which the file's bones point:
  // the one nearest the mean direction of every child from its parent, in the parent's frame.
  std::optional<Vec3> LearnBoneAxis() const {
    Vec3 sum = Vec3::Zero();
    int count = 0;
    for (std::size_t j = 0; j < joint_count_; ++j) {
      const int parent = mesh_.joints[j].parent;
      if (parent < 0) continue;
      const Vec3 offset = position_[j] - position_[parent];
      if (offset.norm() < min_length_) continue;
      sum += JointRotation(mesh_.joints[parent]).transpose() * offset.normalized();
      ++count;
    }
    if (count == 0 || sum.norm() < 0.3 * count) return std::nullopt;  // no agreement
    Eigen::Index axis = 0;
    sum.cwiseAbs().maxCoeff(&axis);
    Vec3 local = Vec3::Zero();
    local[axis] = sum[axis] > 0.0 ? 1.0 : -1.0;
    return local;
  }

  // Direction of the bone coming into joint j (from its nearest ancestor at another place).
  std::optional<Vec3> Incoming(int j) const {
    for (int a = mesh_.joints[j].parent; a >= 0; a = mesh_.joints[a].parent) {
      const Vec3 offset = position_[j] - position_[a];
      if (offset.norm() >= min_length_) return offset.normalized();
    }
    return std::nullopt;
  }

  // Where child c leads from joint j: c, or when c sits on j, its first descendant elsewhere.
  Vec3 Reach(int j, int c) const {
    int d = c;
    while ((position_[d] - position_[j]).norm() < min_length_ && !children_[d].empty())
      d = children_[d].front();
    return position_[d] - position_[j];
  }

  // The child continuing j's chain (-1 for a leaf).
  int ChainChild(int j) const {
    const std::vector<int>& kids = children_[j];
    if (kids.empty()) return -1;
    const std::optional<Vec3> incoming = Incoming(j);
    int best = kids.front();
    auto larger = [&](int a, int b) {  // subtree a larger than subtree b
      if (subtree_joints_[a] != subtree_joints_[b]) return subtree_joints_[a] > subtree_joints_[b];
      return subtree_vertices_[a] > subtree_vertices_[b];
    };
    auto alignment = [&](int c) {
      const Vec3 reach = Reach(j, c);
      return reach.norm() < min_length_ ? -2.0 : reach.normalized().dot(*incoming);
    };
    for (std::size_t k = 1; k < kids.size(); ++k) {
      const int c = kids[k];
      if (incoming) {
        const double a = alignment(c), b = alignment(best);
        if (a > b + 1e-9 || (std::abs(a - b) <= 1e-9 && larger(c, best))) best = c;
      } else if (larger(c, best)) {
        best = c;
      }
    }
    return best;
  }

  // The axis a leaf bone runs along: the bone coming into it, else its bind orientation's bone
  // axis, else the bind axis nearest the direction to its vertices.
  Vec3 LeafDirection(int j) const {
    if (const std::optional<Vec3> incoming = Incoming(j)) return *incoming;
    const Mat3 rotation = JointRotation(mesh_.joints[j]);
    if (bone_axis_) return (rotation * *bone_axis_).normalized();
    Vec3 centroid = Vec3::Zero();
    for (std::uint32_t w : own_vertices_[j]) centroid += (*points_)[w];
    if (!own_vertices_[j].empty()) centroid /= double(own_vertices_[j].size());
    const Vec3 toward = centroid - position_[j];
    if (own_vertices_[j].empty() || toward.norm() < min_length_)
      return rotation.col(0).normalized();
    Eigen::Index axis = 0;
    const Vec3 local = rotation.transpose() * toward;
    local.cwiseAbs().maxCoeff(&axis);
    return (local[axis] > 0.0 ? 1.0 : -1.0) * rotation.col(axis).normalized();
  }

  // Appends p unless it lies within the minimum bone length of the curve's last point.
  void AppendPoint(std::vector<Vec3>& curve, const Vec3& p) const {
    if (curve.empty() || (p - curve.back()).norm() >= min_length_) curve.push_back(p);
  }

  // Children before parents: each bone's curve (run on through merged chain children), whether
  // it is kept as a part, and its vertex count with its merged children's.
  void DecideBones() {
    kept_.assign(joint_count_, false);
    curves_.assign(joint_count_, {});
    std::vector<std::size_t> vertices(joint_count_, 0);
    for (std::size_t j = 0; j < joint_count_; ++j) vertices[j] = own_vertices_[j].size();
    for (std::size_t jj = joint_count_; jj-- > 0;) {
      const int j = int(jj);
      std::vector<Vec3>& curve = curves_[j];
      curve.push_back(position_[j]);
      if (const int chain = ChainChild(j); chain >= 0) {
        if (kept_[chain])
          AppendPoint(curve, position_[chain]);
        else
          for (const Vec3& p : curves_[chain]) AppendPoint(curve, p);
      } else if (!own_vertices_[j].empty()) {
        const Vec3 direction = LeafDirection(j);
        double reach = 0.0;
        for (std::uint32_t w : own_vertices_[j])
          reach = std::max(reach, ((*points_)[w] - position_[j]).dot(direction));
        AppendPoint(curve, position_[j] + reach * direction);
      }
      kept_[j] = vertices[j] > 0 && curve.size() >= 2;
      const int parent = mesh_.joints[j].parent;
      if (!kept_[j] && parent >= 0) vertices[parent] += vertices[j];
    }
  }

  Result<RigDescription> Assemble() {
    // owner[j]: the kept joint whose part takes joint j's vertices (-1: none).
    std::vector<int> owner(joint_count_, -1);
    for (std::size_t j = 0; j < joint_count_; ++j) {
      const int parent = mesh_.joints[j].parent;
      owner[j] = kept_[j] ? int(j) : parent >= 0 ? owner[parent] : -1;
    }
    // Trees of kept parts: each kept part's tree root and each tree's vertex count.
    std::vector<int> tree(joint_count_, -1);
    std::vector<std::size_t> tree_vertices(joint_count_, 0);
    std::vector<int> roots;
    for (std::size_t j = 0; j < joint_count_; ++j) {
      if (!kept_[j]) continue;
      const int parent = mesh_.joints[j].parent;
      const int parent_part = parent >= 0 ? owner[parent] : -1;
      tree[j] = parent_part >= 0 ? tree[parent_part] : int(j);
      if (parent_part < 0) roots.push_back(int(j));
    }
    if (roots.empty())
      return Error{"the skeleton has no bone with both a length and skinned vertices"};
    for (int w : dominant_)
      if (w >= 0 && owner[w] >= 0) ++tree_vertices[tree[owner[w]]];
    std::stable_sort(roots.begin(), roots.end(),
                     [&](int a, int b) { return tree_vertices[a] > tree_vertices[b]; });

    // Parts, tree by tree (largest first), parents before children within each tree.
    RigDescription description;
    std::vector<int> part_of(joint_count_, -1);
    std::vector<int> part_joint;
    for (std::size_t t = 0; t < roots.size(); ++t) {
      for (std::size_t j = 0; j < joint_count_; ++j) {
        if (!kept_[j] || tree[j] != roots[t]) continue;
        PartDescription part;
        part.central_curve = curves_[j];
        part.joint = MakeJoint(int(j));
        const int parent = mesh_.joints[j].parent;
        if (parent >= 0 && owner[parent] >= 0) {
          part.parent = description.parts[part_of[owner[parent]]].name;
        } else if (t > 0) {
          // A further tree hangs from the part nearest its root joint placed so far.
          std::size_t nearest = 0;
          double distance = std::numeric_limits<double>::infinity();
          for (std::size_t p = 0; p < description.parts.size(); ++p) {
            const double d = DistanceToPolyline(description.parts[p].central_curve, position_[j]);
            if (d < distance) {
              distance = d;
              nearest = p;
            }
          }
          part.parent = description.parts[nearest].name;
        }
        part_of[j] = int(description.parts.size());
        part_joint.push_back(int(j));
        part.name = UniqueName(int(j));
        description.parts.push_back(std::move(part));
      }
    }

    description.vertex_part.assign(mesh_.welded_positions.empty() ? 0 : dominant_.size(), -1);
    for (std::size_t w = 0; w < description.vertex_part.size(); ++w)
      if (dominant_[w] >= 0 && owner[dominant_[w]] >= 0)
        description.vertex_part[w] = part_of[owner[dominant_[w]]];
    if (std::string error = ValidateRigDescription(description); !error.empty())
      return Error{"skeleton gives an invalid description: " + error};
    return description;
  }

  // The joint's name, or "bone_<index>" when empty; a name another part took (or another
  // joint owns) gets "_2", "_3", ...
  std::string UniqueName(int j) {
    if (reserved_.empty())
      for (const Joint& joint : mesh_.joints) reserved_.insert(joint.name);
    const std::string& own = mesh_.joints[j].name;
    const std::string base = own.empty() ? "bone_" + std::to_string(j) : own;
    auto taken = [&](const std::string& name) {
      return used_.contains(name) || (name != own && reserved_.contains(name));
    };
    std::string name = base;
    for (int k = 2; taken(name); ++k) name = base + "_" + std::to_string(k);
    used_.insert(name);
    return name;
  }

  // A ball joint about the bone's bind X axis (Z when X runs along the bone; the default rest
  // normal when both do).
  JointDescription MakeJoint(int j) const {
    JointDescription joint;
    joint.type = JointType::kBall;
    const std::vector<Vec3>& curve = curves_[j];
    const Vec3 bone = (curve[1] - curve[0]).normalized();
    const Mat3 rotation = JointRotation(mesh_.joints[j]);
    for (int column : {0, 2}) {
      const Vec3 axis = rotation.col(column);
      if (axis.norm() < 1e-9) continue;
      if (std::abs(axis.normalized().dot(bone)) <= kAlongBoneCos) {
        joint.axis = axis.normalized();
        break;
      }
    }
    return joint;
  }

  const Mesh& mesh_;
  const std::size_t joint_count_;
  const std::vector<Vec3>* points_ = nullptr;
  std::vector<int> dominant_;  // per welded vertex: its joint of largest weight, or -1
  std::vector<std::vector<int>> children_;
  std::vector<Vec3> position_;
  std::vector<std::vector<std::uint32_t>> own_vertices_;
  std::vector<std::size_t> subtree_joints_, subtree_vertices_;
  double min_length_ = 1e-9;
  std::optional<Vec3> bone_axis_;
  std::vector<bool> kept_;
  std::vector<std::vector<Vec3>> curves_;
  std::set<std::string> reserved_, used_;
};

}  // namespace

Result<RigDescription> DescribeFromSkeleton(const Mesh& mesh) {
  return SkeletonDescriber(mesh).Describe();
}

}  // namespace wirerig
