#include "gltf_correctives.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>
#include <utility>

#include <Eigen/Eigenvalues>

#include "gltf_buffers.h"
#include "gltf_meshopt.h"
#include "wirerig/runtime/parallel.h"

namespace wirerig::gltf {
namespace {

using RowMatrixf = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The largest |row segment (3v .. 3v + 3)| of `m` - `weight` `shape`^T (#K x 3#V), over the rows
// and vertices, and the row where it lies. Column blocks at a time (`m` is column-major).
double MaxVertexNorm(const Eigen::MatrixXd& m, const Eigen::VectorXd* weight = nullptr,
                     const Eigen::VectorXd* shape = nullptr, Eigen::Index* worst_row = nullptr) {
  double worst = 0.0;
  Eigen::MatrixXd block(m.rows(), 3);
  for (Eigen::Index i = 0; i + 2 < m.cols(); i += 3) {
    block = m.middleCols<3>(i);
    if (shape != nullptr) block.noalias() -= *weight * shape->segment<3>(i).transpose();
    Eigen::Index row = 0;
    const double largest = block.rowwise().squaredNorm().maxCoeff(&row);
    if (largest > worst) {
      worst = largest;
      if (worst_row != nullptr) *worst_row = row;
    }
  }
  return std::sqrt(worst);
}

// residuals diag(column_weight) residuals^T (column_weight empty: all 1), its lower half: strips
// of kGramStrips rows on `pool`, each strip's entries computed whole by one task (no partial
// sums: the same bits on any number of threads, and no memory beyond the #K x #K result and a
// strip of weighted rows per thread).
constexpr std::size_t kGramStrips = 16;
Eigen::MatrixXd WeightedGram(const Eigen::MatrixXd& residuals, const Eigen::VectorXd& column_weight,
                             const ParallelFor& pool) {
  const Eigen::Index rows = residuals.rows();
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(rows, rows);
  RunEach(&pool, kGramStrips, [&](std::size_t b) {
    const Eigen::Index begin = rows * Eigen::Index(b) / Eigen::Index(kGramStrips);
    const Eigen::Index end = rows * Eigen::Index(b + 1) / Eigen::Index(kGramStrips);
    if (end <= begin) return;
    Eigen::MatrixXd strip = residuals.middleRows(begin, end - begin);
    if (column_weight.size() > 0) strip *= column_weight.asDiagonal();
    gram.block(begin, 0, end - begin, end).noalias() = strip * residuals.topRows(end).transpose();
  });
  return gram;
}

// A candidate shape (unit length, or bytes), its least-squares weights per key against what the
// shapes so far leave (`left`), and the worst vertex error it leaves.
struct Candidate {
  Eigen::VectorXd shape, weight;
  double error = std::numeric_limits<double>::infinity();
  Eigen::Index worst_key = 0;  // where the error lies
};

// `column_weight` (3#V, or empty: all 1): each column's weight in the least-squares fit of the
// shape's weights per key.
Candidate Fit(const Eigen::MatrixXd& left, Eigen::VectorXd shape, bool byte_shapes,
              const Eigen::VectorXd& column_weight) {
  Candidate c;
  const double norm = shape.norm();
  if (!(norm > 0.0) || !std::isfinite(norm)) return c;
  shape /= norm;
  if (byte_shapes) {
    const double largest_component = shape.cwiseAbs().maxCoeff();
    shape = (shape * (kByteScale / largest_component)).array().round() / kByteScale;
    if (!(shape.squaredNorm() > 0.0)) return c;
  }
  if (column_weight.size() == 0) {
    c.weight = left * shape / shape.squaredNorm();
  } else {
    const Eigen::VectorXd weighted = column_weight.cwiseProduct(shape);
    const double denominator = weighted.dot(shape);
    if (!(denominator > 0.0)) return c;
    c.weight = left * weighted / denominator;
  }
  c.shape = std::move(shape);
  c.error = MaxVertexNorm(left, &c.weight, &c.shape, &c.worst_key);
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
  double error = 0.0;            // worst vertex error left, m
  Eigen::VectorXd vertex_error;  // #V: each vertex's worst error left over the keys, m
};

// `eigen`: of residuals diag(column_weight) residuals^T (column_weight empty: all 1).
Selection Select(const Eigen::MatrixXd& residuals,
                 const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& eigen,
                 const CorrectiveOptions& options, bool mixed,
                 const Eigen::VectorXd& column_weight) {
  const Eigen::Index rows = residuals.rows();
  Selection out;
  Eigen::MatrixXd left = residuals;  // what the shapes so far do not carry
  const double largest = eigen.eigenvalues()(rows - 1);
  Eigen::Index next_eigen = rows - 1;  // the largest eigenvalue not yet taken
  Eigen::Index worst_key = 0;
  out.error = MaxVertexNorm(left, nullptr, nullptr, &worst_key);
  while (out.error > options.max_error &&
         out.shapes.size() < std::min<std::size_t>(options.max_shapes, std::size_t(rows))) {
    Candidate pca;
    if (next_eigen >= 0 && eigen.eigenvalues()(next_eigen) > 1e-14 * largest)
      pca = Fit(left, residuals.transpose() * eigen.eigenvectors().col(next_eigen),
                options.byte_shapes, column_weight);
    // The worst key's residual whole, or near its worst vertex only.
    Candidate row, part;
    if (mixed) {
      row = Fit(left, left.row(worst_key).transpose(), options.byte_shapes, column_weight);
      part =
          Fit(left, WorstPart(left.row(worst_key).transpose()), options.byte_shapes, column_weight);
    }
    Candidate& key = part.error < row.error ? part : row;
    const bool take_pca = pca.error <= key.error;
    Candidate& chosen = take_pca ? pca : key;
    if (!std::isfinite(chosen.error)) break;  // nothing left to carry
    if (take_pca) --next_eigen;
    left.noalias() -= chosen.weight * chosen.shape.transpose();
    out.error = chosen.error, worst_key = chosen.worst_key;
    out.shapes.push_back(std::move(chosen.shape));
    out.weights.push_back(std::move(chosen.weight));
  }
  out.vertex_error = Eigen::VectorXd::Zero(left.cols() / 3);
  for (Eigen::Index v = 0; v < out.vertex_error.size(); ++v)
    out.vertex_error(v) = left.middleCols<3>(3 * v).rowwise().norm().maxCoeff();
  return out;
}

// The first `count` principal shapes of the weighted residuals (`eigen` of residuals
// diag(column_weight) residuals^T): each X^T u_i, unit (or bytes), with their weights per key
// by weighted least squares over all of them at once (for float shapes these are the u_i
// themselves up to scale: the shapes are orthogonal in the weights). One pass of products
// rather than Select's passes per shape, by vertex blocks on `pool` (kVertexBlocks), sums in block
// order.
constexpr std::size_t kVertexBlocks = 16;
Selection Project(const Eigen::MatrixXd& residuals,
                  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& eigen, std::size_t count,
                  bool byte_shapes, const Eigen::VectorXd& column_weight, const ParallelFor& pool) {
  const Eigen::Index rows = residuals.rows(), vertices = residuals.cols() / 3;
  const Eigen::Index k = std::min<Eigen::Index>(Eigen::Index(count), rows);
  // Vertex blocks: the products below by column blocks on `pool`, sums in block order.
  auto columns_of = [&](std::size_t b) {
    const Eigen::Index begin = vertices * Eigen::Index(b) / Eigen::Index(kVertexBlocks);
    const Eigen::Index end = vertices * Eigen::Index(b + 1) / Eigen::Index(kVertexBlocks);
    return std::pair{3 * begin, 3 * (end - begin)};
  };
  const Eigen::MatrixXd u = eigen.eigenvectors().rightCols(k).rowwise().reverse();  // largest first
  Eigen::MatrixXd shapes(k, residuals.cols());                                      // k x 3#V
  RunEach(&pool, kVertexBlocks, [&](std::size_t b) {
    const auto [begin, size] = columns_of(b);
    shapes.middleCols(begin, size).noalias() = u.transpose() * residuals.middleCols(begin, size);
  });
  Eigen::Index kept = 0;
  for (Eigen::Index s = 0; s < k; ++s) {
    const double norm = shapes.row(s).norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) break;
    shapes.row(kept) = shapes.row(s) / norm;
    if (byte_shapes)
      shapes.row(kept) = (shapes.row(kept) * (kByteScale / shapes.row(kept).cwiseAbs().maxCoeff()))
                             .array()
                             .round() /
                         kByteScale;
    ++kept;
  }
  shapes.conservativeResize(kept, Eigen::NoChange);
  // Weighted least squares for all the weights at once: normal = S W S^T, right = S W X^T.
  std::vector<Eigen::MatrixXd> normals(kVertexBlocks), rights(kVertexBlocks);
  RunEach(&pool, kVertexBlocks, [&](std::size_t b) {
    const auto [begin, size] = columns_of(b);
    const Eigen::MatrixXd weighted =
        shapes.middleCols(begin, size) * column_weight.segment(begin, size).asDiagonal();
    normals[b] = weighted * shapes.middleCols(begin, size).transpose();
    rights[b] = weighted * residuals.middleCols(begin, size).transpose();
  });
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(kept, kept),
                  right = Eigen::MatrixXd::Zero(kept, rows);
  for (std::size_t b = 0; b < kVertexBlocks; ++b) normal += normals[b], right += rights[b];
  normal.diagonal().array() += 1e-12 * normal.diagonal().cwiseAbs().maxCoeff() + 1e-300;
  const Eigen::MatrixXd weights = normal.ldlt().solve(right).transpose();  // #K x k
  Selection out;
  out.vertex_error = Eigen::VectorXd::Zero(vertices);
  RunEach(&pool, kVertexBlocks, [&](std::size_t b) {
    const auto [begin, size] = columns_of(b);
    Eigen::MatrixXd left = residuals.middleCols(begin, size);
    left.noalias() -= weights * shapes.middleCols(begin, size);
    for (Eigen::Index i = 0; i < size; i += 3)
      out.vertex_error((begin + i) / 3) = left.middleCols<3>(i).rowwise().norm().maxCoeff();
  });
  for (Eigen::Index s = 0; s < kept; ++s) {
    out.shapes.push_back(shapes.row(s).transpose());
    out.weights.push_back(weights.col(s));
  }
  out.error = vertices > 0 ? out.vertex_error.maxCoeff() : 0.0;
  return out;
}

// Each vertex's shape entries refined toward the smallest worst error over the keys, the
// shapes' weights per key held: a vertex's error depends on its own entries only, so each
// vertex the selection leaves above kRefineShare of the target gets Lawson's reweighting over
// the keys (least squares with weights per key, each round's weights times the errors they
// left) until it is within that share, keeping its best entries. Byte shapes' entries stay
// multiples of 1 / 127 in [-1, 1]. Vertices run in parallel on `pool` (each writes its own).
constexpr double kRefineShare = 0.8;
constexpr int kVertexRounds = 24;
void RefineVertices(const Eigen::MatrixXd& residuals, const CorrectiveOptions& options,
                    const ParallelFor& pool, Selection* selection) {
  const Eigen::Index keys = residuals.rows(), shapes = Eigen::Index(selection->shapes.size());
  if (shapes == 0) return;
  Eigen::MatrixXd a(keys, shapes);
  for (Eigen::Index s = 0; s < shapes; ++s) a.col(s) = selection->weights[std::size_t(s)];
  auto worst = [&](const Eigen::MatrixXd& x, const Eigen::MatrixXd& b, Eigen::VectorXd* errors) {
    *errors = (x - a * b).rowwise().norm();
    return errors->maxCoeff();
  };
  std::vector<Eigen::Index> refined;
  for (Eigen::Index v = 0; v < selection->vertex_error.size(); ++v)
    if (selection->vertex_error(v) > kRefineShare * options.max_error) refined.push_back(v);
  RunEach(&pool, refined.size(), [&](std::size_t r) {
    const Eigen::Index v = refined[r];
    const Eigen::MatrixXd x = residuals.middleCols(3 * v, 3);
    Eigen::MatrixXd best(shapes, 3);
    for (Eigen::Index s = 0; s < shapes; ++s)
      best.row(s) = selection->shapes[std::size_t(s)].segment<3>(3 * v).transpose();
    Eigen::VectorXd errors;
    double best_error = worst(x, best, &errors);
    Eigen::VectorXd key_weight = Eigen::VectorXd::Ones(keys);
    for (int round = 0; round < kVertexRounds && best_error > kRefineShare * options.max_error;
         ++round) {
      const double mean = errors.cwiseProduct(key_weight).mean();
      if (!(mean > 0.0) || !std::isfinite(mean)) break;
      key_weight = key_weight.cwiseProduct(errors) / mean;
      const Eigen::MatrixXd weighted = key_weight.asDiagonal() * a;
      Eigen::MatrixXd normal = weighted.transpose() * a;
      normal.diagonal().array() += 1e-12 * normal.diagonal().maxCoeff() + 1e-300;
      Eigen::MatrixXd b = normal.ldlt().solve(weighted.transpose() * x);
      if (options.byte_shapes)
        b = (b * kByteScale).array().round().cwiseMax(-kByteScale).cwiseMin(kByteScale) /
            kByteScale;
      if (!b.allFinite()) break;
      const double error = worst(x, b, &errors);
      if (error < best_error) best_error = error, best = b;
    }
    for (Eigen::Index s = 0; s < shapes; ++s)
      selection->shapes[std::size_t(s)].segment<3>(3 * v) = best.row(s).transpose();
    selection->vertex_error(v) = best_error;
  });
  selection->error = selection->vertex_error.size() > 0 ? selection->vertex_error.maxCoeff() : 0.0;
}

// Rounds of Lawson's reweighting in SelectMinimax, and the least weight of a vertex (the mean
// is 1). Each round solves a #K x #K eigenproblem, so clips of more than kMinimaxKeys keys get
// the per-vertex refinement only.
constexpr int kMinimaxRounds = 12;
constexpr Eigen::Index kMinimaxKeys = 1024;
constexpr double kLeastVertexWeight = 1e-3;

// The selection with the smallest worst error found by Lawson's iteratively reweighted least
// squares, each candidate then refined per vertex (RefineVertices): PCA minimises the squared
// error summed over the vertices, the target bounds the worst one. Each round weights every
// vertex's columns by its weight so far times the square root of the worst error the last
// round left it (normalised to mean 1; the plain product overshoots and alternates) and selects
// again on the weighted residuals. Stops once a refined candidate meets the target.
Selection SelectMinimax(const Eigen::MatrixXd& residuals, const CorrectiveOptions& options,
                        Selection start, const ParallelFor& pool) {
  const Eigen::Index columns = residuals.cols();
  Selection best = start;
  RefineVertices(residuals, options, pool, &best);
  Eigen::VectorXd vertex_weight = Eigen::VectorXd::Ones(columns / 3);
  Selection last = std::move(start);
  const int rounds = residuals.rows() <= kMinimaxKeys ? kMinimaxRounds : 0;
  for (int round = 0; round < rounds && best.error > options.max_error; ++round) {
    vertex_weight = vertex_weight.cwiseProduct(last.vertex_error.cwiseSqrt());
    const double mean = vertex_weight.mean();
    if (!(mean > 0.0) || !std::isfinite(mean)) break;
    // A vertex the last round fitted exactly keeps a little weight (it would keep none).
    vertex_weight = (vertex_weight / mean).cwiseMax(kLeastVertexWeight);
    Eigen::VectorXd column_weight(columns);
    for (Eigen::Index c = 0; c < columns; ++c) column_weight(c) = vertex_weight(c / 3);
    // The solver reads the lower half.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(
        WeightedGram(residuals, column_weight, pool));
    last = Project(residuals, eigen, options.max_shapes, options.byte_shapes, column_weight, pool);
    Selection refined = last;
    RefineVertices(residuals, options, pool, &refined);
    if (refined.error < best.error) best = std::move(refined);
  }
  return best;
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
  const ThreadPool pool(std::max(1u, std::thread::hardware_concurrency()));
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(
      WeightedGram(residuals, Eigen::VectorXd(), pool));
  // PCA alone reaches the target with the fewest shapes when it can; when it cannot within
  // max_shapes, the mixed choice is kept if it leaves a smaller worst error.
  const Eigen::VectorXd unweighted;
  Selection selection = Select(residuals, eigen, options, /*mixed=*/false, unweighted);
  if (selection.error > options.max_error) {
    Selection mixed = Select(residuals, eigen, options, /*mixed=*/true, unweighted);
    if (mixed.error < selection.error) selection = std::move(mixed);
    selection = SelectMinimax(residuals, options, std::move(selection), pool);
  }
  // Once the target is met, fewer shapes may meet it too when their entries aim at the worst
  // vertex.
  for (std::size_t shapes = selection.shapes.size();
       selection.error <= options.max_error && shapes > 1; --shapes) {
    CorrectiveOptions fewer = options;
    fewer.max_shapes = shapes - 1;
    Selection candidate = SelectMinimax(
        residuals, fewer, Select(residuals, eigen, fewer, /*mixed=*/false, unweighted), pool);
    if (candidate.error > options.max_error) break;
    selection = std::move(candidate);
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
