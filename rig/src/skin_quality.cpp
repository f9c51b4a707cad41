#include "wirerig/rig/skin_quality.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace wirerig {
namespace {

constexpr double kSmoothCos = 0.5;   // cos 60 degrees
constexpr double kFoldedCos = -0.5;  // cos 120 degrees
// A border vertex within this fraction of the rest surface's bounding diagonal of its rest
// place has stayed put (rounding of an evaluation that did not move it).
constexpr double kStillFraction = 1e-9;

Vec3 TriangleNormal(std::span<const Vec3> p, const Triangle& t) {
  return (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
}

// cos of the angle between two vectors; 1 when either vanishes (no fold is measurable).
double CosBetween(const Vec3& a, const Vec3& b) {
  const double n = a.norm() * b.norm();
  return n > 0.0 ? a.dot(b) / n : 1.0;
}

}  // namespace

SkinQualityReference MakeSkinQualityReference(std::span<const Vec3> rest,
                                              std::span<const Triangle> triangles) {
  SkinQualityReference out;
  out.triangles = triangles;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> index;
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = triangles[f][k], b = triangles[f][(k + 1) % 3];
      const auto key = std::minmax(a, b);
      const auto [it, added] = index.emplace(key, out.edges.size());
      if (added) {
        SkinQualityReference::Edge edge;
        edge.a = key.first;
        edge.b = key.second;
        edge.left = edge.right = std::uint32_t(f);
        edge.rest_length = (rest[a] - rest[b]).norm();
        out.edges.push_back(edge);
      } else {
        out.edges[it->second].right = std::uint32_t(f);
      }
    }
  for (SkinQualityReference::Edge& edge : out.edges)
    edge.smooth = edge.left != edge.right &&
                  CosBetween(TriangleNormal(rest, triangles[edge.left]),
                             TriangleNormal(rest, triangles[edge.right])) > kSmoothCos;
  return out;
}

SkinQuality MeasureSkin(const SkinQualityReference& reference, std::span<const Vec3> positions,
                        std::span<const std::uint8_t> only) {
  SkinQuality out;
  for (const SkinQualityReference::Edge& edge : reference.edges) {
    if (!only.empty() && !(only[edge.a] && only[edge.b])) continue;
    if (edge.rest_length > 0.0)
      out.worst_stretch = std::max(
          out.worst_stretch, (positions[edge.a] - positions[edge.b]).norm() / edge.rest_length);
    if (edge.smooth &&
        CosBetween(TriangleNormal(positions, reference.triangles[edge.left]),
                   TriangleNormal(positions, reference.triangles[edge.right])) < kFoldedCos)
      ++out.folded_edges;
  }
  return out;
}

double RegionVolume(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                    std::span<const std::uint8_t> flagged, const Vec3& apex) {
  double six = 0.0;
  for (const Triangle& t : triangles) {
    if (!(flagged[t[0]] && flagged[t[1]] && flagged[t[2]])) continue;
    six += (positions[t[0]] - apex).dot((positions[t[1]] - apex).cross(positions[t[2]] - apex));
  }
  return six / 6.0;
}

std::vector<std::uint32_t> SurfaceBorder(std::span<const Triangle> triangles) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(3 * triangles.size());
  for (const Triangle& t : triangles)
    for (std::size_t k = 0; k < 3; ++k) edges.push_back(std::minmax(t[k], t[(k + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  std::vector<std::uint32_t> border;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i != 2) border.insert(border.end(), {edges[i].first, edges[i].second});
    i = j;
  }
  std::sort(border.begin(), border.end());
  border.erase(std::unique(border.begin(), border.end()), border.end());
  return border;
}

std::optional<double> SurfaceVolumeChange(std::span<const Vec3> rest, std::span<const Vec3> posed,
                                          std::span<const Triangle> triangles,
                                          std::span<const std::uint32_t> border) {
  if (rest.empty() || posed.size() != rest.size()) return std::nullopt;
  Vec3 low = rest.front(), high = low;
  for (const Vec3& p : rest) low = low.cwiseMin(p), high = high.cwiseMax(p);
  const double still = kStillFraction * (high - low).norm();
  for (std::uint32_t v : border)
    if (!((posed[v] - rest[v]).norm() <= still)) return std::nullopt;
  // The cones from one apex to every triangle: their volume changes by the enclosed volume's
  // change alone while the border (where caps of the holes would hang) stays.
  const Vec3 apex = rest.front();
  double six = 0.0;
  for (const Triangle& t : triangles) {
    six += (posed[t[0]] - apex).dot((posed[t[1]] - apex).cross(posed[t[2]] - apex));
    six -= (rest[t[0]] - apex).dot((rest[t[1]] - apex).cross(rest[t[2]] - apex));
  }
  return six / 6.0;
}

CrossSection MakeCrossSection(std::span<const Vec3> rest, const SkinQualityReference& reference,
                              const Vec3& point, const Vec3& normal, double radius) {
  const Vec3 x = normal.unitOrthogonal(), y = normal.cross(x);
  std::vector<std::pair<double, CrossSection::Cut>> cuts;
  for (const SkinQualityReference::Edge& edge : reference.edges) {
    const Vec3 &a = rest[edge.a], &b = rest[edge.b];
    if ((a - point).norm() > radius || (b - point).norm() > radius) continue;
    const double da = (a - point).dot(normal), db = (b - point).dot(normal);
    if ((da < 0.0) == (db < 0.0) || da == db) continue;
    const double t = da / (da - db);
    const Vec3 c = (1.0 - t) * a + t * b - point;
    cuts.push_back({std::atan2(c.dot(y), c.dot(x)), {edge.a, edge.b, t}});
  }
  std::sort(cuts.begin(), cuts.end(),
            [](const auto& l, const auto& r) { return l.first < r.first; });
  CrossSection out;
  for (const auto& cut : cuts) out.cuts.push_back(cut.second);
  return out;
}

double CrossSectionPerimeter(const CrossSection& section, std::span<const Vec3> positions) {
  const std::size_t n = section.cuts.size();
  auto at = [&](std::size_t i) {
    const CrossSection::Cut& c = section.cuts[i % n];
    return Vec3((1.0 - c.t) * positions[c.a] + c.t * positions[c.b]);
  };
  double length = 0.0;
  for (std::size_t i = 0; i < n; ++i) length += (at(i + 1) - at(i)).norm();
  return length;
}

}  // namespace wirerig
