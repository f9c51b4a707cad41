// Welding render vertices by position, and bounds.
#include "wirerig/rig/mesh.h"

#include "wirerig/io/finite.h"
#include "wirerig/io/json_text.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace wirerig {
namespace {

// Bit pattern of a coordinate, with -0 folded onto +0 so that equal values get equal keys.
std::uint64_t CoordinateBits(double x) { return std::bit_cast<std::uint64_t>(x == 0.0 ? 0.0 : x); }

struct PositionKey {
  std::uint64_t x, y, z;
  bool operator==(const PositionKey&) const = default;
};

struct PositionKeyHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
    h ^= (k.y + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2));
    h ^= (k.z + 0x94D049BB133111EBull + (h << 6) + (h >> 2));
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
};

PositionKey KeyOf(const Vec3& p) {
  return {CoordinateBits(p.x()), CoordinateBits(p.y()), CoordinateBits(p.z())};
}

struct CellKey {
  std::int64_t x, y, z;
  bool operator==(const CellKey&) const = default;
};

struct CellKeyHash {
  std::size_t operator()(const CellKey& k) const {
    return PositionKeyHash{}(PositionKey{static_cast<std::uint64_t>(k.x),
                                         static_cast<std::uint64_t>(k.y),
                                         static_cast<std::uint64_t>(k.z)});
  }
};

// Exact welding: render vertices with bit-identical positions (after folding -0) merge.
void WeldExact(Mesh& mesh) {
  std::unordered_map<PositionKey, std::uint32_t, PositionKeyHash> index;
  index.reserve(mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3& p = mesh.positions[v];
    const auto [it, inserted] =
        index.try_emplace(KeyOf(p), static_cast<std::uint32_t>(mesh.welded_positions.size()));
    if (inserted) mesh.welded_positions.push_back(p);
    mesh.weld_map[v] = it->second;
  }
}

// Welding within `tolerance`: a grid of cells at least `tolerance` wide, so every welded
// vertex within reach of a position lies in the 27 cells around it. Render vertices are
// visited in order; each joins the lowest-numbered welded vertex within reach, else starts a
// new one. Non-finite positions are only merged with identical ones.
void WeldWithTolerance(Mesh& mesh, double tolerance) {
  // Cells no finer than 2^-40 of the largest coordinate, so cell indices fit in 64 bits.
  double max_abs = 0.0;
  for (const Vec3& p : mesh.positions) {
    if (!IsFinite(p)) continue;
    max_abs = std::max({max_abs, std::abs(p.x()), std::abs(p.y()), std::abs(p.z())});
  }
  const double tol = std::min(tolerance, 1e150);  // beyond this, squares would overflow
  const double cell = std::max(tol, std::ldexp(max_abs, -40));
  const double tol2 = tol * tol;

  std::unordered_map<CellKey, std::vector<std::uint32_t>, CellKeyHash> grid;
  std::unordered_map<PositionKey, std::uint32_t, PositionKeyHash> non_finite;
  grid.reserve(mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3& p = mesh.positions[v];
    if (!IsFinite(p)) {
      const auto [it, inserted] = non_finite.try_emplace(
          KeyOf(p), static_cast<std::uint32_t>(mesh.welded_positions.size()));
      if (inserted) mesh.welded_positions.push_back(p);
      mesh.weld_map[v] = it->second;
      continue;
    }
    const CellKey c{static_cast<std::int64_t>(std::floor(p.x() / cell)),
                    static_cast<std::int64_t>(std::floor(p.y() / cell)),
                    static_cast<std::int64_t>(std::floor(p.z() / cell))};
    std::uint32_t best = UINT32_MAX;
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find(CellKey{c.x + dx, c.y + dy, c.z + dz});
          if (it == grid.end()) continue;
          for (const std::uint32_t w : it->second) {
            if (w >= best) continue;
            const Vec3& q = mesh.welded_positions[w];
            // Per-component test first: neighbouring cells keep differences finite.
            const Vec3 d = p - q;
            if (std::abs(d.x()) > tol || std::abs(d.y()) > tol || std::abs(d.z()) > tol) continue;
            if (d.squaredNorm() <= tol2) best = w;
          }
        }
      }
    }
    if (best == UINT32_MAX) {
      best = static_cast<std::uint32_t>(mesh.welded_positions.size());
      mesh.welded_positions.push_back(p);
      grid[c].push_back(best);
    }
    mesh.weld_map[v] = best;
  }
}

}  // namespace

void WeldByPosition(Mesh& mesh, double tolerance) {
  mesh.weld_map.assign(mesh.positions.size(), 0);
  mesh.welded_positions.clear();
  mesh.welded_triangles.clear();
  // Negative or NaN tolerances mean exact welding.
  if (tolerance > 0.0) {
    WeldWithTolerance(mesh, tolerance);
  } else {
    WeldExact(mesh);
  }
  mesh.welded_triangles.reserve(mesh.triangles.size());
  const std::size_t v_count = mesh.positions.size();
  for (const Triangle& t : mesh.triangles) {
    Triangle w{};
    for (int k = 0; k < 3; ++k) {
      // An out-of-range index stays out of range (it cannot name a welded vertex).
      w[k] = t[k] < v_count ? mesh.weld_map[t[k]] : UINT32_MAX;
    }
    mesh.welded_triangles.push_back(w);
  }
}

Bounds ComputeBounds(const Mesh& mesh) {
  const std::vector<Vec3>& points =
      mesh.welded_positions.empty() ? mesh.positions : mesh.welded_positions;
  Bounds bounds;
  bool first = true;
  for (const Vec3& p : points) {
    if (!IsFinite(p)) continue;
    if (first) {
      bounds.min = p;
      bounds.max = p;
      first = false;
    } else {
      bounds.min = bounds.min.cwiseMin(p);
      bounds.max = bounds.max.cwiseMax(p);
    }
  }
  return bounds;
}

void MakeNamesUtf8(Mesh& mesh) {
  for (MeshPart& part : mesh.parts) part.name = ValidUtf8(part.name);
  for (MeshMaterial& material : mesh.materials) material.name = ValidUtf8(material.name);
  for (Joint& joint : mesh.joints) joint.name = ValidUtf8(joint.name);
}

}  // namespace wirerig
