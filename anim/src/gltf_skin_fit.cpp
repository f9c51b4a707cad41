#include "gltf_skin_fit.h"
#include "gltf_flesh_joints.h"
#include "gltf_skin_weights.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <Eigen/SVD>

#include "wirerig/runtime/parallel.h"

namespace wirerig::gltf {
namespace {

using Rigid = RigidTransform;

constexpr int kFleshRounds = 6;           // weight rounds with the flesh joints in, the best kept
constexpr std::size_t kKeysPerTask = 16;  // keys per task of the transforms' fit

Rigid SampleAt(const BakedSpine& spine, std::size_t key, std::size_t s) {
  const std::size_t i = key * spine.SampleCount() + s;
  return {spine.rotations[i].normalized(), spine.points[i]};
}

Rigid RestSampleAt(const BakedSpine& spine, std::size_t s) {
  return {spine.rest_rotations[s].normalized(), spine.rest_points[s]};
}

// Whether every sample keeps its rest place and turn in the first sample's frame at every key
// (to 1e-6 of the spine's length and 1e-6 rad).
bool MovesRigidly(const BakedSpine& spine, std::size_t keys) {
  const std::size_t n = spine.SampleCount();
  double length = 0.0;
  for (std::size_t s = 1; s < n; ++s)
    length += (spine.rest_points[s] - spine.rest_points[s - 1]).norm();
  const double tolerance = 1e-6 * std::max(length, 1e-9);
  const Rigid rest_first = RestSampleAt(spine, 0);
  for (std::size_t k = 0; k < keys; ++k) {
    const Rigid first = SampleAt(spine, k, 0);
    for (std::size_t s = 1; s < n; ++s) {
      const Rigid rest = rest_first.LocalOf(RestSampleAt(spine, s));
      const Rigid now = first.LocalOf(SampleAt(spine, k, s));
      if ((rest.translation - now.translation).norm() > tolerance ||
          rest.rotation.angularDistance(now.rotation) > 1e-6)
        return false;
    }
  }
  return true;
}

// The chosen samples of every spine, in increasing order (the first is always sample 0).
Result<std::vector<std::vector<std::size_t>>> ChooseSamples(const BakedAnimation& bake,
                                                            const SkinFitOptions& options) {
  const std::size_t spines = bake.spines.size();
  const std::size_t per_part = options.max_joints_per_part;
  std::vector<std::size_t> count(spines, 1);
  std::vector<bool> deformable(spines, false);
  std::size_t total = 0;
  for (std::size_t i = 0; i < spines; ++i) {
    const BakedSpine& spine = bake.spines[i];
    if (per_part == 0) {
      count[i] = spine.SampleCount();
    } else if (!MovesRigidly(spine, bake.KeyCount())) {
      deformable[i] = true;
      count[i] = std::min(spine.SampleCount(), per_part);
    }
    total += count[i];
  }
  char message[200];
  if (total > options.max_joints && (per_part == 0 || spines > options.max_joints)) {
    std::snprintf(message, sizeof message,
                  per_part == 0 ? "a joint at every spine sample needs %zu joints, more than "
                                  "max_joints (%zu)"
                                : "the rig's %zu parts need a joint each, more than max_joints "
                                  "(%zu)",
                  per_part == 0 ? total : spines, options.max_joints);
    return Error{message};
  }
  if (total > options.max_joints) {
    // Every part keeps one joint; the deformable ones share what is left, in part order.
    std::size_t left = options.max_joints - spines;
    for (std::size_t i = 0; i < spines; ++i)
      if (deformable[i]) count[i] = 1;
    for (bool grew = true; grew && left > 0;) {
      grew = false;
      for (std::size_t i = 0; i < spines && left > 0; ++i) {
        if (!deformable[i] || count[i] >= std::min(bake.spines[i].SampleCount(), per_part))
          continue;
        ++count[i];
        --left;
        grew = true;
      }
    }
  }
  std::vector<std::vector<std::size_t>> samples(spines);
  for (std::size_t i = 0; i < spines; ++i) {
    const std::size_t n = bake.spines[i].SampleCount(), c = count[i];
    for (std::size_t m = 0; m < c; ++m) {
      samples[i].push_back(c == 1 ? 0
                                  : static_cast<std::size_t>(
                                        std::lround(double(m) * double(n - 1) / double(c - 1))));
    }
  }
  return samples;
}

// Per vertex, its bake weights on samples moved to the chosen joints (see the header).
SkinInfluences MapInfluences(const BakedAnimation& bake,
                             const std::vector<std::vector<std::size_t>>& samples,
                             const std::vector<std::size_t>& first_joint, std::size_t slots,
                             bool byte_weights) {
  // Global sample index -> (spine, sample).
  std::vector<std::pair<std::size_t, std::size_t>> sample_of;
  for (std::size_t i = 0; i < bake.spines.size(); ++i)
    for (std::size_t s = 0; s < bake.spines[i].SampleCount(); ++s) sample_of.emplace_back(i, s);
  SkinInfluences influences;
  influences.slots = slots;
  influences.byte_weights = byte_weights;
  std::vector<std::pair<std::uint32_t, double>> pairs;
  auto add = [&pairs](std::size_t joint, double w) {
    if (!(w > 0.0)) return;
    const auto j = static_cast<std::uint32_t>(joint);
    auto same =
        std::find_if(pairs.begin(), pairs.end(), [j](const auto& p) { return p.first == j; });
    if (same != pairs.end()) {
      same->second += w;
    } else {
      pairs.emplace_back(j, w);
    }
  };
  for (std::size_t v = 0; v < bake.vertex_count; ++v) {
    pairs.clear();
    for (std::size_t c = 0; c < 4; ++c) {
      const double w = bake.skin_weights[v][static_cast<Eigen::Index>(c)];
      if (!(w > 0.0)) continue;
      const auto [spine, s] = sample_of[bake.skin_joints[v][c]];
      const std::vector<std::size_t>& chosen = samples[spine];
      // The chosen joints m, m + 1 around sample s.
      const auto after = std::upper_bound(chosen.begin(), chosen.end(), s);
      const std::size_t m = static_cast<std::size_t>(after - chosen.begin()) - 1;
      if (after == chosen.end() || chosen[m] == s) {
        add(first_joint[spine] + m, w);
        continue;
      }
      const double f = double(s - chosen[m]) / double(*after - chosen[m]);
      add(first_joint[spine] + m, w * (1.0 - f));
      add(first_joint[spine] + m + 1, w * f);
    }
    AppendInfluences(pairs, &influences);
  }
  return influences;
}

// One key's skinning transforms x -> rotation[j] x + translation[j] (the joint's world
// transform times its inverse rest transform) fitted to the bake, joint by joint.
class KeyFit {
 public:
  KeyFit(const SkinInfluences& influences, const BaseVertices& base, std::size_t joints)
      : influences_(influences), slots_(influences.slots), base_(base), members_(joints) {
    for (std::size_t v = 0; v < base.Count(); ++v)
      for (std::size_t c = 0; c < slots_; ++c)
        if (influences.weights[v * slots_ + c] > 0.0f)
          members_[influences.joints[v * slots_ + c]].push_back(
              {static_cast<std::uint32_t>(v), static_cast<std::uint8_t>(c)});
  }

  // Improves rotation / translation (#J, the start) for the baked positions `target` (#V).
  void Run(std::span<const Vec3f> target, int iterations, std::span<Mat3> rotation,
           std::span<Vec3> translation) {
    for (int pass = 0; pass < iterations; ++pass)
      for (std::size_t j = 0; j < members_.size(); ++j) FitJoint(j, target, rotation, translation);
  }

 private:
  struct Member {
    std::uint32_t vertex;
    std::uint8_t slot;
  };

  Vec3 Rest(std::size_t v) const {
    return Eigen::Map<const Eigen::Vector3f>(&base_.positions[v * 3]).cast<double>();
  }

  // Minimises sum over the joint's vertices of |e - w (R r + t)|^2, e being the bake minus
  // the other joints' share; a small pull towards the current rotation keeps joints whose
  // vertices lie on a line or a plane from spinning about it.
  void FitJoint(std::size_t j, std::span<const Vec3f> target, std::span<Mat3> rotation,
                std::span<Vec3> translation) {
    const std::vector<Member>& members = members_[j];
    if (members.size() < 3) return;
    residual_.resize(members.size());
    double sum_w2 = 0.0;
    Vec3 sum_w2r = Vec3::Zero(), sum_we = Vec3::Zero();
    for (std::size_t i = 0; i < members.size(); ++i) {
      const std::size_t v = members[i].vertex;
      const Vec3 r = Rest(v);
      Vec3 e = target[v].cast<double>();
      for (std::size_t c = 0; c < slots_; ++c) {
        const float w = influences_.weights[v * slots_ + c];
        if (c == members[i].slot || w == 0.0f) continue;
        const std::size_t other = influences_.joints[v * slots_ + c];
        e -= double(w) * (rotation[other] * r + translation[other]);
      }
      const double w = influences_.weights[v * slots_ + members[i].slot];
      residual_[i] = e;
      sum_w2 += w * w;
      sum_w2r += w * w * r;
      sum_we += w * e;
    }
    const Vec3 center_rest = sum_w2r / sum_w2, center_target = sum_we / sum_w2;
    Mat3 covariance = Mat3::Zero();  // sum target' source'^T
    double spread = 0.0;
    for (std::size_t i = 0; i < members.size(); ++i) {
      const double w = influences_.weights[members[i].vertex * slots_ + members[i].slot];
      const Vec3 source = w * (Rest(members[i].vertex) - center_rest);
      covariance += (residual_[i] - w * center_target) * source.transpose();
      spread += source.squaredNorm();
    }
    covariance += 1e-3 * spread * rotation[j];
    const Eigen::JacobiSVD<Mat3> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Mat3 fix = Mat3::Identity();
    fix(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
    const Mat3 r_new = svd.matrixU() * fix * svd.matrixV().transpose();
    const Vec3 t_new = center_target - r_new * center_rest;
    double before = 0.0, after = 0.0;
    for (std::size_t i = 0; i < members.size(); ++i) {
      const std::size_t v = members[i].vertex;
      const double w = influences_.weights[v * slots_ + members[i].slot];
      const Vec3 r = Rest(v);
      before += (residual_[i] - w * (rotation[j] * r + translation[j])).squaredNorm();
      after += (residual_[i] - w * (r_new * r + t_new)).squaredNorm();
    }
    if (after < before) {
      rotation[j] = r_new;
      translation[j] = t_new;
    }
  }

  const SkinInfluences& influences_;
  const std::size_t slots_;
  const BaseVertices& base_;
  std::vector<std::vector<Member>> members_;
  std::vector<Vec3> residual_;
};

// Appends `flesh`'s joints after the #J joints so far ("thigh_l_flesh_0", ...): their parents,
// names and rest frames, and their skinning transforms into each key's row (#K x #J, key-major,
// becoming #K x (#J + #N)).
void AppendFleshJoints(const FleshJoints& flesh, std::size_t keys, std::vector<int>* parent,
                       std::vector<std::string>* names, std::vector<Rigid>* rest,
                       std::vector<Mat3>* rotation, std::vector<Vec3>* translation) {
  const std::size_t joints = parent->size(), added = flesh.Count(), total = joints + added;
  std::vector<Mat3> rotations(keys * total);
  std::vector<Vec3> translations(keys * total);
  for (std::size_t k = 0; k < keys; ++k) {
    std::copy_n(rotation->begin() + std::ptrdiff_t(k * joints), joints,
                rotations.begin() + std::ptrdiff_t(k * total));
    std::copy_n(translation->begin() + std::ptrdiff_t(k * joints), joints,
                translations.begin() + std::ptrdiff_t(k * total));
    std::copy_n(flesh.rotation.begin() + std::ptrdiff_t(k * added), added,
                rotations.begin() + std::ptrdiff_t(k * total + joints));
    std::copy_n(flesh.translation.begin() + std::ptrdiff_t(k * added), added,
                translations.begin() + std::ptrdiff_t(k * total + joints));
  }
  *rotation = std::move(rotations);
  *translation = std::move(translations);
  std::vector<std::size_t> count(joints, 0);
  for (std::size_t n = 0; n < added; ++n) {
    const auto up = static_cast<std::size_t>(flesh.parent[n]);
    parent->push_back(flesh.parent[n]);
    names->push_back((*names)[up] + "_flesh_" + std::to_string(count[up]++));
    rest->push_back(flesh.rest[n]);
  }
}

}  // namespace

Result<FittedSkin> FitSkeleton(const BakedAnimation& bake, const BaseVertices& base,
                               const SkinFitOptions& options) {
  Result<std::vector<std::vector<std::size_t>>> chosen = ChooseSamples(bake, options);
  if (!chosen) return Error{chosen.error()};
  const std::vector<std::vector<std::size_t>>& samples = chosen.value();

  // Joints in spine order (parents first, as the spines are), and their names and parents.
  std::vector<std::size_t> first_joint;
  std::vector<int> parent;
  std::vector<std::string> names;
  std::vector<std::pair<std::size_t, std::size_t>> joint_sample;  // (spine, sample)
  for (std::size_t i = 0; i < bake.spines.size(); ++i) {
    const BakedSpine& spine = bake.spines[i];
    first_joint.push_back(parent.size());
    const std::string base_name = spine.name.empty() ? "spine" + std::to_string(i) : spine.name;
    for (std::size_t m = 0; m < samples[i].size(); ++m) {
      int p = static_cast<int>(parent.size()) - 1;
      if (m == 0 && spine.parent < 0) p = -1;
      if (m == 0 && spine.parent >= 0) {
        // The parent's chosen joint at or before the attachment sample.
        const auto ps = static_cast<std::size_t>(spine.parent);
        const std::vector<std::size_t>& up = samples[ps];
        const auto after =
            std::upper_bound(up.begin(), up.end(), static_cast<std::size_t>(spine.parent_joint));
        p = static_cast<int>(first_joint[ps] + static_cast<std::size_t>(after - up.begin()) - 1);
      }
      parent.push_back(p);
      names.push_back(samples[i].size() == 1 ? base_name : base_name + "_" + std::to_string(m));
      joint_sample.emplace_back(i, samples[i][m]);
    }
  }
  // Bridge joints: where a part hangs from its parent, a leaf joint under the parent's joint
  // starts half-way between the two sides (the helper joint games put at elbows and knees), so
  // the fitted skin can bend across the joint as the rig's bridge does. Added after every part's
  // own joints, while the budget allows.
  std::vector<std::pair<std::size_t, std::size_t>> bridges;  // (bridge joint, child's first)
  for (std::size_t i = 0; options.bridge_joints && i < bake.spines.size(); ++i) {
    if (bake.spines[i].parent < 0 || parent.size() >= options.max_joints) continue;
    const std::size_t child = first_joint[i];
    bridges.emplace_back(parent.size(), child);
    parent.push_back(parent[child]);
    names.push_back(
        (bake.spines[i].name.empty() ? "spine" + std::to_string(i) : bake.spines[i].name) +
        "_bridge");
    joint_sample.push_back(joint_sample[child]);  // at the child's root
  }
  std::size_t joints = parent.size();
  const std::size_t keys = bake.KeyCount();

  FittedSkin fitted;
  fitted.influences =
      MapInfluences(bake, samples, first_joint, options.influences, options.byte_weights);
  std::vector<Rigid> rest(joints);
  for (std::size_t j = 0; j < joints; ++j)
    rest[j] = RestSampleAt(bake.spines[joint_sample[j].first], joint_sample[j].second);
  // Skinning transforms x -> R x + t of every joint at every key (the joint's world transform
  // times its inverse rest transform), starting from the baked spine frames.
  std::vector<Mat3> rotation(keys * joints);
  std::vector<Vec3> translation(keys * joints);
  for (std::size_t k = 0; k < keys; ++k) {
    for (std::size_t j = 0; j < joints; ++j) {
      const Rigid now = SampleAt(bake.spines[joint_sample[j].first], k, joint_sample[j].second);
      rotation[k * joints + j] = (now.rotation * rest[j].rotation.conjugate()).toRotationMatrix();
      translation[k * joints + j] =
          now.translation - rotation[k * joints + j] * rest[j].translation;
    }
  }
  for (const auto& [bridge, child] : bridges) {
    const auto up = static_cast<std::size_t>(parent[bridge]);
    const Vec3 x = rest[bridge].translation;  // the joint's place: both sides agree on it
    for (std::size_t k = 0; k < keys; ++k) {
      const Quat half =
          Quat(rotation[k * joints + up]).slerp(0.5, Quat(rotation[k * joints + child]));
      rotation[k * joints + bridge] = half.toRotationMatrix();
      translation[k * joints + bridge] = rotation[k * joints + child] * x +
                                         translation[k * joints + child] -
                                         rotation[k * joints + bridge] * x;
    }
  }
  // Keys are independent: tasks of kKeysPerTask keys on every core, each with its own KeyFit.
  const ThreadPool pool(std::max(1u, std::thread::hardware_concurrency()));
  auto fit_transforms = [&] {
    struct Context {
      const SkinInfluences* influences;
      const BaseVertices* base;
      const BakedAnimation* bake;
      std::size_t joints, keys;
      int iterations;
      Mat3* rotation;
      Vec3* translation;
    } context{&fitted.influences, &base, &bake, joints, keys, options.iterations, rotation.data(),
              translation.data()};
    const auto task = [](const void* c, std::size_t t) {
      const Context& x = *static_cast<const Context*>(c);
      KeyFit fit(*x.influences, *x.base, x.joints);
      const std::size_t vertices = x.base->Count();
      for (std::size_t k = t * kKeysPerTask; k < std::min(x.keys, (t + 1) * kKeysPerTask); ++k) {
        fit.Run(std::span(x.bake->positions).subspan(k * vertices, vertices), x.iterations,
                std::span(x.rotation + k * x.joints, x.joints),
                std::span(x.translation + k * x.joints, x.joints));
      }
    };
    RunTasks(&pool, (keys + kKeysPerTask - 1) / kKeysPerTask, task, &context);
  };
  // Weights first, on the baked frames (a rigid part's frames are already right); then the
  // transforms for those weights.
  for (int round = 0; round < options.weight_rounds; ++round) {
    fitted.influences =
        FitWeights(fitted.influences, parent, base, bake, rotation, translation, &pool);
    fit_transforms();
  }
  if (options.weight_rounds == 0) fit_transforms();
  if (options.flesh_joints && options.weight_rounds > 0 && joints < options.max_joints) {
    const FleshJoints flesh =
        FindFleshJoints(fitted.influences, base, bake, rest, rotation, translation,
                        options.max_joints - joints, options.flesh_error);
    if (flesh.Count() > 0) {
      // The alternation is not monotone (only the largest weights are kept), so the round that
      // leaves the least squared error is kept, or the skin without flesh joints if none beats it.
      const auto squared_error = [&] {
        return SquaredSkinError(fitted.influences, base, bake, rotation, translation);
      };
      const std::size_t bones = joints;
      double best_error = squared_error();
      bool best_has_flesh = false;
      SkinInfluences best_influences = fitted.influences;
      std::vector<Mat3> best_rotation = rotation;
      std::vector<Vec3> best_translation = translation;
      AppendFleshJoints(flesh, keys, &parent, &names, &rest, &rotation, &translation);
      joints = parent.size();
      for (int round = 0; round < kFleshRounds; ++round) {
        fitted.influences =
            FitWeights(fitted.influences, parent, base, bake, rotation, translation, &pool);
        fit_transforms();
        if (const double error = squared_error(); error < best_error) {
          best_error = error;
          best_has_flesh = true;
          best_influences = fitted.influences;
          best_rotation = rotation, best_translation = translation;
        }
      }
      if (!best_has_flesh) parent.resize(bones), names.resize(bones), rest.resize(bones);
      fitted.influences = std::move(best_influences);
      rotation = std::move(best_rotation), translation = std::move(best_translation);
      joints = parent.size();
    }
  }
  std::vector<Rigid> keyed(keys * joints);
  for (std::size_t i = 0; i < keys * joints; ++i) {
    const std::size_t j = i % joints;
    const Quat q(rotation[i]);
    keyed[i] = {(q * rest[j].rotation).normalized(),
                rotation[i] * rest[j].translation + translation[i]};
  }
  // Each joint's reach: the farthest vertex it moves, from its rest origin.
  std::vector<double> reach(joints, 0.0);
  for (std::size_t v = 0; v < base.Count(); ++v) {
    const Vec3 p = Eigen::Map<const Eigen::Vector3f>(&base.positions[v * 3]).cast<double>();
    const std::size_t slots = fitted.influences.slots;
    for (std::size_t c = 0; c < slots; ++c) {
      if (fitted.influences.weights[v * slots + c] == 0.0f) continue;
      const std::size_t j = fitted.influences.joints[v * slots + c];
      reach[j] = std::max(reach[j], (p - rest[j].translation).norm());
    }
  }
  std::vector<float> times;
  for (double t : bake.times) times.push_back(static_cast<float>(t));
  KeyThinning thinning;
  thinning.times = times;
  thinning.tolerance = options.key_tolerance;
  thinning.reach = reach;
  thinning.translation_bits = options.translation_bits;
  thinning.rotation_bits = options.rotation_bits;
  fitted.skeleton = MakeSkeleton(std::move(parent), std::move(names), rest, keyed, thinning);
  return fitted;
}

}  // namespace wirerig::gltf
