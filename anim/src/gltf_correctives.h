// Corrective blend shapes for what the skin's joints cannot do (a profile's bulge, a wire's
// stretch): the residual that makes the skinned mesh exact at every key (SkinFit's residual
// morph targets, in bind space) compressed by PCA to the few shapes that carry it, with their
// weights per key as the animation, instead of one target per key.
//
// The residuals form a #K x 3#V matrix X; the eigenvectors u_i of X X^T (largest eigenvalue
// lambda_i first) give shapes X^T u_i (the SVD of X). Each step takes either PCA's next shape or
// the worst key's remaining residual as a shape, whole or near its worst vertex only (an
// error a few keys hold, which PCA ranks by energy and leaves for last), whichever leaves the
// smaller worst vertex error, its weights per key fitted by least squares to what the shapes before
// it leave. Shapes are added until every vertex at every key is within `max_error` of its exact
// residual (in bind space: the skinning matrix blends rotations, so the skinned error is no larger
// up to the blend's shrinkage), or `max_shapes` are used. When that misses the target, rounds of
// Lawson's reweighting (vertices weighted by the worst error the last round left them) choose
// the shapes again, and each vertex's own entries are refined toward its smallest worst error
// over the keys; once the target is met, one shape fewer is tried likewise while it holds.
// The shapes carry positions only (millimetres of bulge: the skinned normals stand, and each
// shape costs half the bytes).
#pragma once

#include <cstddef>
#include <vector>

#include "gltf_mesh.h"
#include "gltf_skinning.h"

namespace wirerig::gltf {

struct CorrectiveOptions {
  std::size_t max_shapes = 16;
  double max_error = 1e-3;  // m
  int delta_bits = 0;       // > 0: the shapes stored through the EXPONENTIAL filter
  // Shapes stored as normalized signed bytes (KHR_mesh_quantization): each shape is scaled to
  // its largest component (the scale goes into its weights) and rounded to q / 127, and its
  // weights are then fitted to what the shapes before it leave (least squares per key), so the
  // rounding is carried like any other residual and the error is the stored file's.
  bool byte_shapes = false;
};

struct Correctives {
  std::size_t shape_count = 0;
  std::vector<float> positions;  // #S x #V x 3 bind-space deltas (multiples of 1/127: byte_shapes)
  bool byte_shapes = false;
  std::vector<float> weights;  // #K x #S, key-major
  double max_error = 0.0;      // m: skinned, shapes applied, against the bake at the keys
  double rms_error = 0.0;      // m
};

// `fit` must carry residuals (FitSkin with residuals) for `bake`.
Correctives FitCorrectives(const Skeleton& skeleton, const SkinInfluences& influences,
                           const BaseVertices& base, const BakedAnimation& bake, const SkinFit& fit,
                           const CorrectiveOptions& options);

}  // namespace wirerig::gltf
