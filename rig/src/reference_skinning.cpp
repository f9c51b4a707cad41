#include "wirerig/rig/reference_skinning.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>

#include "wirerig/runtime/spine_interpolation.h"

namespace wirerig {
namespace {

constexpr std::size_t kMaxBones = 256;
constexpr double kSimilaritySigma = 0.1;

double SmoothStep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Le and Hodgins 2016, Eq. 4: how alike two weight vectors are (dense over the bones).
double Similarity(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) {
    if (a[j] == 0.0 || b[j] == 0.0) continue;
    for (std::size_t k = j + 1; k < a.size(); ++k) {
      if (a[k] == 0.0 || b[k] == 0.0) continue;
      const double d = a[j] * b[k] - a[k] * b[j];
      s += 2.0 * a[j] * a[k] * b[j] * b[k] *
           std::exp(-d * d / (kSimilaritySigma * kSimilaritySigma));
    }
  }
  return s;
}

struct Quatf {
  float w, x, y, z;
};

Quatf ToQuat(const BoneMatrix& m) {
  Mat3 r;
  r << m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10];
  const Quat q(r);
  return {float(q.w()), float(q.x()), float(q.y()), float(q.z())};
}

// v + 2 q.vec x (q.vec x v + w v)
inline void Rotate(const Quatf& q, float x, float y, float z, float* ox, float* oy, float* oz) {
  const float tx = 2.0f * (q.y * z - q.z * y), ty = 2.0f * (q.z * x - q.x * z),
              tz = 2.0f * (q.x * y - q.y * x);
  *ox = x + q.w * tx + (q.y * tz - q.z * ty);
  *oy = y + q.w * ty + (q.z * tx - q.x * tz);
  *oz = z + q.w * tz + (q.x * ty - q.y * tx);
}

// Linear blend skinning as ozz-animation's SkinningJob writes it: each bone's transform as four
// columns of four floats (one SIMD register each, the fourth lane 0), the influences' columns
// blended with one multiply-add per column, the point and normal transformed by splatting their
// coordinates. The normal is renormalised (a blend of rotations is not one).
using Float4 = float __attribute__((vector_size(16)));
struct BoneColumns {
  Float4 column[4];
};

void LinearBlend(const ReferenceSkin& s, std::span<const BoneMatrix> bones, std::span<float> x,
                 std::span<float> y, std::span<float> z, std::span<float> nx, std::span<float> ny,
                 std::span<float> nz) {
  std::array<BoneColumns, kMaxBones> columns;
  for (std::size_t b = 0; b < bones.size(); ++b)
    for (int c = 0; c < 4; ++c)
      columns[b].column[c] = Float4{bones[b][std::size_t(c)], bones[b][std::size_t(4 + c)],
                                    bones[b][std::size_t(8 + c)], 0.0f};
  constexpr int K = ReferenceSkin::kInfluences;
  const std::size_t n = s.x.size();
  for (std::size_t v = 0; v < n; ++v) {
    Float4 c0{}, c1{}, c2{}, c3{};
    for (int k = 0; k < K; ++k) {
      const float w = s.weights[v][std::size_t(k)];
      const BoneColumns& m = columns[s.bones[v][std::size_t(k)]];
      c0 += w * m.column[0], c1 += w * m.column[1], c2 += w * m.column[2];
      c3 += w * m.column[3];
    }
    const Float4 p = c0 * s.x[v] + c1 * s.y[v] + c2 * s.z[v] + c3;
    const Float4 q = c0 * s.nx[v] + c1 * s.ny[v] + c2 * s.nz[v];
    x[v] = p[0], y[v] = p[1], z[v] = p[2];
    const Float4 qq = q * q;
    const float inverse = 1.0f / __builtin_sqrtf(qq[0] + qq[1] + qq[2]);
    nx[v] = q[0] * inverse, ny[v] = q[1] * inverse, nz[v] = q[2] * inverse;
  }
}

}  // namespace

const char* ToString(ReferenceSkinning method) {
  switch (method) {
    case ReferenceSkinning::kDualQuaternion:
      return "dual quaternion";
    case ReferenceSkinning::kCentreOfRotation:
      return "centres of rotation";
    case ReferenceSkinning::kLinearBlend:
      break;
  }
  return "linear blend";
}

ReferenceSkin MakeReferenceSkin(const RigModel& model, std::span<const Vec3> rest) {
  const std::size_t n = rest.size(), bones = model.parts.size();
  assert(bones <= kMaxBones);
  ReferenceSkin skin;
  std::vector<Vec3> normals(n, Vec3::Zero());
  for (const Triangle& t : model.triangles) {
    const Vec3 f = (rest[t[1]] - rest[t[0]]).cross(rest[t[2]] - rest[t[0]]);
    for (std::uint32_t i : t) normals[i] += f;
  }
  std::vector<std::vector<double>> dense(n, std::vector<double>(bones, 0.0));
  for (std::size_t v = 0; v < n; ++v) {
    skin.x.push_back(float(rest[v].x()));
    skin.y.push_back(float(rest[v].y()));
    skin.z.push_back(float(rest[v].z()));
    const Vec3 normal = normals[v].norm() > 0.0 ? normals[v].normalized() : Vec3::UnitY();
    skin.nx.push_back(float(normal.x()));
    skin.ny.push_back(float(normal.y()));
    skin.nz.push_back(float(normal.z()));
    const VertexAttachment& a = model.vertices[v];
    double own = 1.0;
    for (const JointInfluence& j : a.joints) {
      // A skinless bone's blend (skinless_spread.h) is left out: with it the torso's vertices
      // needed a fifth bone and lost one of their four (the baselines' spine rows folded 40
      // edges); a game rig weighs the torso to the chest, the arm to the clavicle's children.
      if (j.joint < 0 || IsSkinless(model.parts[std::size_t(j.joint)])) continue;
      const double child = SmoothStep(j.u);
      dense[v][std::size_t(j.joint)] += j.weight * child;
      const auto parent = std::size_t(model.parts[std::size_t(j.joint)].parent);
      dense[v][parent] += j.weight * (1 - child);
      // The bridge's motion minus its side's (rig_model.h): the child's for the child's skin
      // (own: its part is the child), the child's rigid motion for the skin of parts below it.
      if (j.joint == int(a.part))
        own -= j.weight;
      else if (IsBelowPart(model, a.part, std::size_t(j.joint)))
        dense[v][std::size_t(j.joint)] -= j.weight;
      else
        dense[v][parent] -= j.weight;
    }
    dense[v][a.part] += own;
    // The largest weights by magnitude (a joint's skin spread over an ancestor's subtracts its
    // parent's motion).
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t b = 0; b < bones; ++b)
      if (dense[v][b] != 0.0) order.push_back({dense[v][b], b});
    std::sort(order.begin(), order.end(),
              [](const auto& l, const auto& r) { return std::abs(l.first) > std::abs(r.first); });
    order.resize(std::min<std::size_t>(order.size(), ReferenceSkin::kInfluences));
    double sum = 0.0;
    for (const auto& o : order) sum += o.first;
    std::array<std::uint16_t, ReferenceSkin::kInfluences> ids{};
    std::array<float, ReferenceSkin::kInfluences> ws{};
    std::fill(dense[v].begin(), dense[v].end(), 0.0);
    for (std::size_t k = 0; k < order.size(); ++k) {
      ids[k] = std::uint16_t(order[k].second);
      ws[k] = float(order[k].first / sum);
      dense[v][order[k].second] = order[k].first / sum;
    }
    skin.bones.push_back(ids);
    skin.weights.push_back(ws);
  }
  // Centres of rotation: over the triangles blending two or more bones (the others add 0).
  struct Blended {
    std::vector<double> weights;
    Vec3 centroid;
    double area;
  };
  std::vector<Blended> triangles;
  for (const Triangle& t : model.triangles) {
    std::vector<double> w(bones, 0.0);
    for (std::uint32_t i : t)
      for (std::size_t b = 0; b < bones; ++b) w[b] += dense[i][b] / 3.0;
    if (std::count_if(w.begin(), w.end(), [](double x) { return x > 0.0; }) < 2) continue;
    const Vec3 f = (rest[t[1]] - rest[t[0]]).cross(rest[t[2]] - rest[t[0]]);
    triangles.push_back(
        {std::move(w), (rest[t[0]] + rest[t[1]] + rest[t[2]]) / 3.0, 0.5 * f.norm()});
  }
  for (std::size_t v = 0; v < n; ++v) {
    Vec3 centre = rest[v];
    if (skin.weights[v][1] > 0.0f) {
      Vec3 sum = Vec3::Zero();
      double total = 0.0;
      for (const Blended& t : triangles) {
        const double s = Similarity(dense[v], t.weights) * t.area;
        sum += s * t.centroid;
        total += s;
      }
      if (total > 0.0) centre = sum / total;
    }
    skin.cx.push_back(float(centre.x()));
    skin.cy.push_back(float(centre.y()));
    skin.cz.push_back(float(centre.z()));
  }
  return skin;
}

void BoneMatricesFromWorkspace(const RigModel& model, const RigWorkspace& workspace,
                               std::span<BoneMatrix> out) {
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const PartModel& part = model.parts[i];
    const Mat3 r = FrameAxes(workspace.spine_frames[i].front()) *
                   FrameAxes(part.spine_frames.front()).transpose();
    const Vec3 t = workspace.spine_points[i].front() - r * part.spine_points.front();
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 3; ++col) out[i][std::size_t(4 * row + col)] = float(r(row, col));
      out[i][std::size_t(4 * row + 3)] = float(t[row]);
    }
  }
}

void ReferenceSkinningJob::Run() const {
  const ReferenceSkin& s = *skin;
  const std::size_t n = s.x.size();
  constexpr int K = ReferenceSkin::kInfluences;
  if (method == ReferenceSkinning::kLinearBlend) {
    LinearBlend(s, bones, x, y, z, nx, ny, nz);
    return;
  }
  // Per bone: rotation quaternion and translation (dual part from them).
  std::array<Quatf, kMaxBones> real;
  std::array<Quatf, kMaxBones> dual;
  for (std::size_t b = 0; b < bones.size(); ++b) {
    real[b] = ToQuat(bones[b]);
    const float tx = bones[b][3], ty = bones[b][7], tz = bones[b][11];
    const Quatf& q = real[b];
    // dual = 0.5 (0, t) q
    dual[b] = {-0.5f * (tx * q.x + ty * q.y + tz * q.z), 0.5f * (tx * q.w + ty * q.z - tz * q.y),
               0.5f * (-tx * q.z + ty * q.w + tz * q.x), 0.5f * (tx * q.y - ty * q.x + tz * q.w)};
  }
  for (std::size_t v = 0; v < n; ++v) {
    const Quatf& pivot = real[s.bones[v][0]];
    Quatf r{0, 0, 0, 0}, d{0, 0, 0, 0};
    for (int k = 0; k < K; ++k) {
      const std::uint16_t b = s.bones[v][k];
      const Quatf& q = real[b];
      float w = s.weights[v][k];
      if (q.w * pivot.w + q.x * pivot.x + q.y * pivot.y + q.z * pivot.z < 0.0f) w = -w;
      r.w += w * q.w, r.x += w * q.x, r.y += w * q.y, r.z += w * q.z;
      const Quatf& e = dual[b];
      d.w += w * e.w, d.x += w * e.x, d.y += w * e.y, d.z += w * e.z;
    }
    const float inv = 1.0f / std::sqrt(r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z);
    r = {r.w * inv, r.x * inv, r.y * inv, r.z * inv};
    float px, py, pz;
    if (method == ReferenceSkinning::kDualQuaternion) {
      d = {d.w * inv, d.x * inv, d.y * inv, d.z * inv};
      Rotate(r, s.x[v], s.y[v], s.z[v], &px, &py, &pz);
      // translation 2 (r.w d.vec - d.w r.vec + r.vec x d.vec)
      px += 2.0f * (r.w * d.x - d.w * r.x + r.y * d.z - r.z * d.y);
      py += 2.0f * (r.w * d.y - d.w * r.y + r.z * d.x - r.x * d.z);
      pz += 2.0f * (r.w * d.z - d.w * r.z + r.x * d.y - r.y * d.x);
    } else {
      // Centre of rotation c moved by linear blending; the rest turns about it by r.
      const float cx = s.cx[v], cy = s.cy[v], cz = s.cz[v];
      float lx = 0, ly = 0, lz = 0;
      for (int k = 0; k < K; ++k) {
        const float w = s.weights[v][k];
        const BoneMatrix& b = bones[s.bones[v][k]];
        lx += w * (b[0] * cx + b[1] * cy + b[2] * cz + b[3]);
        ly += w * (b[4] * cx + b[5] * cy + b[6] * cz + b[7]);
        lz += w * (b[8] * cx + b[9] * cy + b[10] * cz + b[11]);
      }
      Rotate(r, s.x[v] - cx, s.y[v] - cy, s.z[v] - cz, &px, &py, &pz);
      px += lx, py += ly, pz += lz;
    }
    x[v] = px, y[v] = py, z[v] = pz;
    Rotate(r, s.nx[v], s.ny[v], s.nz[v], &nx[v], &ny[v], &nz[v]);
  }
}

}  // namespace wirerig
