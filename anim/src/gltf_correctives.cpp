#include "gltf_correctives.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "gltf_buffers.h"
#include "gltf_meshopt.h"

namespace wirerig::gltf {
namespace {

using RowMatrixf = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The largest |row segment (3v .. 3v + 3)| over the rows and vertices of `m` (#K x 3#V).
double MaxVertexNorm(const Eigen::MatrixXd& m) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < m.rows(); ++k)
    for (Eigen::Index i = 0; i + 2 < m.cols(); i += 3)
      worst = std::max(worst, Vec3(m(k, i), m(k, i + 1), m(k, i + 2)).squaredNorm());
  return std::sqrt(worst);
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

  Correctives out;
  Eigen::MatrixXd left = residuals;  // what the shapes so far do not carry
  std::vector<Eigen::VectorXd> weights;
  const double largest = eigen.eigenvalues()(rows - 1);
  while (out.shape_count < std::min<std::size_t>(options.max_shapes, keys) &&
         MaxVertexNorm(left) > options.max_error) {
    const Eigen::Index i = rows - 1 - static_cast<Eigen::Index>(out.shape_count);
    const double lambda = eigen.eigenvalues()(i);
    if (!(lambda > 1e-14 * largest)) break;  // nothing left to carry
    const Eigen::VectorXd u = eigen.eigenvectors().col(i);
    Eigen::VectorXd shape = residuals.transpose() * u / std::sqrt(lambda);
    Eigen::VectorXd weight = u * std::sqrt(lambda);
    if (options.byte_shapes) {
      const double largest_component = shape.cwiseAbs().maxCoeff();
      if (!(largest_component > 0.0)) break;
      shape = (shape * (kByteScale / largest_component)).array().round() / kByteScale;
      weight = left * shape / shape.squaredNorm();
    }
    left.noalias() -= weight * shape.transpose();
    for (Eigen::Index c = 0; c < columns; ++c) out.positions.push_back(float(shape(c)));
    weights.push_back(weight);
    ++out.shape_count;
  }
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
