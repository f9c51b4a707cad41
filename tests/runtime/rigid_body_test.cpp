// Rigid spine wires (PHYSICS.md section 7) against independent analytic references: box
// inertia (solid and thin shell, derived here face by face), the parallel-axis theorem,
// uniformly accelerated motion, spin-up about a principal axis, conservation laws of the
// torque-free body with the drift table's orders, and the closed-form precession of an
// axisymmetric body. Then determinism and input validation.
#include "wirerig/runtime/rigid_body.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr std::array kIntegrators = {RigidIntegrator::kRk4, RigidIntegrator::kMomentum};

const char* Name(RigidIntegrator integrator) {
  return integrator == RigidIntegrator::kRk4 ? "rk4" : "momentum";
}

double NaN() { return std::numeric_limits<double>::quiet_NaN(); }
double Inf() { return std::numeric_limits<double>::infinity(); }

// ---------------------------------------------------------------------------------------
// Meshes built here, independently of the code under test.

struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;

  void Append(const Mesh& other) {
    const auto offset = static_cast<std::uint32_t>(positions.size());
    positions.insert(positions.end(), other.positions.begin(), other.positions.end());
    for (const Triangle& t : other.triangles)
      triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  void Flip() {
    for (Triangle& t : triangles) std::swap(t[1], t[2]);
  }
};

// Corner index bit 0: +x, bit 1: +y, bit 2: +z. Each quad (a, b, c, d) runs counter-clockwise
// seen from outside: (b - a) x (d - a) points along the outward normal.
constexpr std::array<std::array<std::uint32_t, 4>, 6> kBoxQuads = {{
    {1, 3, 7, 5},  // +x
    {0, 4, 6, 2},  // -x
    {2, 6, 7, 3},  // +y
    {0, 1, 5, 4},  // -y
    {4, 5, 7, 6},  // +z
    {0, 2, 3, 1},  // -z
}};

Vec3 Corner(const Vec3& size, std::uint32_t i) {
  return 0.5 * Vec3((i & 1) ? size.x() : -size.x(), (i & 2) ? size.y() : -size.y(),
                    (i & 4) ? size.z() : -size.z());
}

// A closed, outward-facing box of the given size, rotated by `rotation` about its centre and
// placed at `center`. With `split_faces`, every face gets its own four vertices (as glTF
// meshes with per-face normals do); `skip_faces` leaves the first faces out (open box).
Mesh Box(const Vec3& size, const Mat3& rotation = Mat3::Identity(),
         const Vec3& center = Vec3::Zero(), bool split_faces = false, int skip_faces = 0) {
  Mesh mesh;
  if (!split_faces)
    for (std::uint32_t i = 0; i < 8; ++i)
      mesh.positions.push_back(center + rotation * Corner(size, i));
  for (int f = skip_faces; f < 6; ++f) {
    std::array<std::uint32_t, 4> q = kBoxQuads[f];
    if (split_faces) {
      for (std::uint32_t& i : q) {
        mesh.positions.push_back(center + rotation * Corner(size, i));
        i = static_cast<std::uint32_t>(mesh.positions.size() - 1);
      }
    }
    mesh.triangles.push_back({q[0], q[1], q[2]});
    mesh.triangles.push_back({q[0], q[2], q[3]});
  }
  return mesh;
}

// Every triangle's right-hand normal points away from `center` (valid for convex meshes).
void ExpectOutward(const Mesh& mesh, const Vec3& center) {
  for (const Triangle& t : mesh.triangles) {
    const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    EXPECT_GT((b - a).cross(c - a).dot((a + b + c) / 3.0 - center), 0.0);
  }
}

// Solid box l x w x h, mass m: I = m/12 diag(w^2 + h^2, l^2 + h^2, l^2 + w^2).
Mat3 SolidBoxInertia(const Vec3& size, double mass) {
  const Vec3 s2 = size.cwiseProduct(size);
  return (mass / 12.0) * Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y()).asDiagonal();
}

// Thin-shell box (areal density sigma), derived face by face. For I_xx = sigma * integral of
// (y^2 + z^2) dA: the two faces normal to x (w x h rectangles through the centre) give
// A (w^2 + h^2)/12 each; the two faces normal to y (l x h at y = +-w/2) give A (w^2/4 + h^2/12)
// each; the two faces normal to z (l x w at z = +-h/2) give A (w^2/12 + h^2/4) each. The
// other axes follow by permuting (l, w, h).
double ShellMomentAboutFirstAxis(double l, double w, double h, double sigma) {
  const double yz_faces = w * h * (w * w + h * h) / 12.0;
  const double xz_faces = l * h * (w * w / 4.0 + h * h / 12.0);
  const double xy_faces = l * w * (w * w / 12.0 + h * h / 4.0);
  return 2.0 * sigma * (yz_faces + xz_faces + xy_faces);
}
Mat3 ShellBoxInertia(const Vec3& size, double sigma) {
  const double l = size.x(), w = size.y(), h = size.z();
  return Vec3(ShellMomentAboutFirstAxis(l, w, h, sigma), ShellMomentAboutFirstAxis(w, l, h, sigma),
              ShellMomentAboutFirstAxis(h, l, w, sigma))
      .asDiagonal();
}

Mat3 TestRotation() {
  return Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
}

MassProperties Solid(const Mesh& mesh, double density) {
  MassProperties mp;
  const Status status = ComputeSolidMassProperties(mesh.positions, mesh.triangles, density, &mp);
  EXPECT_TRUE(status.ok()) << ToString(status);
  return mp;
}

// Principal decomposition consistent with the inertia: R0 orthonormal, right-handed,
// R0 diag(I_b) R0^T = I, and moments ascending.
void ExpectPrincipalFrame(const MassProperties& mp, double tol) {
  const Mat3& r = mp.principal_axes;
  EXPECT_LT((r.transpose() * r - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  EXPECT_LT(
      (r * mp.principal_moments.asDiagonal() * r.transpose() - mp.inertia).cwiseAbs().maxCoeff(),
      tol);
  EXPECT_LE(mp.principal_moments[0], mp.principal_moments[1]);
  EXPECT_LE(mp.principal_moments[1], mp.principal_moments[2]);
}

// ---------------------------------------------------------------------------------------
// Mass properties.

TEST(RigidMassProperties, BoxOneByTwoByThreeIsExact) {
  const Mesh box = Box(Vec3(1.0, 2.0, 3.0));
  ExpectOutward(box, Vec3::Zero());
  const MassProperties mp = Solid(box, 2.0);
  EXPECT_NEAR(mp.volume, 6.0, 1e-14);
  EXPECT_NEAR(mp.mass, 12.0, 1e-13);
  EXPECT_LT(mp.center.norm(), 1e-15);
  const Mat3 expected = Vec3(13.0, 10.0, 5.0).asDiagonal();
  EXPECT_LT((mp.inertia - expected).cwiseAbs().maxCoeff(), 1e-12) << mp.inertia;
  EXPECT_LT((mp.inertia - SolidBoxInertia(Vec3(1.0, 2.0, 3.0), 12.0)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((mp.principal_moments - Vec3(5.0, 10.0, 13.0)).cwiseAbs().maxCoeff(), 1e-12);
  ExpectPrincipalFrame(mp, 1e-12);
  // The axes are the box axes: z (smallest moment), y, then x completing a right-handed frame.
  Mat3 permutation;
  permutation << 0, 0, 1, 0, 1, 0, 1, 0, 0;
  EXPECT_LT((mp.principal_axes.cwiseAbs() - permutation).cwiseAbs().maxCoeff(), 1e-12)
      << mp.principal_axes;
}

TEST(RigidMassProperties, RotatedAndTranslatedBoxGivesTheRotatedInertia) {
  const Mat3 rotation = TestRotation();
  const Vec3 center(10.0, -5.0, 3.0);
  const Mesh box = Box(Vec3(1.0, 2.0, 3.0), rotation, center);
  ExpectOutward(box, center);
  const MassProperties mp = Solid(box, 2.0);
  EXPECT_NEAR(mp.mass, 12.0, 1e-12);
  EXPECT_LT((mp.center - center).norm(), 1e-13);
  const Mat3 expected = rotation * Vec3(13.0, 10.0, 5.0).asDiagonal() * rotation.transpose();
  EXPECT_LT((mp.inertia - expected).cwiseAbs().maxCoeff(), 1e-12) << mp.inertia;
  EXPECT_LT((mp.principal_moments - Vec3(5.0, 10.0, 13.0)).cwiseAbs().maxCoeff(), 1e-12);
  ExpectPrincipalFrame(mp, 1e-12);
  // Each principal axis is (up to sign) a column of the rotation: z, y, x of the box.
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(std::abs(mp.principal_axes.col(k).dot(rotation.col(2 - k))), 1.0, 1e-12);
}

TEST(RigidMassProperties, FarFromTheOriginKeepsItsPrecision) {
  // 1 km away, the origin-based tetrahedra would cancel to ~1e-16 * (1e3)^2 relative error in
  // the inertia; sums about the bounding-box centre do not.
  const Vec3 center(1e3, -2e3, 1.5e3);
  const MassProperties mp = Solid(Box(Vec3(1.0, 2.0, 3.0), TestRotation(), center), 2.0);
  const Mat3 expected =
      TestRotation() * Vec3(13.0, 10.0, 5.0).asDiagonal() * TestRotation().transpose();
  EXPECT_LT((mp.inertia - expected).cwiseAbs().maxCoeff(), 1e-11) << mp.inertia;
  EXPECT_LT((mp.center - center).norm(), 1e-11);
}

TEST(RigidMassProperties, SplitFacesAsInGltfGiveTheSameResult) {
  const MassProperties welded = Solid(Box(Vec3(1.0, 2.0, 3.0), TestRotation()), 2.0);
  const MassProperties split =
      Solid(Box(Vec3(1.0, 2.0, 3.0), TestRotation(), Vec3::Zero(), /*split_faces=*/true), 2.0);
  EXPECT_NEAR(split.mass, welded.mass, 1e-13);
  EXPECT_LT((split.inertia - welded.inertia).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(RigidMassProperties, TwoBoxesCombineByTheParallelAxisTheorem) {
  // A non-convex body: two disjoint boxes. Reference: each box's own inertia shifted by
  // m (|d|^2 1 - d d^T) to the common centre of mass.
  const Vec3 size_a(1.0, 2.0, 3.0), size_b(2.0, 1.0, 1.0);
  const Vec3 center_a(0.0, 0.0, 0.0), center_b(3.0, 1.0, -1.0);
  Mesh mesh = Box(size_a, Mat3::Identity(), center_a);
  mesh.Append(Box(size_b, Mat3::Identity(), center_b));
  const double rho = 1.5;
  const double m_a = rho * 6.0, m_b = rho * 2.0, m = m_a + m_b;
  const Vec3 c = (m_a * center_a + m_b * center_b) / m;
  const auto shift = [](double mass, const Vec3& d) -> Mat3 {
    return mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  };
  const Mat3 expected = SolidBoxInertia(size_a, m_a) + shift(m_a, center_a - c) +
                        SolidBoxInertia(size_b, m_b) + shift(m_b, center_b - c);
  const MassProperties mp = Solid(mesh, rho);
  EXPECT_NEAR(mp.mass, m, 1e-13);
  EXPECT_LT((mp.center - c).norm(), 1e-14);
  EXPECT_LT((mp.inertia - expected).cwiseAbs().maxCoeff(), 1e-12) << mp.inertia;
  ExpectPrincipalFrame(mp, 1e-12);
}

TEST(RigidMassProperties, ShellOfABoxMatchesTheThinShellFormula) {
  const Vec3 size(1.0, 2.0, 3.0);
  const double rho = 2.0, h = 0.01, sigma = rho * h;
  const double area = 2.0 * (1.0 * 2.0 + 1.0 * 3.0 + 2.0 * 3.0);
  const Mat3 rotation = TestRotation();
  const Vec3 center(-4.0, 2.0, 7.0);
  const Mesh box = Box(size, rotation, center);
  MassProperties mp;
  const Status status = ComputeShellMassProperties(box.positions, box.triangles, rho, h, &mp);
  ASSERT_TRUE(status.ok()) << ToString(status);
  EXPECT_NEAR(mp.volume, area * h, 1e-15);
  EXPECT_NEAR(mp.mass, sigma * area, 1e-15);
  EXPECT_LT((mp.center - center).norm(), 1e-13);
  const Mat3 expected = rotation * ShellBoxInertia(size, sigma) * rotation.transpose();
  EXPECT_LT((mp.inertia - expected).cwiseAbs().maxCoeff(), 1e-13) << mp.inertia;
  ExpectPrincipalFrame(mp, 1e-13);
  // The formula itself, checked on a hollow cube of side s: I = (5/18) m s^2, m = 6 sigma s^2.
  const Mat3 cube = ShellBoxInertia(Vec3::Ones(), 1.0);
  EXPECT_NEAR(cube(0, 0), 6.0 * 5.0 / 18.0, 1e-15);
}

TEST(RigidMassProperties, ShellNeedNotBeClosedOrOutward) {
  // An open box (no +x face) as a shell: the solid refuses it, the shell takes it, facing
  // either way.
  Mesh open = Box(Vec3(1.0, 2.0, 3.0), Mat3::Identity(), Vec3::Zero(), false, 1);
  MassProperties outward, inward;
  ASSERT_TRUE(ComputeShellMassProperties(open.positions, open.triangles, 1.0, 0.1, &outward).ok());
  open.Flip();
  ASSERT_TRUE(ComputeShellMassProperties(open.positions, open.triangles, 1.0, 0.1, &inward).ok());
  EXPECT_NEAR(outward.mass, 0.1 * (22.0 - 6.0), 1e-14);
  EXPECT_LT((outward.inertia - inward.inertia).cwiseAbs().maxCoeff(), 1e-14);
  // The centre moves away from the missing face: the +x face (area 6) is gone, and the
  // remaining area 16 balances to x_c = -6 * 0.5 / 16.
  EXPECT_NEAR(outward.center.x(), -6.0 * 0.5 / 16.0, 1e-15);
}

// Refusals: each names the field, and leaves *out untouched.
class RigidMassPropertiesValidation : public ::testing::Test {
 protected:
  Mesh box = Box(Vec3(1.0, 2.0, 3.0));
  MassProperties out;

  void SetUp() override { out.mass = 42.0; }
  void ExpectSolidRefused(double density, std::string_view field, int index = -1) {
    const Status status = ComputeSolidMassProperties(box.positions, box.triangles, density, &out);
    EXPECT_FALSE(status.ok());
    EXPECT_EQ(status.field, field) << ToString(status);
    EXPECT_EQ(status.index, index) << ToString(status);
    EXPECT_FALSE(status.reason.empty());
    EXPECT_EQ(out.mass, 42.0);
  }
  void ExpectShellRefused(double density, double thickness, std::string_view field,
                          int index = -1) {
    const Status status =
        ComputeShellMassProperties(box.positions, box.triangles, density, thickness, &out);
    EXPECT_FALSE(status.ok());
    EXPECT_EQ(status.field, field) << ToString(status);
    EXPECT_EQ(status.index, index) << ToString(status);
    EXPECT_EQ(out.mass, 42.0);
  }
};

TEST_F(RigidMassPropertiesValidation, DensityNotPositiveOrNotFinite) {
  for (double bad : {0.0, -1.0, NaN(), Inf()}) {
    ExpectSolidRefused(bad, "density");
    ExpectShellRefused(bad, 0.1, "density");
  }
}
TEST_F(RigidMassPropertiesValidation, ThicknessNotPositiveOrNotFinite) {
  for (double bad : {0.0, -0.1, NaN(), Inf()}) ExpectShellRefused(1.0, bad, "thickness");
}
TEST_F(RigidMassPropertiesValidation, NoTriangles) {
  box.triangles.clear();
  ExpectSolidRefused(1.0, "triangles");
  ExpectShellRefused(1.0, 0.1, "triangles");
}
TEST_F(RigidMassPropertiesValidation, IndexOutOfRange) {
  box.triangles[5][2] = 8;
  ExpectSolidRefused(1.0, "triangles", 5);
  ExpectShellRefused(1.0, 0.1, "triangles", 5);
}
TEST_F(RigidMassPropertiesValidation, NonFiniteOrFarPositions) {
  box.positions[3].y() = NaN();
  ExpectSolidRefused(1.0, "positions", 3);
  ExpectShellRefused(1.0, 0.1, "positions", 3);
  box.positions[3].y() = Inf();
  ExpectSolidRefused(1.0, "positions", 3);
  box.positions[3].y() = 1e60;
  ExpectSolidRefused(1.0, "positions", 3);
}
TEST_F(RigidMassPropertiesValidation, InwardFacingSurface) {
  box.Flip();
  ExpectSolidRefused(1.0, "volume");
}
TEST_F(RigidMassPropertiesValidation, OpenSurface) {
  box = Box(Vec3(1.0, 2.0, 3.0), Mat3::Identity(), Vec3::Zero(), false, 1);
  ExpectSolidRefused(1.0, "volume");
  // One missing triangle, far smaller than the rest: still an opening.
  box = Box(Vec3(1.0, 2.0, 3.0));
  box.triangles.pop_back();
  ExpectSolidRefused(1.0, "volume");
}
TEST_F(RigidMassPropertiesValidation, FlatSurfaceEnclosesNothing) {
  // A doubled square (both sides): closed in the vector-area sense, zero volume.
  box.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  box.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 2, 1}, {0, 3, 2}};
  ExpectSolidRefused(1.0, "volume");
}
TEST_F(RigidMassPropertiesValidation, DegenerateTrianglesHaveNoArea) {
  box.triangles = {{0, 0, 1}, {2, 2, 2}};
  ExpectShellRefused(1.0, 0.1, "triangles");
}
TEST_F(RigidMassPropertiesValidation, DensityThatWouldOverflowTheInertia) {
  ExpectSolidRefused(1e300, "density");
  ExpectShellRefused(1e300, 1e10, "density");
}
TEST_F(RigidMassPropertiesValidation, MissingOutput) {
  EXPECT_EQ(ComputeSolidMassProperties(box.positions, box.triangles, 1.0, nullptr).field, "out");
  EXPECT_EQ(ComputeShellMassProperties(box.positions, box.triangles, 1.0, 0.1, nullptr).field,
            "out");
}

// ---------------------------------------------------------------------------------------
// Motion. A small driver: n steps of dt from `state` with a wrench sampled from f(t).

template <typename WrenchAt>
Status Simulate(RigidIntegrator integrator, double mass, const Vec3& moments, double dt, int n,
                RigidBodyState* state, WrenchAt wrench_at) {
  RigidBodyStepJob job;
  job.integrator = integrator;
  job.mass = mass;
  job.principal_moments = moments;
  job.dt = dt;
  job.state = state;
  for (int i = 0; i < n; ++i) {
    const double t = state->time;
    job.at_start = wrench_at(t);
    job.at_middle = wrench_at(t + 0.5 * dt);
    job.at_end = wrench_at(t + dt);
    if (Status s = job.Run(); !s) return s;
  }
  return Status::Ok();
}

Wrench NoWrench(double) { return {}; }

// Bit-for-bit equality of two states (NaN included).
bool SameBits(const RigidBodyState& a, const RigidBodyState& b) {
  const auto same = [](double x, double y) {
    return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
  };
  for (int k = 0; k < 3; ++k)
    if (!same(a.position[k], b.position[k]) || !same(a.velocity[k], b.velocity[k]) ||
        !same(a.angular_velocity[k], b.angular_velocity[k]))
      return false;
  for (int k = 0; k < 4; ++k)
    if (!same(a.orientation.coeffs()[k], b.orientation.coeffs()[k])) return false;
  return same(a.time, b.time);
}

TEST(RigidMotion, ConstantForceGivesUniformAcceleration) {
  const double m = 2.0;
  const Vec3 f(1.0, -9.81 * m, 0.5), x0(1.0, 2.0, 3.0), v0(0.5, 1.0, -1.0);
  for (RigidIntegrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    RigidBodyState s;
    s.position = x0;
    s.velocity = v0;
    const int n = 300;
    const double dt = 0.01, t = n * dt;
    ASSERT_TRUE(Simulate(integrator, m, Vec3(1, 2, 3), dt, n, &s, [&](double) {
                  return Wrench{f, Vec3::Zero()};
                }).ok());
    const Vec3 x = x0 + v0 * t + f * (t * t / (2.0 * m));
    const Vec3 v = v0 + f * (t / m);
    EXPECT_LT((s.position - x).cwiseAbs().maxCoeff(), 1e-12) << (s.position - x).transpose();
    EXPECT_LT((s.velocity - v).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_EQ(s.angular_velocity, Vec3::Zero());
    EXPECT_TRUE(s.orientation.coeffs() == Quat::Identity().coeffs());
    EXPECT_NEAR(s.time, t, 1e-13);
  }
}

TEST(RigidMotion, Rk4IsExactForAForceQuadraticInTime) {
  // x'' = (a0 + a1 t + a2 t^2): x = x0 + v0 t + a0 t^2/2 + a1 t^3/6 + a2 t^4/12.
  const Vec3 a0(1.0, 0.0, -2.0), a1(0.0, 3.0, 1.0), a2(-1.5, 0.5, 0.0);
  const double m = 3.0;
  RigidBodyState s;
  const int n = 50;
  const double dt = 0.04, t = n * dt;
  ASSERT_TRUE(Simulate(RigidIntegrator::kRk4, m, Vec3(1, 1, 1), dt, n, &s, [&](double tau) {
                return Wrench{m * (a0 + a1 * tau + a2 * tau * tau), Vec3::Zero()};
              }).ok());
  const Vec3 x = a0 * (t * t / 2) + a1 * (t * t * t / 6) + a2 * (t * t * t * t / 12);
  const Vec3 v = a0 * t + a1 * (t * t / 2) + a2 * (t * t * t / 3);
  EXPECT_LT((s.position - x).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LT((s.velocity - v).cwiseAbs().maxCoeff(), 1e-13);
}

TEST(RigidMotion, ConstantTorqueAboutAPrincipalAxisFromRest) {
  const Vec3 moments(1.0, 2.0, 3.0);
  const double tau = 0.5, dt = 0.01;
  const int n = 200;
  const double t = n * dt;
  for (RigidIntegrator integrator : kIntegrators)
    for (int k = 0; k < 3; ++k) {
      SCOPED_TRACE(::testing::Message() << Name(integrator) << " axis " << k);
      const Vec3 e = Vec3::Unit(k);
      RigidBodyState s;
      ASSERT_TRUE(Simulate(integrator, 1.0, moments, dt, n, &s, [&](double) {
                    return Wrench{Vec3::Zero(), tau * e};
                  }).ok());
      const double theta = tau * t * t / (2.0 * moments[k]);
      const Quat expected(std::cos(theta / 2), std::sin(theta / 2) * e.x(),
                          std::sin(theta / 2) * e.y(), std::sin(theta / 2) * e.z());
      EXPECT_LT((s.orientation.coeffs() - expected.coeffs()).cwiseAbs().maxCoeff(), 1e-10)
          << s.orientation.coeffs().transpose();
      EXPECT_LT((s.angular_velocity - (tau * t / moments[k]) * e).cwiseAbs().maxCoeff(), 1e-12);
    }
}

TEST(RigidMotion, TorqueAboutIsTheMomentArmCrossTheForce) {
  // r = (0, 2, 0) from the centre, F = (3, 0, 0): r x F = (0, 0, -6).
  EXPECT_EQ(TorqueAbout(Vec3(1, 0, 0), Vec3(1, 2, 0), Vec3(3, 0, 0)), Vec3(0, 0, -6));
  EXPECT_EQ(TorqueAbout(Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(3, 4, 5)), Vec3::Zero());
}

TEST(RigidMotion, EnergyAndMomentumOfAKnownState) {
  RigidBodyState s;
  s.velocity = Vec3(1.0, 2.0, 2.0);          // |v|^2 = 9
  s.angular_velocity = Vec3(1.0, 0.0, 2.0);  // body axes
  s.orientation =
      Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()));  // body x -> world y
  const Vec3 moments(1.0, 2.0, 3.0);
  EXPECT_NEAR(KineticEnergy(s, 2.0, moments), 0.5 * 2.0 * 9.0 + 0.5 * (1.0 + 3.0 * 4.0), 1e-15);
  // L_body = (1, 0, 6) -> world (0, 1, 6).
  EXPECT_LT((AngularMomentumWorld(s, moments) - Vec3(0.0, 1.0, 6.0)).norm(), 1e-15);
}

TEST(RigidMotion, MassPropertiesFrameMatchesTheStateConvention) {
  // With orientation = R0 (principal axes), the world angular momentum of a body spinning at
  // omega_world is I_world omega_world.
  const MassProperties mp = Solid(Box(Vec3(1.0, 2.0, 3.0), TestRotation()), 2.0);
  RigidBodyState s;
  s.orientation = Quat(mp.principal_axes);
  const Vec3 omega_world(0.3, -1.2, 0.7);
  s.angular_velocity = mp.principal_axes.transpose() * omega_world;
  EXPECT_LT((AngularMomentumWorld(s, mp.principal_moments) - mp.inertia * omega_world).norm(),
            1e-13);
  EXPECT_NEAR(KineticEnergy(s, 0.0, mp.principal_moments),
              0.5 * omega_world.dot(mp.inertia * omega_world), 1e-13);
}

// The drift table of PHYSICS.md section 7: I = diag(1, 2, 3), omega0 = (0.1, 1, 0.1)
// (near the unstable intermediate axis), T = 100. Largest relative errors along the run.
struct Drift {
  double momentum = 0.0;
  double energy = 0.0;
};

Drift TorqueFreeDrift(RigidIntegrator integrator, double dt) {
  const Vec3 moments(1.0, 2.0, 3.0);
  RigidBodyState s;
  s.angular_velocity = Vec3(0.1, 1.0, 0.1);
  const Vec3 l0 = AngularMomentumWorld(s, moments);
  const double e0 = KineticEnergy(s, 1.0, moments);
  RigidBodyStepJob job;
  job.integrator = integrator;
  job.mass = 1.0;
  job.principal_moments = moments;
  job.dt = dt;
  job.state = &s;
  Drift drift;
  const int n = static_cast<int>(std::lround(100.0 / dt));
  for (int i = 0; i < n; ++i) {
    EXPECT_TRUE(job.Run().ok());
    drift.momentum =
        std::max(drift.momentum, (AngularMomentumWorld(s, moments) - l0).norm() / l0.norm());
    drift.energy = std::max(drift.energy, std::abs(KineticEnergy(s, 1.0, moments) - e0) / e0);
  }
  EXPECT_NEAR(s.orientation.squaredNorm(), 1.0, 1e-15);
  return drift;
}

TEST(RigidTorqueFree, MomentumFormConservesMomentumAndDriftsInEnergyAtSecondOrder) {
  const Drift coarse = TorqueFreeDrift(RigidIntegrator::kMomentum, 0.01);
  const Drift fine = TorqueFreeDrift(RigidIntegrator::kMomentum, 0.001);
  RecordProperty("L_drift_dt_0.01", ::testing::PrintToString(coarse.momentum));
  RecordProperty("L_drift_dt_0.001", ::testing::PrintToString(fine.momentum));
  RecordProperty("E_drift_dt_0.01", ::testing::PrintToString(coarse.energy));
  RecordProperty("E_drift_dt_0.001", ::testing::PrintToString(fine.energy));
  // L is conserved up to the round-off of the L -> omega_b -> L round trip of each step
  // (the state stores omega_b): measured 1.1e-13 (1e4 steps) and 1.0e-12 (1e5 steps).
  EXPECT_LT(coarse.momentum, 1e-12);
  EXPECT_LT(fine.momentum, 1e-11);
  // Table: 6.4e-6 / 5.6e-8 (measured 4.2e-6 / 4.2e-8).
  EXPECT_LT(coarse.energy, 6.4e-5);
  EXPECT_LT(fine.energy, 5.6e-7);
  // Second order: a tenth of the step, a hundredth of the drift.
  EXPECT_GT(coarse.energy / fine.energy, 50.0);
  EXPECT_LT(coarse.energy / fine.energy, 200.0);
}

TEST(RigidTorqueFree, Rk4DriftsAtFourthOrder) {
  const Drift coarse = TorqueFreeDrift(RigidIntegrator::kRk4, 0.01);
  const Drift fine = TorqueFreeDrift(RigidIntegrator::kRk4, 0.001);
  RecordProperty("L_drift_dt_0.01", ::testing::PrintToString(coarse.momentum));
  RecordProperty("L_drift_dt_0.001", ::testing::PrintToString(fine.momentum));
  RecordProperty("E_drift_dt_0.01", ::testing::PrintToString(coarse.energy));
  RecordProperty("E_drift_dt_0.001", ::testing::PrintToString(fine.energy));
  // Table: L 1.4e-10 / 2.1e-14, energy 6.9e-12 / 3.2e-14 (measured, largest along the run:
  // L 1.7e-10 / 4.3e-14, energy 7.4e-12 / 4.8e-14).
  EXPECT_LT(coarse.momentum, 1.4e-9);
  EXPECT_LT(fine.momentum, 2.1e-13);
  EXPECT_LT(coarse.energy, 6.9e-11);
  EXPECT_LT(fine.energy, 3.2e-13);
  // Fourth order in L down to dt = 0.001; energy reaches round-off there, so its order is
  // taken between dt = 0.02 and 0.01 (measured ratios 16 for L, 20 for energy).
  EXPECT_GT(coarse.momentum / fine.momentum, 1e3);
  const Drift coarser = TorqueFreeDrift(RigidIntegrator::kRk4, 0.02);
  EXPECT_GT(coarser.momentum / coarse.momentum, 10.0);  // 2^4 = 16; order > 3.3
  EXPECT_GT(coarser.energy / coarse.energy, 10.0);
}

TEST(RigidTorqueFree, AxisymmetricBodyPrecessesInTheBodyFrame) {
  // I1 = I2: Euler's equations I1 w1' = -(I3 - I1) w3 w2, I1 w2' = (I3 - I1) w3 w1 and
  // w3' = 0 give omega_b = (a cos Wt, a sin Wt, w3) with W = (I3 - I1) w3 / I1.
  const Vec3 moments(1.0, 1.0, 2.0);
  const double a = 0.3, w3 = 1.5, precession = (moments[2] - moments[0]) * w3 / moments[0];
  for (RigidIntegrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    RigidBodyState s;
    s.angular_velocity = Vec3(a, 0.0, w3);
    const Vec3 l0 = AngularMomentumWorld(s, moments);
    RigidBodyStepJob job;
    job.integrator = integrator;
    job.mass = 1.0;
    job.principal_moments = moments;
    job.dt = 1e-3;
    job.state = &s;
    double error = 0.0;
    for (int i = 1; i <= 5000; ++i) {
      ASSERT_TRUE(job.Run().ok());
      const double t = i * job.dt;
      const Vec3 expected(a * std::cos(precession * t), a * std::sin(precession * t), w3);
      error = std::max(error, (s.angular_velocity - expected).norm());
    }
    RecordProperty(std::string("error_") + Name(integrator), ::testing::PrintToString(error));
    // Measured 1.3e-6 (momentum form) and 1e-13 (RK4).
    EXPECT_LT(error, integrator == RigidIntegrator::kRk4 ? 1e-11 : 1e-4);
    EXPECT_LT((AngularMomentumWorld(s, moments) - l0).norm(), 1e-12);
  }
}

// ---------------------------------------------------------------------------------------
// Determinism and validation.

Wrench Wobbly(double t) {
  return {Vec3(std::sin(3 * t), -9.81, std::cos(t)), Vec3(0.2 * std::cos(2 * t), 0.1, -0.3 * t)};
}

TEST(RigidStepJob, SameInputsGiveBitIdenticalResults) {
  for (RigidIntegrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    RigidBodyState first, second;
    first.angular_velocity = second.angular_velocity = Vec3(0.4, -2.0, 1.0);
    first.orientation = second.orientation =
        Quat(Eigen::AngleAxisd(0.3, Vec3(1, 1, 0).normalized()));
    ASSERT_TRUE(Simulate(integrator, 2.0, Vec3(1, 2, 3), 1.0 / 60, 600, &first, Wobbly).ok());
    ASSERT_TRUE(Simulate(integrator, 2.0, Vec3(1, 2, 3), 1.0 / 60, 600, &second, Wobbly).ok());
    EXPECT_TRUE(SameBits(first, second));
    EXPECT_NEAR(first.orientation.norm(), 1.0, 1e-15);
  }
}

TEST(RigidStepJob, CoarseStepsOfAFastSpinNeverGoNonFinite) {
  // Half a turn per step near the intermediate axis: far outside RK4's stability region, so its
  // spin grows step by step until Validate refuses the next step (naming dt) rather than let
  // it overflow. The momentum form stays bounded: |L| is conserved.
  for (RigidIntegrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    RigidBodyState s;
    s.angular_velocity = Vec3(0.5, 3.0, 0.2);
    const Status status = Simulate(integrator, 1.0, Vec3(1, 2, 3), 1.0, 200, &s, NoWrench);
    if (integrator == RigidIntegrator::kRk4) {
      EXPECT_EQ(status.field, "dt") << ToString(status);
    } else {
      EXPECT_TRUE(status.ok()) << ToString(status);
      EXPECT_NEAR(s.time, 200.0, 1e-12);
    }
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(s.angular_velocity[k]));
    EXPECT_NEAR(s.orientation.squaredNorm(), 1.0, 1e-15);
  }
}

class RigidStepJobValidation : public ::testing::Test {
 protected:
  RigidBodyState state;
  RigidBodyStepJob job;

  void SetUp() override {
    state.position = Vec3(1.0, 2.0, 3.0);
    state.velocity = Vec3(0.1, 0.0, -0.2);
    state.angular_velocity = Vec3(0.3, 1.0, 0.1);
    state.time = 0.5;
    job.mass = 2.0;
    job.principal_moments = Vec3(1.0, 2.0, 3.0);
    job.dt = 0.01;
    job.at_start = job.at_middle = job.at_end = Wrench{Vec3(0, -19.62, 0), Vec3(0, 0, 0.1)};
    job.state = &state;
    ASSERT_TRUE(job.Validate().ok());
  }
  // Expects both integrators to refuse, naming field/index/member, and Run() to write nothing.
  void ExpectRefused(std::string_view field, int index = -1, std::string_view member = {}) {
    for (RigidIntegrator integrator : kIntegrators) {
      SCOPED_TRACE(Name(integrator));
      job.integrator = integrator;
      ExpectRefusedAsIs(field, index, member);
    }
  }
  void ExpectRefusedAsIs(std::string_view field, int index = -1, std::string_view member = {}) {
    const Status status = job.Validate();
    EXPECT_FALSE(status.ok());
    EXPECT_EQ(status.field, field) << ToString(status);
    EXPECT_EQ(status.index, index) << ToString(status);
    EXPECT_EQ(status.member, member) << ToString(status);
    EXPECT_FALSE(status.reason.empty());
    const RigidBodyState before = state;
    EXPECT_FALSE(job.Run().ok());
    EXPECT_TRUE(SameBits(state, before));
  }
};

TEST_F(RigidStepJobValidation, ValidJobRunsAndAdvancesTime) {
  for (RigidIntegrator integrator : kIntegrators) {
    job.integrator = integrator;
    const double t0 = state.time;
    ASSERT_TRUE(job.Run().ok());
    EXPECT_EQ(state.time, t0 + job.dt);
  }
}
TEST_F(RigidStepJobValidation, UnknownIntegrator) {
  job.integrator = static_cast<RigidIntegrator>(9);
  ExpectRefusedAsIs("integrator");
}
TEST_F(RigidStepJobValidation, MassNotPositiveOrNotFinite) {
  for (double bad : {0.0, -1.0, NaN(), Inf()}) {
    job.mass = bad;
    ExpectRefused("mass");
  }
}
TEST_F(RigidStepJobValidation, PrincipalMomentNotPositiveOrNotFinite) {
  for (int k = 0; k < 3; ++k)
    for (double bad : {0.0, -1.0, NaN(), Inf()}) {
      job.principal_moments = Vec3(1.0, 2.0, 3.0);
      job.principal_moments[k] = bad;
      ExpectRefused("principal_moments", k);
    }
}
TEST_F(RigidStepJobValidation, StepNotPositiveOrNotFinite) {
  for (double bad : {0.0, -0.01, NaN(), Inf()}) {
    job.dt = bad;
    ExpectRefused("dt");
  }
}
TEST_F(RigidStepJobValidation, NonFiniteWrench) {
  job.at_start.force.y() = NaN();
  ExpectRefused("at_start", -1, "force");
  job.at_start.force.y() = 0.0;
  job.at_middle.torque.x() = Inf();
  ExpectRefused("at_middle", -1, "torque");
  job.at_middle.torque.x() = 0.0;
  job.at_end.force.z() = -Inf();
  ExpectRefused("at_end", -1, "force");
  job.at_end.force.z() = 0.0;
  job.at_end.torque.z() = NaN();
  ExpectRefused("at_end", -1, "torque");
}
TEST_F(RigidStepJobValidation, MissingState) {
  job.state = nullptr;
  for (RigidIntegrator integrator : kIntegrators) {
    job.integrator = integrator;
    EXPECT_EQ(job.Validate().field, "state");
    EXPECT_FALSE(job.Run().ok());
  }
}
TEST_F(RigidStepJobValidation, NonFiniteOrHugeState) {
  state.position.x() = NaN();
  ExpectRefused("state", -1, "position");
  state.position.x() = 1e200;
  ExpectRefused("state", -1, "position");
  state.position.x() = 0.0;
  state.velocity.z() = Inf();
  ExpectRefused("state", -1, "velocity");
  state.velocity.z() = 0.0;
  state.angular_velocity.y() = -Inf();
  ExpectRefused("state", -1, "angular_velocity");
  state.angular_velocity.y() = 1.0;
  state.time = NaN();
  ExpectRefused("state", -1, "time");
}
TEST_F(RigidStepJobValidation, OrientationNotUnit) {
  state.orientation = Quat(1.0, 0.0, 0.1, 0.0);  // |q|^2 = 1.01
  ExpectRefused("state", -1, "orientation");
  state.orientation = Quat(0.0, 0.0, 0.0, 0.0);
  ExpectRefused("state", -1, "orientation");
  state.orientation = Quat(NaN(), 0.0, 0.0, 0.0);
  ExpectRefused("state", -1, "orientation");
  state.orientation = Quat(1e300, 1e300, 0.0, 0.0);
  ExpectRefused("state", -1, "orientation");
  // Within 1e-6 of unit is accepted, and the result is unit again.
  state.orientation = Quat(1.0 + 4e-7, 0.0, 0.0, 0.0);
  ASSERT_TRUE(job.Run().ok());
  EXPECT_NEAR(state.orientation.squaredNorm(), 1.0, 1e-15);
}
TEST_F(RigidStepJobValidation, StepThatCouldOverflow) {
  job.at_middle.force.x() = 1e300;
  job.mass = 1e-10;
  ExpectRefused("dt");
}
TEST_F(RigidStepJobValidation, Rk4RefusesAStepItsStagesCouldBlowUpMomentumFormTakesIt) {
  // A needle spinning fast about its long axis, with a long step: the gyroscopic term
  // (I_max / I_min) omega^2 could grow through RK4's stages; the momentum form only turns.
  state.angular_velocity = Vec3(1e40, 1e40, 1e40);
  job.principal_moments = Vec3(1e-30, 1.0, 1.0);
  job.dt = 1.0;
  job.integrator = RigidIntegrator::kRk4;
  ExpectRefusedAsIs("dt");
  job.integrator = RigidIntegrator::kMomentum;
  EXPECT_TRUE(job.Validate().ok()) << ToString(job.Validate());
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
