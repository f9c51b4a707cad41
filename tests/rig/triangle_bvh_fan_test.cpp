// TriangleBvh::RaycastFan against Raycast, ray by ray: every ray of a fan must get Raycast's
// nearest hit exactly (same t; the same triangle, u, v and point, or, where two triangles give
// exactly that t, a point equal to rounding). Random origins and planes on a torus, capsule and
// cone; rays exactly through the vertices and edges of a gridded cube (watertightness: every
// ray from inside hits); skewed and scaled frames; origins outside or far away; tiny meshes
// and a soup with degenerate triangles (short leaves, repeated slots).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/triangle_bvh.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr double kPi = std::numbers::pi;

struct Fixture {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  TriangleBvh bvh;
  void Build() { bvh = TriangleBvh::Build(positions, triangles); }
};

Fixture FromMesh(const Mesh& mesh) {
  Fixture f;
  f.positions = mesh.welded_positions;
  f.triangles = mesh.welded_triangles;
  f.Build();
  return f;
}

// The cube [-1, 1]^3, each face a k x k grid of squares split into two triangles: vertices
// at multiples of 2 / k, exactly representable for k a power of two.
Fixture GriddedCube(int k) {
  Fixture f;
  auto vertex = [&](const Vec3& p) {
    f.positions.push_back(p);
    return static_cast<std::uint32_t>(f.positions.size() - 1);
  };
  for (int axis = 0; axis < 3; ++axis) {
    for (const double side : {-1.0, 1.0}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i < k; ++i) {
        for (int j = 0; j < k; ++j) {
          std::uint32_t corner[4];
          for (int c = 0; c < 4; ++c) {
            Vec3 p;
            p[axis] = side;
            p[u] = -1.0 + 2.0 * (i + (c == 1 || c == 2)) / k;
            p[v] = -1.0 + 2.0 * (j + (c >= 2)) / k;
            corner[c] = vertex(p);
          }
          f.triangles.push_back({corner[0], corner[1], corner[2]});
          f.triangles.push_back({corner[0], corner[2], corner[3]});
        }
      }
    }
  }
  f.Build();
  return f;
}

// Compares the fan with ray-by-ray Raycast; returns the number of hits.
std::size_t ExpectFanMatchesRays(const Fixture& f, const Vec3& origin, const Vec3& normal,
                                 const Vec3& binormal, const std::vector<double>& cosines,
                                 const std::vector<double>& sines) {
  std::vector<std::optional<RayHit>> fan(cosines.size());
  f.bvh.RaycastFan(origin, normal, binormal, cosines, sines, fan);
  std::size_t hits = 0;
  for (std::size_t j = 0; j < fan.size(); ++j) {
    const Vec3 direction = cosines[j] * normal + sines[j] * binormal;
    const std::optional<RayHit> ray =
        f.bvh.Raycast(origin, direction, 0.0, std::numeric_limits<double>::max());
    EXPECT_EQ(fan[j].has_value(), ray.has_value()) << "ray " << j << " of " << fan.size();
    if (!ray || !fan[j]) continue;
    ++hits;
    EXPECT_EQ(fan[j]->t, ray->t) << "ray " << j << " of " << fan.size();
    if (fan[j]->triangle == ray->triangle) {
      EXPECT_EQ(fan[j]->u, ray->u);
      EXPECT_EQ(fan[j]->v, ray->v);
      EXPECT_EQ(fan[j]->point, ray->point);
    } else {
      // Two triangles at exactly the same t: the ray passes through their shared edge.
      EXPECT_LT((fan[j]->point - ray->point).norm(), 1e-14 * (1.0 + ray->t * direction.norm()));
    }
  }
  return hits;
}

// n rays at 2 pi j / n.
void EvenFan(int n, std::vector<double>& cosines, std::vector<double>& sines) {
  cosines.resize(static_cast<std::size_t>(n));
  sines.resize(cosines.size());
  for (int j = 0; j < n; ++j) {
    cosines[std::size_t(j)] = std::cos(2.0 * kPi * j / n);
    sines[std::size_t(j)] = std::sin(2.0 * kPi * j / n);
  }
}

struct Random {
  std::uint64_t state;
  double Uniform() {  // in [-1, 1)
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) * 0x1p-52 - 1.0;
  }
  Vec3 Unit() { return Vec3(Uniform(), Uniform(), Uniform()).normalized(); }
};

TEST(RaycastFan, MatchesRaycastFromRandomOriginsAndPlanes) {
  std::vector<Fixture> shapes;
  shapes.push_back(FromMesh(MakeTorus(0.5, 0.1, 48, 24)));
  shapes.push_back(FromMesh(MakeCapsule(0.1, 1.0, 16, 12, 4)));
  shapes.push_back(FromMesh(MakeCone(0.3, 0.05, 1.0, 12, 3)));
  Random random{2024};
  std::vector<double> cosines, sines;
  std::size_t hits = 0;
  for (const Fixture& shape : shapes) {
    for (int trial = 0; trial < 40; ++trial) {
      const Vec3 origin(0.6 * random.Uniform(), 0.5 + 0.6 * random.Uniform(),
                        0.6 * random.Uniform());
      const Vec3 axis = random.Unit();
      const Vec3 normal = axis.unitOrthogonal();
      const Vec3 binormal = axis.cross(normal);
      for (int n : {3, 7, 33, 100, 101, 257, 512}) {
        EvenFan(n, cosines, sines);
        hits += ExpectFanMatchesRays(shape, origin, normal, binormal, cosines, sines);
      }
    }
  }
  EXPECT_GT(hits, 15000u);
}

TEST(RaycastFan, MatchesRaycastWithSkewedFramesAndUnevenAngles) {
  const Fixture torus = FromMesh(MakeTorus(0.5, 0.1, 48, 24));
  Random random{77};
  std::size_t hits = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Vec3 origin(0.5 * random.Uniform(), 0.2 * random.Uniform(), 0.5 * random.Uniform());
    // Neither unit nor orthogonal (but not parallel).
    const Vec3 normal = 3.0 * random.Unit();
    const Vec3 binormal = 0.25 * (random.Unit() + 0.3 * normal);
    // Increasing angles with uneven gaps; cosines and sines not of unit length.
    std::vector<double> cosines, sines;
    const double first = 2.0 * kPi * (0.5 + 0.5 * random.Uniform());
    double angle = first;
    for (int j = 0; j < 90 && angle < first + 1.98 * kPi; ++j) {
      const double scale = 1.5 + random.Uniform();
      cosines.push_back(scale * std::cos(angle));
      sines.push_back(scale * std::sin(angle));
      angle += 2.0 * kPi / 90.0 * (0.2 + 0.75 * (1.0 + random.Uniform()));
    }
    hits += ExpectFanMatchesRays(torus, origin, normal, binormal, cosines, sines);
  }
  EXPECT_GT(hits, 1000u);
}

TEST(RaycastFan, RaysThroughGridVerticesAndEdgesAllHit) {
  const Fixture cube = GriddedCube(4);
  // Directions (c, s) with small integer components: from the centre in an axis plane, each
  // ray meets the cube exactly on a grid vertex or edge (its hit coordinates are multiples of
  // 1/4, the grid's spacing 1/2 in those coordinates).
  std::vector<double> cosines, sines;
  for (int q = 0; q < 4; ++q) {
    const int steps[][2] = {{2, 0}, {2, 1}, {1, 1}, {1, 2}};
    for (const auto& step : steps) {
      double c = step[0], s = step[1];
      for (int r = 0; r < q; ++r) {  // rotate by quarter turns
        const double t = c;
        c = -s;
        s = t;
      }
      cosines.push_back(c);
      sines.push_back(s);
    }
  }
  const Vec3 x = Vec3::UnitX(), y = Vec3::UnitY(), z = Vec3::UnitZ();
  struct Plane {
    Vec3 origin, normal, binormal;
  };
  const std::vector<Plane> planes = {
      {Vec3(0, 0, 0), x, y},         {Vec3(0, 0, 0), y, z},         {Vec3(0, 0, 0), z, x},
      {Vec3(0, 0, 0.5), x, y},       {Vec3(0.5, 0, 0), y, z},       {Vec3(0, 0, -0.5), y, x},
      {Vec3(0, 0, 0), x + y, z},     {Vec3(0, 0, 0), x - y, x + y}, {Vec3(0.5, 0.5, 0), x, y},
      {Vec3(0, 0, 0), x + y + z, z}, {Vec3(0.25, -0.5, 0.5), x, y},
  };
  for (const Plane& plane : planes) {
    const std::size_t hits =
        ExpectFanMatchesRays(cube, plane.origin, plane.normal, plane.binormal, cosines, sines);
    EXPECT_EQ(hits, cosines.size()) << "origin " << plane.origin.transpose();
  }
  // Even fans through the grid lines too, at many ray counts.
  for (int n : {8, 16, 24, 48, 96}) {
    EvenFan(n, cosines, sines);
    for (const Plane& plane : planes)
      EXPECT_EQ(
          ExpectFanMatchesRays(cube, plane.origin, plane.normal, plane.binormal, cosines, sines),
          cosines.size());
  }
}

TEST(RaycastFan, RaysThroughTheVertexRingsOfATorusAllHit) {
  // The torus's vertex rings lie in planes through its axis: a fan in such a plane from a point
  // of the core circle, with as many rays as the tube has segments (and multiples), passes
  // through (or within rounding of) the ring's vertices.
  const int tube = 24;
  const Fixture torus = FromMesh(MakeTorus(0.5, 0.1, 48, tube));
  std::vector<double> cosines, sines;
  for (int ring = 0; ring < 48; ring += 5) {
    const double phi = 2.0 * kPi * ring / 48;
    const Vec3 radial(std::cos(phi), 0.0, std::sin(phi));
    for (int n : {tube, 2 * tube, 3 * tube}) {
      EvenFan(n, cosines, sines);
      EXPECT_EQ(ExpectFanMatchesRays(torus, 0.5 * radial, radial, Vec3::UnitY(), cosines, sines),
                cosines.size());
    }
  }
}

TEST(RaycastFan, OriginsOutsideFarAwayAndOnTheSurface) {
  const Fixture capsule = FromMesh(MakeCapsule(0.1, 1.0, 16, 12, 4));
  Random random{5};
  std::vector<double> cosines, sines;
  EvenFan(100, cosines, sines);
  for (const double distance : {0.3, 2.0, 50.0, 1e6}) {
    for (int trial = 0; trial < 8; ++trial) {
      // Aim the fan's plane through the capsule so that rays hit.
      const Vec3 target(0.05 * random.Uniform(), 0.5 + 0.4 * random.Uniform(),
                        0.05 * random.Uniform());
      const Vec3 origin = target + distance * random.Unit();
      const Vec3 normal = (target - origin).normalized();
      const Vec3 binormal = normal.cross(random.Unit()).normalized();
      ExpectFanMatchesRays(capsule, origin, normal, binormal, cosines, sines);
    }
  }
  // Origins exactly on vertices of the surface.
  for (std::size_t i = 0; i < capsule.positions.size(); i += 37) {
    const Vec3 axis = random.Unit();
    ExpectFanMatchesRays(capsule, capsule.positions[i], axis.unitOrthogonal(),
                         axis.cross(axis.unitOrthogonal()), cosines, sines);
  }
}

TEST(RaycastFan, TinyMeshesAndDegenerateTriangles) {
  Random random{99};
  // One triangle; two triangles sharing an edge; a soup with collinear (degenerate) triangles,
  // whose leaves hold fewer than four triangles.
  std::vector<Fixture> fixtures(3);
  fixtures[0].positions = {Vec3(1, -1, -1), Vec3(1, 1, -1), Vec3(1, 0, 1)};
  fixtures[0].triangles = {{0, 1, 2}};
  fixtures[1].positions = {Vec3(1, -1, -1), Vec3(1, 1, -1), Vec3(1, 1, 1), Vec3(1, -1, 1)};
  fixtures[1].triangles = {{0, 1, 2}, {0, 2, 3}};
  for (int i = 0; i < 60; ++i) {
    const Vec3 centre(random.Uniform(), random.Uniform(), random.Uniform());
    const Vec3 a = centre + 0.3 * random.Unit(), b = centre + 0.3 * random.Unit();
    const auto base = static_cast<std::uint32_t>(fixtures[2].positions.size());
    fixtures[2].positions.push_back(a);
    fixtures[2].positions.push_back(b);
    // Every fifth triangle collinear: its third vertex halfway between the others.
    fixtures[2].positions.push_back(i % 5 == 0 ? Vec3(0.5 * (a + b))
                                               : Vec3(centre + 0.3 * random.Unit()));
    fixtures[2].triangles.push_back({base, base + 1, base + 2});
  }
  for (Fixture& f : fixtures) f.Build();
  std::vector<double> cosines, sines;
  std::size_t hits = 0;
  for (const Fixture& f : fixtures) {
    for (int trial = 0; trial < 40; ++trial) {
      const Vec3 origin = 0.5 * Vec3(random.Uniform(), random.Uniform(), random.Uniform());
      const Vec3 axis = random.Unit();
      for (int n : {5, 64, 200}) {
        EvenFan(n, cosines, sines);
        hits += ExpectFanMatchesRays(f, origin, axis.unitOrthogonal(),
                                     axis.cross(axis.unitOrthogonal()), cosines, sines);
      }
    }
  }
  EXPECT_GT(hits, 100u);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
