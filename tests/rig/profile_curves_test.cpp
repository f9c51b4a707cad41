// Profile and spine curves on procedural primitives with known cross-sections: profiles are
// circles of the known radius (1e-6 relative) and the spine is the axis. The primitives have
// 4096 radial segments, so a cut through a vertex ring is a 4096-gon whose radius differs from
// the circle's by at most 1 - cos(pi/4096) = 2.9e-7.
#include "wirerig/rig/profile_curves.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/spine_curves.h"
#include "wirerig/rig/triangle_bvh.h"
#include "wirerig/runtime/parallel.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr double kPi = std::numbers::pi;
constexpr int kRadial = 4096;

struct Primitive {
  Mesh mesh;
  TriangleBvh bvh;
  explicit Primitive(Mesh m) : mesh(std::move(m)) {
    bvh = TriangleBvh::Build(mesh.welded_positions, mesh.welded_triangles);
  }
};

Curve MakeCurve(std::vector<Vec3> points, bool closed = false) {
  Curve curve;
  const auto interpolation =
      points.size() >= 3 ? CurveInterpolation::kCubic : CurveInterpolation::kLinear;
  EXPECT_TRUE(Curve::Build(points, closed, interpolation, &curve).ok());
  return curve;
}

ProfileSet Profiles(const Primitive& primitive, const Curve& central, int count, int rays) {
  ProfileRequest request;
  request.central_curve = &central;
  request.profile_count = count;
  request.points_per_profile = rays;
  request.part_bvh = &primitive.bvh;
  return GenerateProfiles(request);
}

double RadialDistance(const Vec3& p) { return std::hypot(p.x(), p.z()); }

TEST(ProfileCurves, CylinderProfilesAreCirclesAndTheSpineIsTheAxis) {
  const double r = 0.2, h = 1.0;
  const Primitive cylinder(MakeCylinder(r, h, kRadial, 4));
  const Curve axis = MakeCurve({Vec3(0, 0, 0), Vec3(0, h, 0)});
  const ProfileSet set = Profiles(cylinder, axis, 9, 32);
  ASSERT_EQ(set.profiles.size(), 9u);
  EXPECT_EQ(set.diagnostics.rays, 9u * 32u);
  EXPECT_EQ(set.diagnostics.misses, 0u);
  EXPECT_EQ(set.diagnostics.self_intersecting, 0u);
  EXPECT_EQ(set.diagnostics.crossing_neighbour, 0u);
  for (std::size_t k = 0; k < set.profiles.size(); ++k) {
    const ProfileCurve& profile = set.profiles[k];
    EXPECT_TRUE(profile.closed);
    EXPECT_DOUBLE_EQ(profile.v, double(k + 1) / 10.0);
    ASSERT_EQ(profile.points.size(), 32u);
    for (const Vec3& p : profile.points) {
      EXPECT_NEAR(RadialDistance(p), r, 1e-6 * r);
      EXPECT_NEAR(p.y(), profile.v * h, 1e-12);  // in the plane normal to the axis
    }
    const Vec3 centroid = ProfileCentroid(profile);
    EXPECT_NEAR(RadialDistance(centroid), 0.0, 1e-6 * r);
    EXPECT_NEAR(centroid.y(), profile.v * h, 1e-12);
  }
}

TEST(ProfileCurves, RoughCentralCurveIsRecentred) {
  // The central curve runs parallel to the axis, 6 cm off it: re-centring finds the axis.
  const double r = 0.2, h = 1.0;
  const Primitive cylinder(MakeCylinder(r, h, kRadial, 4));
  const Curve rough = MakeCurve({Vec3(0.06, 0, -0.02), Vec3(0.06, h, -0.02)});
  const ProfileSet set = Profiles(cylinder, rough, 5, 48);
  ASSERT_EQ(set.profiles.size(), 5u);
  for (const ProfileCurve& profile : set.profiles) {
    EXPECT_NEAR(RadialDistance(profile.origin), 0.0, 1e-6 * r);
    for (const Vec3& p : profile.points) EXPECT_NEAR(RadialDistance(p), r, 1e-6 * r);
  }
  // Without re-centring the origin stays where the rough curve put it.
  ProfileRequest request;
  request.central_curve = &rough;
  request.profile_count = 5;
  request.points_per_profile = 48;
  request.part_bvh = &cylinder.bvh;
  request.recentre_passes = 0;
  const ProfileSet raw = GenerateProfiles(request);
  EXPECT_NEAR(RadialDistance(raw.profiles[0].origin), std::hypot(0.06, 0.02), 1e-12);
}

TEST(ProfileCurves, ConeProfilesHaveTheLinearlyVaryingRadius) {
  const double r0 = 0.3, r1 = 0.1, h = 1.2;
  const Primitive cone(MakeCone(r0, r1, h, kRadial, 1));
  const Curve axis = MakeCurve({Vec3(0, 0, 0), Vec3(0, h, 0)});
  const ProfileSet set = Profiles(cone, axis, 7, 24);
  ASSERT_EQ(set.profiles.size(), 7u);
  for (const ProfileCurve& profile : set.profiles) {
    const double expected = r0 + (r1 - r0) * profile.v;
    for (const Vec3& p : profile.points) EXPECT_NEAR(RadialDistance(p), expected, 1e-6 * expected);
    EXPECT_NEAR(RadialDistance(ProfileCentroid(profile)), 0.0, 1e-6 * expected);
  }
}

TEST(ProfileCurves, TorusProfilesAreTubeCirclesAroundTheCore) {
  // The central curve is the core circle, periodic through 64 points at ring angles; with
  // 15 profiles (16 equal segments) every interface point is one of those points, where the
  // cut plane contains a vertex ring of the torus.
  const double major = 0.5, minor = 0.1;
  const Primitive torus(MakeTorus(major, minor, 512, kRadial));
  std::vector<Vec3> core;
  for (int k = 0; k < 64; ++k) {
    const double a = 2.0 * kPi * k / 64;
    core.emplace_back(major * std::cos(a), 0.0, major * std::sin(a));
  }
  const Curve central = MakeCurve(core, /*closed=*/true);
  const ProfileSet set = Profiles(torus, central, 15, 24);
  ASSERT_EQ(set.profiles.size(), 15u);
  EXPECT_EQ(set.diagnostics.misses, 0u);
  for (const ProfileCurve& profile : set.profiles) {
    EXPECT_TRUE(profile.closed);
    const Vec3 centroid = ProfileCentroid(profile);
    EXPECT_NEAR(RadialDistance(centroid), major, 1e-6 * minor);
    EXPECT_NEAR(centroid.y(), 0.0, 1e-6 * minor);
    for (const Vec3& p : profile.points) {
      const Vec3 core_point = major * Vec3(p.x(), 0, p.z()).normalized();
      EXPECT_NEAR((p - core_point).norm(), minor, 1e-6 * minor);
    }
  }
}

TEST(ProfileCurves, CapsuleBodyProfilesAreCircles) {
  const double r = 0.15, h = 0.8;
  const Primitive capsule(MakeCapsule(r, h, kRadial, 8, 32));
  const Curve axis = MakeCurve({Vec3(0, 0, 0), Vec3(0, h, 0)});
  const ProfileSet set = Profiles(capsule, axis, 7, 24);
  ASSERT_EQ(set.profiles.size(), 7u);
  for (const ProfileCurve& profile : set.profiles)
    for (const Vec3& p : profile.points) EXPECT_NEAR(RadialDistance(p), r, 1e-6 * r);
  Result<Curve> spine = BuildSpineCurve(SpinePoints(set.profiles, set.foreign_points));
  ASSERT_TRUE(spine.ok()) << spine.error();
  for (int i = 0; i <= 20; ++i)
    EXPECT_NEAR(RadialDistance(spine.value().Position(i / 20.0)), 0.0, 1e-6 * r);
  // The spine runs from the first to the last profile's centre, along +Y.
  EXPECT_NEAR(spine.value().length(), h * (7.0 - 1.0) / 8.0, 1e-9);
  EXPECT_NEAR(spine.value().Tangent(0.5).y(), 1.0, 1e-9);
}

TEST(ProfileCurves, OpenSurfaceGivesOpenProfilesAndCountsMisses) {
  // A cylinder without its triangles on one side (x > 0.1): rays towards +x miss.
  Mesh mesh = MakeCylinder(0.2, 1.0, 256, 4);
  std::vector<std::uint32_t> kept;
  for (std::uint32_t f = 0; f < mesh.welded_triangles.size(); ++f) {
    const Triangle& t = mesh.welded_triangles[f];
    const Vec3 c =
        (mesh.welded_positions[t[0]] + mesh.welded_positions[t[1]] + mesh.welded_positions[t[2]]) /
        3.0;
    if (c.x() < 0.1) kept.push_back(f);
  }
  const TriangleBvh open = TriangleBvh::Build(mesh.welded_positions, mesh.welded_triangles, kept);
  const Curve axis = MakeCurve({Vec3(0, 0, 0), Vec3(0, 1, 0)});
  ProfileRequest request;
  request.central_curve = &axis;
  request.profile_count = 3;
  request.points_per_profile = 36;
  request.part_bvh = &open;
  const ProfileSet set = GenerateProfiles(request);
  ASSERT_EQ(set.profiles.size(), 3u);
  EXPECT_EQ(set.diagnostics.open_profiles, 3u);
  EXPECT_GT(set.diagnostics.misses, 0u);
  EXPECT_EQ(set.diagnostics.rays, 3u * 36u);
  for (const ProfileCurve& profile : set.profiles) {
    EXPECT_FALSE(profile.closed);
    EXPECT_LT(profile.points.size(), 36u);
    for (const Vec3& p : profile.points) EXPECT_LT(p.x(), 0.1 + 1e-9);
  }
}

TEST(ProfileCurves, CentroidOfAnOpenProfileIsTheMeanOfItsPoints) {
  ProfileCurve open;
  open.closed = false;
  open.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)};
  EXPECT_TRUE(ProfileCentroid(open).isApprox(Vec3(2.0 / 3.0, 1.0 / 3.0, 0)));
  // A closed square with uneven point spacing: the area centroid is its centre, not the mean.
  ProfileCurve square;
  square.closed = true;
  square.frame.tangent = Vec3::UnitZ();
  square.points = {Vec3(0, 0, 0), Vec3(0.5, 0, 0), Vec3(0.75, 0, 0),
                   Vec3(1, 0, 0), Vec3(1, 1, 0),   Vec3(0, 1, 0)};
  EXPECT_LT((ProfileCentroid(square) - Vec3(0.5, 0.5, 0)).norm(), 1e-15);
}

void ExpectSameSet(const ProfileSet& a, const ProfileSet& b) {
  ASSERT_EQ(a.profiles.size(), b.profiles.size());
  EXPECT_EQ(a.foreign_points, b.foreign_points);
  for (std::size_t k = 0; k < a.profiles.size(); ++k) {
    EXPECT_EQ(a.profiles[k].v, b.profiles[k].v);
    EXPECT_EQ(a.profiles[k].origin, b.profiles[k].origin);
    EXPECT_EQ(a.profiles[k].closed, b.profiles[k].closed);
    EXPECT_EQ(a.profiles[k].points, b.profiles[k].points);
  }
  const ProfileDiagnostics &d = a.diagnostics, &e = b.diagnostics;
  EXPECT_EQ(d.rays, e.rays);
  EXPECT_EQ(d.misses, e.misses);
  EXPECT_EQ(d.other_part_hits, e.other_part_hits);
  EXPECT_EQ(d.open_profiles, e.open_profiles);
  EXPECT_EQ(d.empty_profiles, e.empty_profiles);
  EXPECT_EQ(d.self_intersecting, e.self_intersecting);
  EXPECT_EQ(d.crossing_neighbour, e.crossing_neighbour);
  EXPECT_EQ(d.outside_profiles, e.outside_profiles);
}

TEST(ProfileCurves, ThreadsAndBatchesGiveIdenticalSets) {
  // A torus around a rough core (re-centring at work), an open half cylinder (misses, open
  // profiles) and a cone whose central curve leaves it (outside and empty profiles).
  const Primitive torus(MakeTorus(0.5, 0.1, 128, 256));
  std::vector<Vec3> core;
  for (int k = 0; k < 16; ++k) {
    const double a = 2.0 * kPi * k / 16;
    core.emplace_back((0.5 + 0.02 * std::sin(3 * a)) * std::cos(a), 0.01,
                      (0.5 + 0.02 * std::sin(3 * a)) * std::sin(a));
  }
  const Curve torus_core = MakeCurve(core, /*closed=*/true);
  Mesh half = MakeCylinder(0.2, 1.0, 64, 8);
  std::vector<Triangle> kept;
  for (const Triangle& t : half.welded_triangles)
    if (half.welded_positions[t[0]].x() <= 0.0 && half.welded_positions[t[1]].x() <= 0.0 &&
        half.welded_positions[t[2]].x() <= 0.0)
      kept.push_back(t);
  half.welded_triangles = kept;
  const Primitive open(std::move(half));
  const Curve open_axis = MakeCurve({Vec3(0, 0, 0), Vec3(0, 1, 0)});
  const Primitive cone(MakeCone(0.3, 0.0, 1.0, 64, 8));
  const Curve leaving = MakeCurve({Vec3(0, 0.1, 0), Vec3(0.1, 0.6, 0), Vec3(0.6, 1.2, 0)});

  std::vector<ProfileRequest> requests(3);
  const Primitive* primitives[3] = {&torus, &open, &cone};
  const Curve* curves[3] = {&torus_core, &open_axis, &leaving};
  const int counts[3] = {23, 9, 11};
  for (std::size_t i = 0; i < 3; ++i) {
    requests[i].central_curve = curves[i];
    requests[i].profile_count = counts[i];
    requests[i].points_per_profile = 40;
    requests[i].part_bvh = &primitives[i]->bvh;
    requests[i].positions = primitives[i]->mesh.welded_positions;
    requests[i].triangles = primitives[i]->mesh.welded_triangles;
  }
  std::vector<ProfileSet> sequential;
  for (const ProfileRequest& request : requests) sequential.push_back(GenerateProfiles(request));
  EXPECT_GT(sequential[1].diagnostics.open_profiles, 0u);
  for (std::size_t threads : {1u, 2u, 3u}) {
    const ThreadPool pool(threads);
    const std::vector<ProfileSet> batched = GenerateProfiles(requests, &pool);
    ASSERT_EQ(batched.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
      ExpectSameSet(batched[i], sequential[i]);
      ProfileRequest request = requests[i];
      request.parallel = &pool;
      ExpectSameSet(GenerateProfiles(request), sequential[i]);
    }
  }
  const std::vector<ProfileSet> unthreaded = GenerateProfiles(requests, nullptr);
  for (std::size_t i = 0; i < 3; ++i) ExpectSameSet(unthreaded[i], sequential[i]);
}

// RaycastFan against Raycast ray by ray: the same hits and t (exactly), and the same point to
// rounding (exactly when the same triangle is reported), from random origins in random planes
// and from origins whose rays pass exactly through vertices and edges.
void ExpectFanMatchesRays(const TriangleBvh& bvh, const Vec3& origin, const Vec3& normal,
                          const Vec3& binormal, int n, double scale, std::size_t* hits_seen) {
  std::vector<double> cosines(static_cast<std::size_t>(n)), sines(cosines.size());
  for (int j = 0; j < n; ++j) {
    cosines[std::size_t(j)] = std::cos(2.0 * kPi * j / n);
    sines[std::size_t(j)] = std::sin(2.0 * kPi * j / n);
  }
  std::vector<std::optional<RayHit>> fan(cosines.size());
  bvh.RaycastFan(origin, normal, binormal, cosines, sines, fan);
  for (std::size_t j = 0; j < fan.size(); ++j) {
    const Vec3 direction = cosines[j] * normal + sines[j] * binormal;
    const std::optional<RayHit> ray =
        bvh.Raycast(origin, direction, 0.0, std::numeric_limits<double>::max());
    ASSERT_EQ(fan[j].has_value(), ray.has_value()) << "ray " << j << " of " << n;
    if (!ray) continue;
    ++*hits_seen;
    EXPECT_EQ(fan[j]->t, ray->t) << "ray " << j << " of " << n;
    if (fan[j]->triangle == ray->triangle) {
      EXPECT_EQ(fan[j]->point, ray->point);
    } else {
      EXPECT_LT((fan[j]->point - ray->point).norm(), 1e-14 * scale);
    }
  }
}

TEST(ProfileCurves, RaycastFanFindsWhatRaycastFinds) {
  std::vector<Primitive> meshes;
  meshes.emplace_back(MakeTorus(0.5, 0.1, 48, 24));
  meshes.emplace_back(MakeCapsule(0.1, 1.0, 16, 12, 4));
  meshes.emplace_back(MakeCone(0.3, 0.05, 1.0, 12, 3));
  std::uint64_t state = 12345;
  auto uniform = [&state] {  // in [-1, 1)
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) * 0x1p-52 - 1.0;
  };
  std::size_t hits_seen = 0;
  for (const Primitive& primitive : meshes) {
    for (int trial = 0; trial < 60; ++trial) {
      const Vec3 origin(0.6 * uniform(), 0.5 + 0.6 * uniform(), 0.6 * uniform());
      const Vec3 axis = Vec3(uniform(), uniform(), uniform()).normalized();
      const Vec3 normal = axis.unitOrthogonal();
      const Vec3 binormal = axis.cross(normal);
      for (int n : {3, 8, 20, 64, 100, 257})
        ExpectFanMatchesRays(primitive.bvh, origin, normal, binormal, n, 1.0, &hits_seen);
    }
  }
  // Rays through vertices and along edges: the capsule's axis origin at a vertex ring's height,
  // in the ring's plane, with as many rays as the ring has vertices (and twice as many).
  const Primitive capsule(MakeCapsule(0.1, 1.0, 16, 12, 4));
  for (const Vec3& p : capsule.mesh.welded_positions) {
    if (!(p.y() > 0.05 && p.y() < 0.95)) continue;
    for (int n : {16, 32, 48})
      ExpectFanMatchesRays(capsule.bvh, Vec3(0, p.y(), 0), Vec3(p.x(), 0, p.z()).normalized(),
                           Vec3(p.x(), 0, p.z()).normalized().cross(Vec3::UnitY()), n, 1.0,
                           &hits_seen);
    break;
  }
  EXPECT_GT(hits_seen, 10000u);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
