// Tests for the procedural meshes: closed and consistently oriented (every directed edge once,
// its reverse once), Euler characteristic, vertices exactly on the analytic surface, outward
// smooth normals, and the divergence-theorem volume equal to the exact volume of the inscribed
// polyhedron (regular n-gon frusta; for the torus, Pappus for n-gon wedges), whose distance to
// the analytic volume is bounded by the polygon-area deficit 1 - n sin(2 pi / n) / 2 pi
// <= (2 pi / n)^2 / 6.
#include "wirerig/procedural/shapes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr double kPi = std::numbers::pi;

// Area of the regular n-gon inscribed in the unit circle.
double PolygonArea(int n) { return 0.5 * n * std::sin(2.0 * kPi / n); }
// Bound on the relative area deficit of the inscribed regular n-gon.
double DeficitBound(int n) { return std::pow(2.0 * kPi / n, 2) / 6.0; }

// Signed volume by the divergence theorem.
double Volume(const Mesh& mesh) {
  double six_volume = 0.0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

// Closed, consistently oriented, no degenerate triangles, welding and parts as documented;
// returns the Euler characteristic V - E + F.
int CheckTopology(const Mesh& mesh, const std::string& name) {
  const std::size_t v_count = mesh.positions.size();
  EXPECT_EQ(mesh.normals.size(), v_count);
  EXPECT_TRUE(mesh.uvs.empty());
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  std::vector<int> valence(v_count, 0);
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(t[k], v_count);
      if (t[k] >= v_count) return 0;
      ++valence[t[k]];
      ++directed[{t[k], t[(k + 1) % 3]}];
    }
    EXPECT_TRUE(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]);
    const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    EXPECT_GT((b - a).cross(c - a).norm(), 1e-6 * (b - a).norm() * (c - a).norm());
  }
  int bad = 0;
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) ++bad;
  }
  EXPECT_EQ(bad, 0) << "edges used other than once in each direction";
  for (std::size_t v = 0; v < v_count; ++v) EXPECT_GT(valence[v], 0) << "unused vertex " << v;

  for (std::size_t v = 0; v < v_count; ++v) {
    const Vec3& p = mesh.positions[v];
    const Vec3& n = mesh.normals[v];
    EXPECT_TRUE(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()));
    EXPECT_TRUE(std::isfinite(n.x()) && std::isfinite(n.y()) && std::isfinite(n.z()));
    EXPECT_NEAR(n.norm(), 1.0, 1e-12);
  }
  EXPECT_EQ(mesh.welded_positions, mesh.positions);
  EXPECT_EQ(mesh.welded_triangles, mesh.triangles);
  EXPECT_EQ(mesh.weld_map.size(), v_count);
  for (std::size_t v = 0; v < mesh.weld_map.size(); ++v) EXPECT_EQ(mesh.weld_map[v], v);
  EXPECT_EQ(mesh.parts.size(), 1u);
  if (mesh.parts.size() == 1) {
    EXPECT_EQ(mesh.parts[0].name, name);
    EXPECT_EQ(mesh.parts[0].first_triangle, 0u);
    EXPECT_EQ(mesh.parts[0].triangle_count, mesh.triangles.size());
  }
  return static_cast<int>(v_count) - static_cast<int>(directed.size() / 2) +
         static_cast<int>(mesh.triangles.size());
}

// The volume of the inscribed polyhedron, and a check against it and the analytic volume.
void CheckVolume(const Mesh& mesh, double polyhedron, double analytic, double bound) {
  const double volume = Volume(mesh);
  EXPECT_NEAR(volume, polyhedron, 1e-12 * analytic);
  EXPECT_LE(volume, analytic);  // inscribed in a convex (or, for the torus, swept) solid
  EXPECT_LE(analytic - volume, bound);
}

// Normals point away from the axis point (convex meshes) or the core circle (torus).
void CheckOutwardNormals(const Mesh& mesh, auto&& centre_of) {
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3 centre = centre_of(mesh.positions[v]);
    EXPECT_GT(mesh.normals[v].dot(mesh.positions[v] - centre), 0.0) << "vertex " << v;
  }
}

double Radial(const Vec3& p) { return std::hypot(p.x(), p.z()); }

struct Segments {
  int radial, height;
};

TEST(ProceduralMeshTest, Cylinder) {
  const double r = 0.7, h = 1.9;
  for (const Segments s : {Segments{3, 1}, Segments{8, 2}, Segments{32, 5}, Segments{100, 1}}) {
    const Mesh mesh = MakeCylinder(r, h, s.radial, s.height);
    SCOPED_TRACE(::testing::Message() << s.radial << " x " << s.height);
    EXPECT_EQ(mesh.positions.size(), std::size_t(s.radial * (s.height + 1) + 2));
    EXPECT_EQ(mesh.triangles.size(), std::size_t(2 * s.radial * (s.height + 1)));
    EXPECT_EQ(CheckTopology(mesh, "cylinder"), 2);
    int on_axis = 0;
    for (const Vec3& p : mesh.positions) {
      const bool axis = p.x() == 0.0 && p.z() == 0.0;
      on_axis += axis;
      if (!axis) {
        EXPECT_NEAR(Radial(p), r, 1e-12);
      }
      EXPECT_GE(p.y(), 0.0);
      EXPECT_LE(p.y(), h);
      EXPECT_TRUE(axis || s.height != 1 || p.y() == 0.0 || p.y() == h);
    }
    EXPECT_EQ(on_axis, 2);  // the two cap centres
    const double analytic = kPi * r * r * h;
    CheckVolume(mesh, PolygonArea(s.radial) * r * r * h, analytic,
                analytic * DeficitBound(s.radial));
    CheckOutwardNormals(mesh, [&](const Vec3&) { return Vec3(0.0, 0.5 * h, 0.0); });
  }
  // The first ring starts at +X and runs counter-clockwise seen from +Y.
  const Mesh mesh = MakeCylinder(1.0, 1.0, 4, 1);
  EXPECT_EQ(mesh.positions[1], Vec3(1.0, 0.0, -0.0));
  EXPECT_NEAR((mesh.positions[2] - Vec3(0.0, 0.0, -1.0)).norm(), 0.0, 1e-15);
}

TEST(ProceduralMeshTest, ConeFrustumAndPointedCones) {
  const double h = 1.3;
  for (const auto& [r0, r1] :
       {std::pair{0.9, 0.4}, std::pair{0.3, 0.8}, std::pair{0.9, 0.0}, std::pair{0.0, 0.6}}) {
    for (const Segments s : {Segments{3, 1}, Segments{12, 3}, Segments{48, 4}}) {
      SCOPED_TRACE(::testing::Message()
                   << "r0 " << r0 << " r1 " << r1 << ", " << s.radial << " x " << s.height);
      const Mesh mesh = MakeCone(r0, r1, h, s.radial, s.height);
      const bool pointed = r0 == 0.0 || r1 == 0.0;
      // A pointed end is one apex vertex (no cap, no ring of coincident vertices).
      EXPECT_EQ(mesh.positions.size(),
                std::size_t(pointed ? s.radial * s.height + 2 : s.radial * (s.height + 1) + 2));
      EXPECT_EQ(mesh.triangles.size(),
                std::size_t(pointed ? 2 * s.radial * s.height : 2 * s.radial * (s.height + 1)));
      EXPECT_EQ(CheckTopology(mesh, "cone"), 2);
      for (const Vec3& p : mesh.positions) {
        if (p.x() == 0.0 && p.z() == 0.0) {
          EXPECT_TRUE(p.y() == 0.0 || p.y() == h);
          continue;
        }
        EXPECT_NEAR(Radial(p), r0 + (r1 - r0) * p.y() / h, 1e-12);
      }
      const double analytic = kPi * h * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0;
      CheckVolume(mesh, PolygonArea(s.radial) * h * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0, analytic,
                  analytic * DeficitBound(s.radial));
      CheckOutwardNormals(mesh, [&](const Vec3&) { return Vec3(0.0, 0.4 * h, 0.0); });
    }
  }
}

TEST(ProceduralMeshTest, Torus) {
  const double major = 1.2, minor = 0.3;
  for (const Segments s : {Segments{3, 3}, Segments{16, 8}, Segments{64, 24}}) {
    const int rings = s.radial, tube = s.height;
    SCOPED_TRACE(::testing::Message() << rings << " x " << tube);
    const Mesh mesh = MakeTorus(major, minor, rings, tube);
    EXPECT_EQ(mesh.positions.size(), std::size_t(rings * tube));
    EXPECT_EQ(mesh.triangles.size(), std::size_t(2 * rings * tube));
    EXPECT_EQ(CheckTopology(mesh, "torus"), 0);
    for (const Vec3& p : mesh.positions)
      EXPECT_NEAR(std::hypot(Radial(p) - major, p.y()), minor, 1e-12);
    // Ring k at angle 2 pi k / rings from +X (counter-clockwise seen from +Y), its first vertex
    // on the outer equator.
    for (int k = 0; k < rings; ++k) {
      const double phi = 2.0 * kPi * k / rings;
      const Vec3 expected = (major + minor) * Vec3(std::cos(phi), 0.0, -std::sin(phi));
      EXPECT_NEAR((mesh.positions[std::size_t(k * tube)] - expected).norm(), 0.0, 1e-15);
    }
    // n-gon wedges of an m-gon tube: Pappus with the wedge's chord factor n sin(2 pi / n).
    const double analytic = 2.0 * kPi * kPi * major * minor * minor;
    const double polyhedron = 2.0 * PolygonArea(rings) * major * PolygonArea(tube) * minor * minor;
    CheckVolume(mesh, polyhedron, analytic, analytic * (DeficitBound(rings) + DeficitBound(tube)));
    CheckOutwardNormals(mesh, [&](const Vec3& p) -> Vec3 {
      return Vec3(p.x(), 0.0, p.z()) * (major / Radial(p));  // nearest core-circle point
    });
  }
}

TEST(ProceduralMeshTest, Capsule) {
  const double r = 0.4;
  for (const double h : {0.0, 1.1}) {
    for (const auto& [s, cap_rings] : {std::pair{Segments{3, 1}, 1}, std::pair{Segments{12, 2}, 3},
                                       std::pair{Segments{40, 3}, 10}}) {
      SCOPED_TRACE(::testing::Message() << "h " << h << ", " << s.radial << " x " << s.height
                                        << ", cap rings " << cap_rings);
      const Mesh mesh = MakeCapsule(r, h, s.radial, s.height, cap_rings);
      const int body = h > 0.0 ? s.height : 0;
      const int rings = 2 * (cap_rings - 1) + body + 1;
      EXPECT_EQ(mesh.positions.size(), std::size_t(s.radial * rings + 2));
      EXPECT_EQ(mesh.triangles.size(), std::size_t(2 * s.radial * rings));
      EXPECT_EQ(CheckTopology(mesh, "capsule"), 2);
      int poles = 0;
      for (const Vec3& p : mesh.positions) {
        // Distance to the axis segment y in [0, h] is the radius.
        const double y = std::clamp(p.y(), 0.0, h);
        EXPECT_NEAR((p - Vec3(0.0, y, 0.0)).norm(), r, 1e-12);
        if (p.x() == 0.0 && p.z() == 0.0) {
          ++poles;
          EXPECT_TRUE(p.y() == -r || p.y() == h + r);
        }
      }
      EXPECT_EQ(poles, 2);
      // Each hemisphere: cap_rings n-gon frusta between latitudes pi/2 * l / cap_rings.
      double cap = 0.0;
      for (int l = 0; l < cap_rings; ++l) {
        const double a0 = 0.5 * kPi * l / cap_rings, a1 = 0.5 * kPi * (l + 1) / cap_rings;
        const double r0 = r * std::cos(a0), r1 = l + 1 == cap_rings ? 0.0 : r * std::cos(a1);
        cap += r * (std::sin(a1) - std::sin(a0)) * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0;
      }
      const double analytic = kPi * r * r * h + 4.0 / 3.0 * kPi * r * r * r;
      // The meridian quarter-disc loses at most pi r^2 / 4 * deficit(4 cap_rings) of area,
      // at most 2 pi r from the axis (Pappus).
      const double bound = analytic * DeficitBound(s.radial) +
                           2.0 * kPi * kPi * r * r * r / 2.0 * DeficitBound(4 * cap_rings);
      CheckVolume(mesh, PolygonArea(s.radial) * (r * r * h + 2.0 * cap), analytic, bound);
      CheckOutwardNormals(mesh, [&](const Vec3&) { return Vec3(0.0, 0.5 * h, 0.0); });
    }
  }
}

TEST(ProceduralMeshTest, VolumeConvergesQuadratically) {
  // Doubling the segments divides the volume error by about 4.
  const double analytic = 2.0 * kPi * kPi * 1.0 * 0.25 * 0.25;
  const double e1 = analytic - Volume(MakeTorus(1.0, 0.25, 32, 16));
  const double e2 = analytic - Volume(MakeTorus(1.0, 0.25, 64, 32));
  EXPECT_NEAR(e1 / e2, 4.0, 0.1);
  const double c_analytic = kPi * 0.5 * 0.5 * 2.0;
  const double c1 = c_analytic - Volume(MakeCylinder(0.5, 2.0, 32, 1));
  const double c2 = c_analytic - Volume(MakeCylinder(0.5, 2.0, 64, 1));
  EXPECT_NEAR(c1 / c2, 4.0, 0.1);
}

TEST(ProceduralMeshTest, SegmentCountsAreClampedToMinimums) {
  const Mesh cylinder = MakeCylinder(1.0, 1.0, 0, -5);
  EXPECT_EQ(cylinder.triangles.size(), MakeCylinder(1.0, 1.0, 3, 1).triangles.size());
  EXPECT_EQ(CheckTopology(cylinder, "cylinder"), 2);
  const Mesh cone = MakeCone(1.0, 0.0, 1.0, 2, 0);
  EXPECT_EQ(cone.triangles.size(), MakeCone(1.0, 0.0, 1.0, 3, 1).triangles.size());
  EXPECT_EQ(CheckTopology(cone, "cone"), 2);
  const Mesh torus = MakeTorus(1.0, 0.5, 1, 2);
  EXPECT_EQ(torus.triangles.size(), 18u);
  EXPECT_EQ(CheckTopology(torus, "torus"), 0);
  const Mesh capsule = MakeCapsule(1.0, 1.0, 1, 0, 0);
  EXPECT_EQ(capsule.triangles.size(), MakeCapsule(1.0, 1.0, 3, 1, 1).triangles.size());
  EXPECT_EQ(CheckTopology(capsule, "capsule"), 2);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
