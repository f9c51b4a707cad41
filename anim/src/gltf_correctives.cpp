#include "gltf_correctives.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "gltf_buffers.h"
#include "gltf_meshopt.h"

namespace wirerig::gltf {
namespace {

using RowMatrixf = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The largest |row segment (3v .. 3v + 3)| of `m` - `weight` `shape`^T (#K x 3#V), over the rows
// and vertices, and the row where it lies.
double MaxVertexNorm(const Eigen::MatrixXd& m, const Eigen::VectorXd* weight = nullptr,
                     const Eigen::VectorXd* shape = nullptr, Eigen::Index* worst_row = nullptr) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < m.rows(); ++k) {
    const double w = weight != nullptr ? (*weight)(k) : 0.0;
    for (Eigen::Index i = 0; i + 2 < m.cols(); i += 3) {
      Vec3 r(m(k, i), m(k, i + 1), m(k, i + 2));
      if (shape != nullptr) r -= w * Vec3((*shape)(i), (*shape)(i + 1), (*shape)(i + 2));
      if (r.squaredNorm() > worst) {
        worst = r.squaredNorm();
        if (worst_row != nullptr) *worst_row = k;
      }
    }
  }
  return std::sqrt(worst);
}

// A candidate shape (unit length, or bytes), its least-squares weights per key against what the
// shapes so far leave (`left`), and the worst vertex error it leaves.
struct Candidate {
  Eigen::VectorXd shape, weight;
  double error = std::numeric_limits<double>::infinity();
};

Candidate Fit(const Eigen::MatrixXd& left, Eigen::VectorXd shape, bool byte_shapes) {
  Candidate c;
  const double norm = shape.norm();
  if (!(norm > 0.0) || !std::isfinite(norm)) return c;
  shape /= norm;
  if (byte_shapes) {
    const double largest_component = shape.cwiseAbs().maxCoeff();
    shape = (shape * (kByteScale / largest_component)).array().round() / kByteScale;
    if (!(shape.squaredNorm() > 0.0)) return c;
  }
  c.weight = left * shape / shape.squaredNorm();
  c.shape = std::move(shape);
  c.error = MaxVertexNorm(left, &c.weight, &c.shape);
  return c;
}

// The part of one key's residual (3#V) near its worst: the vertices within a factor
// kWorstPartFactor of its largest, the others zeroed (so that the shape carries the miss, not
// the clip's persistent residual that the key holds too, which PCA's shapes carry).
constexpr double kWorstPartFactor = 0.5;
Eigen::VectorXd WorstPart(Eigen::VectorXd row) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i + 2 < row.size(); i += 3)
    worst = std::max(worst, row.segment<3>(i).norm());
  for (Eigen::Index i = 0; i + 2 < row.size(); i += 3)
    if (row.segment<3>(i).norm() < kWorstPartFactor * worst) row.segment<3>(i).setZero();
  return row;
}

// Shapes and their weights per key, chosen greedily; `mixed`: see the header.
struct Selection {
  std::vector<Eigen::VectorXd> shapes, weights;
  double error = 0.0;  // worst vertex error left, m
};

Selection Select(const Eigen::MatrixXd& residuals,
                 const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& eigen,
                 const CorrectiveOptions& options, bool mixed) {
  const Eigen::Index rows = residuals.rows();
  Selection out;
  Eigen::MatrixXd left = residuals;  // what the shapes so far do not carry
  const double largest = eigen.eigenvalues()(rows - 1);
  Eigen::Index next_eigen = rows - 1;  // the largest eigenvalue not yet taken
  Eigen::Index worst_key = 0;
  while ((out.error = MaxVertexNorm(left, nullptr, nullptr, &worst_key)) > options.max_error &&
         out.shapes.size() < std::min<std::size_t>(options.max_shapes, std::size_t(rows))) {
    Candidate pca;
    if (next_eigen >= 0 && eigen.eigenvalues()(next_eigen) > 1e-14 * largest)
      pca = Fit(left, residuals.transpose() * eigen.eigenvectors().col(next_eigen),
                options.byte_shapes);
    // The worst key's residual whole, or near its worst vertex only.
    Candidate row, part;
    if (mixed) {
      row = Fit(left, left.row(worst_key).transpose(), options.byte_shapes);
      part = Fit(left, WorstPart(left.row(worst_key).transpose()), options.byte_shapes);
    }
    Candidate& key = part.error < row.error ? part : row;
    const bool take_pca = pca.error <= key.error;
    Candidate& chosen = take_pca ? pca : key;
    if (!std::isfinite(chosen.error)) break;  // nothing left to carry
    if (take_pca) --next_eigen;
    left.noalias() -= chosen.weight * chosen.shape.transpose();
    out.shapes.push_back(std::move(chosen.shape));
    out.weights.push_back(std::move(chosen.weight));
  }
  return out;
}

}  // namespace

Correctives FitCorrectives(const Skeleton& skeleton, const SkinInfluences& influences,
                           const BaseVertices& base, const BakedAnimation& bake, const SkinFit& fit,
                           const CorrectiveOptions& options) {
  const std::size_t keys = bake.KeyCount(), vertices = base.Count();
  const auto rows = static_cast<Eigen::Index>(keys);
  const auto columns = static_cast<Eigen::Index>(3 * vertices);
  const Eigen::MatrixXd residuals =
      Eigen::Map<const RowMatrixf>(fit.residual_positions.data(), rows, columns).cast<double>();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(residuals * residuals.transpose());
  // PCA alone reaches the target with the fewest shapes when it can; when it cannot within
  // max_shapes, the mixed choice is kept if it leaves a smaller worst error.
  Selection selection = Select(residuals, eigen, options, /*mixed=*/false);
  if (selection.error > options.max_error) {
    Selection mixed = Select(residuals, eigen, options, /*mixed=*/true);
    if (mixed.error < selection.error) selection = std::move(mixed);
  }
  Correctives out;
  out.shape_count = selection.shapes.size();
  for (const Eigen::VectorXd& shape : selection.shapes)
    for (Eigen::Index c = 0; c < columns; ++c) out.positions.push_back(float(shape(c)));
  const std::vector<Eigen::VectorXd>& weights = selection.weights;
  const std::size_t shapes = out.shape_count;
  out.byte_shapes = options.byte_shapes;
  if (options.delta_bits > 0 && !options.byte_shapes)
    RoundLikeExpFilter(out.positions, 3, options.delta_bits);
  out.weights.assign(keys * shapes, 0.0f);
  for (std::size_t s = 0; s < shapes; ++s)
    for (std::size_t k = 0; k < keys; ++k)
      out.weights[k * shapes + s] = static_cast<float>(weights[s](static_cast<Eigen::Index>(k)));

  // The error as a reader computes it: float shapes and weights, skinned.
  double sum_squares = 0.0;
  for (std::size_t k = 0; k < keys; ++k) {
    const std::vector<Mat4d> skin = SkinMatrices(skeleton, k);
    for (std::size_t v = 0; v < vertices; ++v) {
      Vec3 p = Eigen::Map<const Eigen::Vector3f>(&base.positions[v * 3]).cast<double>();
      for (std::size_t s = 0; s < shapes; ++s) {
        p += double(out.weights[k * shapes + s]) *
             Eigen::Map<const Eigen::Vector3f>(&out.positions[(s * vertices + v) * 3])
                 .cast<double>();
      }
      const Mat4d m = BlendedSkinMatrix(influences, skin, v);
      const Vec3 skinned = m.topLeftCorner<3, 3>() * p + m.topRightCorner<3, 1>();
      const double error = (skinned - bake.positions[k * vertices + v].cast<double>()).norm();
      out.max_error = std::max(out.max_error, error);
      sum_squares += error * error;
    }
  }
  out.rms_error = std::sqrt(sum_squares / double(std::max<std::size_t>(1, keys * vertices)));
  return out;
}

}  // namespace wirerig::gltf
