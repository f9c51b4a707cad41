// Linear blend skinning on the CPU with the glTF formula, from the values as stored in the file:
// joint world transforms G_j composed from the float local transforms (rotations normalized),
// skinning matrices S_j = G_j * inverse_bind_j, and per vertex p' = sum_i w_i S_{j_i} p.
#pragma once

#include <span>
#include <vector>

#include "gltf_mesh.h"
#include "gltf_skin.h"

namespace wirerig::gltf {

// Joint-to-world transforms (#J) for the local transforms `translations`, `rotations` (#J).
std::vector<Mat4d> JointGlobals(const Skeleton& skeleton, std::span<const Vec3f> translations,
                                std::span<const Quatf> rotations);

// Skinning matrices S_j at key `key`.
std::vector<Mat4d> SkinMatrices(const Skeleton& skeleton, std::size_t key);

// The blended matrix sum_i w_i S_{j_i} of vertex `v`.
Mat4d BlendedSkinMatrix(const SkinInfluences& influences, std::span<const Mat4d> skin_matrices,
                        std::size_t v);

// Error of the skinned rest mesh against the bake at every key and, when asked, the residual
// morph targets that make the skin exact at the keys: per key k and vertex v the delta r with
// M (p + r) = bake (M = the blended matrix, linear part A): r = A^-1 (bake - M p); normals
// likewise n + dn = A^-1 bake_n (with residual_normals). Where A is singular (|det A| < 1e-9) the
// residual falls back to bake - M p and is not exact.
struct SkinFit {
  double max_error = 0.0;                 // m, over keys and vertices
  double rms_error = 0.0;                 // m
  std::vector<float> residual_positions;  // #K x #V x 3, or empty
  std::vector<float> residual_normals;    // #K x #V x 3, or empty
  double residual_max_error = 0.0;        // m, skinned (p + r) against the bake
};
SkinFit FitSkin(const Skeleton& skeleton, const SkinInfluences& influences,
                const BaseVertices& base, const BakedAnimation& bake, bool residuals,
                bool residual_normals);

}  // namespace wirerig::gltf
