// Tests for ExtractCurveSkeleton and DescribeFromCurveSkeleton: a procedural capsule (the
// skeleton is its axis), a sphere under floating-point traps, a pinched vertex, refusals of
// open, non-manifold, misoriented, unwelded and broken input, determinism, and the parts found
// on the cow (quadruped), camel (quadruped) and man (biped) assets. Insideness is checked with
// an independent solid-angle winding number.
#include "wirerig/rig/curve_skeleton.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "wirerig/rig/joint_skin_report.h"
#include "wirerig/rig/mesh.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_description.h"
#include "wirerig/rig/rig_model_builder.h"

#ifndef WIRERIG_ASSET_DIR
#error "the tests need WIRERIG_ASSET_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;

// Loads an asset mesh, or skips the test when the asset is not there.
#define LOAD_ASSET(mesh, name, options)                                                \
  Mesh mesh;                                                                           \
  {                                                                                    \
    const fs::path path = fs::path(WIRERIG_ASSET_DIR) / (name);                        \
    ASSERT_TRUE(fs::exists(path)) << "asset missing (run scripts/setup.sh): " << path; \
    Result<ImportedMesh> imported = ImportMesh(path, (options));                       \
    ASSERT_TRUE(imported.ok()) << imported.error();                                    \
    mesh = std::move(imported).value().mesh;                                           \
  }

// Fills the weld fields as the identity (the procedural meshes share their vertices).
Mesh Welded(std::vector<Vec3> positions, std::vector<Triangle> triangles) {
  Mesh mesh;
  mesh.positions = std::move(positions);
  mesh.triangles = std::move(triangles);
  mesh.parts.push_back({"mesh", 0, static_cast<std::uint32_t>(mesh.triangles.size()), -1});
  mesh.weld_map.resize(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.weld_map.size(); ++i) {
    mesh.weld_map[i] = static_cast<std::uint32_t>(i);
  }
  mesh.welded_positions = mesh.positions;
  mesh.welded_triangles = mesh.triangles;
  return mesh;
}

Mesh Tetrahedron() {
  return Welded({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
                {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

// Capsule around the +Y axis: a cylinder of `radius` from y = 0 to y = length with
// hemispherical caps, outward-facing triangles (a UV sphere when body_rings is 0).
Mesh Capsule(double radius, double length, int segments, int cap_rings, int body_rings) {
  // Profile rings from the bottom to the top: (y, ring radius).
  std::vector<std::pair<double, double>> rings;
  const double quarter = 0.5 * std::numbers::pi;
  for (int k = 1; k <= cap_rings; ++k) {
    const double angle = -quarter + quarter * k / cap_rings;
    rings.emplace_back(radius * std::sin(angle), radius * std::cos(angle));
  }
  for (int k = 1; k <= body_rings; ++k) rings.emplace_back(length * k / body_rings, radius);
  for (int k = 1; k < cap_rings; ++k) {
    const double angle = quarter * k / cap_rings;
    rings.emplace_back(length + radius * std::sin(angle), radius * std::cos(angle));
  }
  std::vector<Vec3> positions{Vec3(0, -radius, 0)};
  for (const auto& [y, r] : rings) {
    for (int j = 0; j < segments; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / segments;
      positions.emplace_back(r * std::cos(phi), y, r * std::sin(phi));
    }
  }
  positions.emplace_back(0, length + radius, 0);
  const auto top = static_cast<std::uint32_t>(positions.size() - 1);
  auto at = [&](std::size_t ring, int j) {
    return static_cast<std::uint32_t>(1 + ring * segments + (j % segments));
  };
  std::vector<Triangle> triangles;
  for (int j = 0; j < segments; ++j) {
    triangles.push_back({0, at(0, j), at(0, j + 1)});
    for (std::size_t ring = 0; ring + 1 < rings.size(); ++ring) {
      triangles.push_back({at(ring, j), at(ring + 1, j), at(ring + 1, j + 1)});
      triangles.push_back({at(ring, j), at(ring + 1, j + 1), at(ring, j + 1)});
    }
    triangles.push_back({at(rings.size() - 1, j), top, at(rings.size() - 1, j + 1)});
  }
  return Welded(std::move(positions), std::move(triangles));
}

double SignedVolume(const Mesh& mesh) {
  double volume = 0.0;
  for (const Triangle& t : mesh.welded_triangles) {
    const Vec3& a = mesh.welded_positions[t[0]];
    volume += a.dot(mesh.welded_positions[t[1]].cross(mesh.welded_positions[t[2]])) / 6.0;
  }
  return volume;
}

// Generalised winding number by solid angles (Van Oosterom and Strackee): 1 inside a closed,
// outward-oriented surface, 0 outside. Independent of the code under test.
double Winding(const Mesh& mesh, const Vec3& point) {
  double total = 0.0;
  for (const Triangle& t : mesh.welded_triangles) {
    const Vec3 a = mesh.welded_positions[t[0]] - point;
    const Vec3 b = mesh.welded_positions[t[1]] - point;
    const Vec3 c = mesh.welded_positions[t[2]] - point;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * std::numbers::pi);
}

std::vector<Vec3> AllPoints(const CurveSkeleton& skeleton) {
  std::vector<Vec3> points = skeleton.nodes;
  for (const CurveSkeleton::Branch& branch : skeleton.branches) {
    points.insert(points.end(), branch.points.begin(), branch.points.end());
  }
  return points;
}

// Structural checks every extracted skeleton must pass.
void ExpectWellFormed(const CurveSkeleton& skeleton) {
  ASSERT_FALSE(skeleton.nodes.empty());
  const int node_count = static_cast<int>(skeleton.nodes.size());
  for (const CurveSkeleton::Branch& branch : skeleton.branches) {
    ASSERT_GE(branch.from, 0);
    ASSERT_LT(branch.from, node_count);
    ASSERT_GE(branch.to, 0);
    ASSERT_LT(branch.to, node_count);
    ASSERT_GE(branch.points.size(), 2u);
    EXPECT_EQ(branch.points.front(), skeleton.nodes[branch.from]);
    EXPECT_EQ(branch.points.back(), skeleton.nodes[branch.to]);
  }
  // Nodes are exactly the skeleton vertices of degree other than 2 (or a cycle's anchor).
  std::vector<int> degree(skeleton.nodes.size(), 0);
  for (const CurveSkeleton::Branch& branch : skeleton.branches) {
    ++degree[branch.from];
    ++degree[branch.to];
  }
  for (const CurveSkeleton::Branch& branch : skeleton.branches) {
    if (branch.from != branch.to) {
      EXPECT_NE(degree[branch.from], 2);
      EXPECT_NE(degree[branch.to], 2);
    }
  }
}

double Length(const std::vector<Vec3>& curve) {
  double length = 0.0;
  for (std::size_t i = 1; i < curve.size(); ++i) length += (curve[i] - curve[i - 1]).norm();
  return length;
}

const PartDescription* Find(const RigDescription& description, const std::string& name) {
  for (const PartDescription& part : description.parts) {
    if (part.name == name) return &part;
  }
  return nullptr;
}

std::multiset<std::string> Names(const RigDescription& description) {
  std::multiset<std::string> names;
  for (const PartDescription& part : description.parts) names.insert(part.name);
  return names;
}

TEST(CurveSkeleton, CapsuleSkeletonIsItsAxis) {
  const double radius = 0.1, length = 0.6;
  const Mesh mesh = Capsule(radius, length, 24, 6, 24);
  ASSERT_GT(SignedVolume(mesh), 0.0);
  const Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
  ASSERT_TRUE(skeleton.ok()) << skeleton.error();
  ExpectWellFormed(skeleton.value());
  // A single polyline between two ends.
  EXPECT_EQ(skeleton.value().nodes.size(), 2u);
  EXPECT_EQ(skeleton.value().branches.size(), 1u);
  double low = 1e9, high = -1e9;
  for (const Vec3& p : AllPoints(skeleton.value())) {
    EXPECT_LT(std::hypot(p.x(), p.z()), 0.05 * radius) << p.transpose();
    EXPECT_GT(p.y(), -radius);
    EXPECT_LT(p.y(), length + radius);
    low = std::min(low, p.y());
    high = std::max(high, p.y());
  }
  // It spans (nearly) the whole cylinder.
  EXPECT_LT(low, 0.1 * length);
  EXPECT_GT(high, 0.9 * length);

  // Described as one part along the axis, its ends pushed towards the caps.
  const Result<RigDescription> description = DescribeFromCurveSkeleton(mesh, skeleton.value());
  ASSERT_TRUE(description.ok()) << description.error();
  EXPECT_EQ(ValidateRigDescription(description.value()), "");
  ASSERT_EQ(description.value().parts.size(), 1u);
  const PartDescription& torso = description.value().parts[0];
  EXPECT_EQ(torso.name, "torso");
  EXPECT_TRUE(torso.parent.empty());
  EXPECT_LT(torso.central_curve.front().y(), torso.central_curve.back().y());  // lower end first
  EXPECT_LT(torso.central_curve.front().y(), -0.5 * radius);
  EXPECT_GT(torso.central_curve.back().y(), length + 0.5 * radius);
  for (const Vec3& p : torso.central_curve) {
    EXPECT_LT(std::hypot(p.x(), p.z()), 0.05 * radius);
    EXPECT_GT(Winding(mesh, p), 0.5) << p.transpose();
  }
}

// A skeleton that jogs sideways inside a capsule by 0.4 of its radius in one 2 cm step (two
// kinks of 63 degrees, as a contraction leaves where branches meet) is described as a curve
// that turns gently: profiles are traced normal to the curve, and a kink sharper than the flesh
// around it is thick would fan them out across each other. Its ends stay where they were.
TEST(CurveSkeleton, KinksSharperThanTheFleshAreSmoothedOut) {
  const double radius = 0.1, length = 0.6;
  const Mesh mesh = Capsule(radius, length, 24, 6, 24);
  CurveSkeleton skeleton;
  CurveSkeleton::Branch branch;
  branch.from = 0, branch.to = 1;
  const int steps = 30;
  for (int k = 0; k <= steps; ++k) {
    const double jog = k > steps / 2 ? 0.4 * radius : 0.0;
    branch.points.emplace_back(jog, length * k / steps, 0.0);
  }
  skeleton.nodes = {branch.points.front(), branch.points.back()};
  skeleton.branches.push_back(branch);
  const Result<RigDescription> description = DescribeFromCurveSkeleton(mesh, skeleton);
  ASSERT_TRUE(description.ok()) << description.error();
  ASSERT_EQ(description.value().parts.size(), 1u);
  const std::vector<Vec3>& curve = description.value().parts[0].central_curve;
  ASSERT_GE(curve.size(), 3u);
  double sharpest = 0.0;
  for (std::size_t k = 1; k + 1 < curve.size(); ++k) {
    const Vec3 a = (curve[k] - curve[k - 1]).normalized(),
               b = (curve[k + 1] - curve[k]).normalized();
    sharpest = std::max(sharpest, std::acos(std::clamp(a.dot(b), -1.0, 1.0)));
  }
  EXPECT_LT(sharpest, 30.0 * std::numbers::pi / 180.0);  // unsmoothed: 63
  EXPECT_LT(std::abs(curve.front().x()), 1e-9);
  EXPECT_NEAR(curve.back().x(), 0.4 * radius, 1e-9);
}

// A UV sphere: its cospherical points make CGAL's interval arithmetic produce invalid
// operations inside the Delaunay triangulation (a SIGFPE under this test main's traps unless
// ExtractCurveSkeleton holds them).
TEST(CurveSkeleton, SphereWorksWithFloatingPointTrapsEnabled) {
  const double radius = 0.3;
  const Mesh mesh = Capsule(radius, 0.0, 32, 8, 0);  // no cylinder: a UV sphere
  ASSERT_GT(SignedVolume(mesh), 0.0);
  const Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
  ASSERT_TRUE(skeleton.ok()) << skeleton.error();
  ExpectWellFormed(skeleton.value());
  for (const Vec3& p : AllPoints(skeleton.value())) {
    EXPECT_LT(p.norm(), 0.5 * radius) << p.transpose();
    EXPECT_GT(Winding(mesh, p), 0.5) << p.transpose();
  }
  const Result<RigDescription> description = DescribeFromCurveSkeleton(mesh, skeleton.value());
  ASSERT_TRUE(description.ok()) << description.error();
  EXPECT_EQ(ValidateRigDescription(description.value()), "");
  ASSERT_EQ(description.value().parts.size(), 1u);
  EXPECT_EQ(description.value().parts[0].name, "torso");
}

TEST(CurveSkeleton, RefusesAnOpenMesh) {
  Mesh mesh = Tetrahedron();
  mesh.welded_triangles.pop_back();
  const Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
  ASSERT_FALSE(skeleton.ok());
  EXPECT_NE(skeleton.error().find("not closed"), std::string::npos) << skeleton.error();
  EXPECT_NE(skeleton.error().find("3 boundary edges"), std::string::npos) << skeleton.error();
}

TEST(CurveSkeleton, RefusesNonManifoldAndMisorientedMeshes) {
  {
    // Two tetrahedra sharing the edge 0-1: four triangles on that edge.
    Mesh mesh = Tetrahedron();
    mesh.welded_positions.push_back(Vec3(0, -1, 0));
    mesh.welded_positions.push_back(Vec3(0, 0, -1));
    mesh.welded_triangles.insert(mesh.welded_triangles.end(),
                                 {{0, 1, 4}, {0, 5, 1}, {0, 4, 5}, {1, 5, 4}});
    const Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
    ASSERT_FALSE(skeleton.ok());
    EXPECT_NE(skeleton.error().find("not 2-manifold"), std::string::npos) << skeleton.error();
    EXPECT_NE(skeleton.error().find("three or more"), std::string::npos) << skeleton.error();
  }
  {
    Mesh mesh = Tetrahedron();
    std::swap(mesh.welded_triangles[0][1], mesh.welded_triangles[0][2]);
    const Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
    ASSERT_FALSE(skeleton.ok());
    EXPECT_NE(skeleton.error().find("not consistently oriented"), std::string::npos)
        << skeleton.error();
  }
}

TEST(CurveSkeleton, SplitsAPinchedVertex) {
  // Two capsules along Y whose poles are one welded vertex: closed, every edge shared by two
  // triangles, but two fans of triangles around the pole (cow.off has such a vertex too).
  const double radius = 0.1, length = 0.5;
  Mesh upper = Capsule(radius, length, 16, 4, 12);
  std::vector<Vec3> positions = upper.welded_positions;
  std::vector<Triangle> triangles = upper.welded_triangles;
  const auto offset = static_cast<std::uint32_t>(positions.size() - 1);
  // The mirror image below y = -radius, reusing vertex 0 (the pole at y = -radius).
  for (std::size_t v = 1; v < upper.welded_positions.size(); ++v) {
    const Vec3& p = upper.welded_positions[v];
    positions.emplace_back(p.x(), -2.0 * radius - p.y(), p.z());
  }
  auto mirrored = [&](std::uint32_t v) { return v == 0 ? 0u : v + offset; };
  for (const Triangle& t : upper.welded_triangles) {
    triangles.push_back({mirrored(t[0]), mirrored(t[2]), mirrored(t[1])});
  }
  const Mesh mesh = Welded(std::move(positions), std::move(triangles));
  ASSERT_GT(SignedVolume(mesh), 0.0);

  const Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
  ASSERT_TRUE(skeleton.ok()) << skeleton.error();
  ExpectWellFormed(skeleton.value());
  EXPECT_EQ(skeleton.value().branches.size(), 2u);
  double low = 1e9, high = -1e9;
  for (const Vec3& p : AllPoints(skeleton.value())) {
    EXPECT_LT(std::hypot(p.x(), p.z()), 0.05 * radius) << p.transpose();
    low = std::min(low, p.y());
    high = std::max(high, p.y());
  }
  EXPECT_GT(high, 0.9 * length);
  EXPECT_LT(low, -2.0 * radius - 0.9 * length);

  // The second piece hangs from the first.
  const Result<RigDescription> description = DescribeFromCurveSkeleton(mesh, skeleton.value());
  ASSERT_TRUE(description.ok()) << description.error();
  EXPECT_EQ(ValidateRigDescription(description.value()), "");
  ASSERT_EQ(description.value().parts.size(), 2u);
  EXPECT_EQ(description.value().parts[1].parent, "torso");
}

TEST(CurveSkeleton, RefusesUnweldedEmptyAndBrokenInput) {
  Mesh mesh = Tetrahedron();
  mesh.welded_triangles.clear();
  mesh.welded_positions.clear();
  Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
  ASSERT_FALSE(skeleton.ok());
  EXPECT_NE(skeleton.error().find("not welded"), std::string::npos) << skeleton.error();

  skeleton = ExtractCurveSkeleton(Mesh{});
  ASSERT_FALSE(skeleton.ok());
  EXPECT_NE(skeleton.error().find("no triangles"), std::string::npos) << skeleton.error();

  mesh = Tetrahedron();
  mesh.welded_triangles[2][1] = 7;
  skeleton = ExtractCurveSkeleton(mesh);
  ASSERT_FALSE(skeleton.ok());
  EXPECT_NE(skeleton.error().find("vertex 7"), std::string::npos) << skeleton.error();

  mesh = Tetrahedron();
  mesh.welded_positions[3].x() = std::numeric_limits<double>::infinity();
  skeleton = ExtractCurveSkeleton(mesh);
  ASSERT_FALSE(skeleton.ok());
  EXPECT_NE(skeleton.error().find("not finite"), std::string::npos) << skeleton.error();

  // A skeleton naming a node that does not exist.
  CurveSkeleton broken;
  broken.nodes = {Vec3(0.2, 0.2, 0.2)};
  broken.branches.push_back({0, 3, {Vec3(0.2, 0.2, 0.2), Vec3(0.3, 0.2, 0.2)}});
  const Result<RigDescription> description = DescribeFromCurveSkeleton(Tetrahedron(), broken);
  ASSERT_FALSE(description.ok());
  EXPECT_NE(description.error().find("branch 0"), std::string::npos) << description.error();
}

TEST(CurveSkeleton, CowIsAQuadrupedWithHeadAndTail) {
  LOAD_ASSET(mesh, "cow.off", ImportOptions{});
  const Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
  ASSERT_TRUE(skeleton.ok()) << skeleton.error();
  ExpectWellFormed(skeleton.value());
  for (const Vec3& p : AllPoints(skeleton.value())) {
    EXPECT_GT(Winding(mesh, p), 0.5) << "skeleton point outside the cow: " << p.transpose();
  }

  const Result<RigDescription> result = DescribeFromCurveSkeleton(mesh, skeleton.value());
  ASSERT_TRUE(result.ok()) << result.error();
  const RigDescription& description = result.value();
  EXPECT_EQ(ValidateRigDescription(description), "");
  // Each leg is a chain: an upper segment from the torso and a lower one below the knee.
  const std::multiset<std::string> expected{"torso",
                                            "head",
                                            "tail",
                                            "leg_front_left_upper",
                                            "leg_front_left_lower",
                                            "leg_front_right_upper",
                                            "leg_front_right_lower",
                                            "leg_back_left_upper",
                                            "leg_back_left_lower",
                                            "leg_back_right_upper",
                                            "leg_back_right_lower"};
  EXPECT_EQ(Names(description), expected);
  ASSERT_EQ(description.parts.size(), 11u);
  EXPECT_EQ(description.parts[0].name, "torso");
  for (const PartDescription& part : description.parts) {
    if (part.name.ends_with("_lower")) {
      EXPECT_EQ(part.parent, part.name.substr(0, part.name.size() - 6) + "_upper");
    } else if (part.name != "torso") {
      EXPECT_EQ(part.parent, "torso") << part.name;
    }
    for (const Vec3& p : part.central_curve) {
      EXPECT_GT(Winding(mesh, p), 0.5) << part.name << " leaves the cow at " << p.transpose();
    }
  }

  const PartDescription* torso = Find(description, "torso");
  const PartDescription* head = Find(description, "head");
  const PartDescription* tail = Find(description, "tail");
  ASSERT_TRUE(torso && head && tail);
  // The torso runs from the hips forwards; head and tail leave its two ends.
  const Vec3 hips = torso->central_curve.front(), shoulders = torso->central_curve.back();
  const Vec3 axis = (shoulders - hips).normalized();
  const Vec3 middle = 0.5 * (hips + shoulders);
  EXPECT_GT(axis.x(), 0.9);  // the cow's body runs along x, its head at +x
  EXPECT_LT((head->central_curve.front() - shoulders).norm(), 1e-9);
  EXPECT_LT((tail->central_curve.front() - hips).norm(), 1e-9);
  EXPECT_GT((head->central_curve.back() - shoulders).dot(axis), 0.0);
  EXPECT_LT((tail->central_curve.back() - hips).dot(axis), 0.0);
  EXPECT_GT(head->central_curve.back().x(), 0.4);
  EXPECT_LT(tail->central_curve.back().x(), -0.4);
  // The torso carries on past its junctions into the rump and the chest: the tail starts a
  // tenth of the body behind the hind legs' tops, the head ahead of the front legs' (the
  // skeleton's torso edge ends at the legs' junctions, and the tail and head started there,
  // taking the rump and the chest). The legs start where they leave the belly, below the
  // torso's line, not at their junctions in the middle of the body (TrimRoot).
  const double body = (head->central_curve.back() - tail->central_curve.back()).dot(axis);
  double torso_bottom = 1e9;
  for (const Vec3& p : torso->central_curve) torso_bottom = std::min(torso_bottom, p.y());
  for (const PartDescription& part : description.parts) {
    if (!part.name.ends_with("_upper")) continue;
    const Vec3& top = part.central_curve.front();
    EXPECT_LT(top.y(), torso_bottom - 0.05 * body) << part.name;
    if (part.name.starts_with("leg_front")) {
      EXPECT_GT((head->central_curve.front() - top).dot(axis), 0.0) << part.name;
    } else {
      EXPECT_GT((top - tail->central_curve.front()).dot(axis), 0.1 * body) << part.name;
    }
  }

  double ground = 1e9;
  for (const Vec3& p : mesh.welded_positions) ground = std::min(ground, p.y());
  // Legs hang down, front legs from the shoulders, left legs on the cow's own left (-Z when
  // its head points to +X and +Y is up).
  for (const std::string side : {"left", "right"}) {
    for (const std::string end : {"front", "back"}) {
      const PartDescription* leg = Find(description, "leg_" + end + "_" + side + "_upper");
      const PartDescription* lower = Find(description, "leg_" + end + "_" + side + "_lower");
      ASSERT_TRUE(leg && lower);
      const Vec3 top = leg->central_curve.front(), foot = lower->central_curve.back();
      EXPECT_LT(foot.y(), top.y() - 0.15) << leg->name;
      EXPECT_LT(foot.y(), ground + 0.1) << leg->name;
      EXPECT_EQ((foot - middle).dot(axis) > 0.0, end == "front") << leg->name;
      EXPECT_EQ(foot.z() < 0.0, side == "left") << leg->name;
      // The knee joins the two segments, each between 30% and 70% of the leg.
      EXPECT_LT((leg->central_curve.back() - lower->central_curve.front()).norm(), 1e-12);
      const double upper_length = Length(leg->central_curve);
      const double total = upper_length + Length(lower->central_curve);
      EXPECT_GT(total, 0.2) << leg->name;
      EXPECT_GT(upper_length, 0.25 * total) << leg->name;
      EXPECT_LT(upper_length, 0.75 * total) << leg->name;
    }
  }
}

TEST(CurveSkeleton, ExtractionIsDeterministic) {
  LOAD_ASSET(mesh, "cow.off", ImportOptions{});
  const Result<CurveSkeleton> first = ExtractCurveSkeleton(mesh);
  // Shuffle the heap: CGAL once ordered its edge collapses by address.
  std::vector<std::unique_ptr<char[]>> clutter;
  for (int i = 0; i < 997; ++i) clutter.emplace_back(new char[16 + (i * 37) % 300]);
  for (std::size_t i = 0; i < clutter.size(); i += 2) clutter[i].reset();
  const Result<CurveSkeleton> second = ExtractCurveSkeleton(mesh);
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_EQ(first.value().nodes, second.value().nodes);
  ASSERT_EQ(first.value().branches.size(), second.value().branches.size());
  for (std::size_t i = 0; i < first.value().branches.size(); ++i) {
    EXPECT_EQ(first.value().branches[i].from, second.value().branches[i].from);
    EXPECT_EQ(first.value().branches[i].to, second.value().branches[i].to);
    EXPECT_EQ(first.value().branches[i].points, second.value().branches[i].points);
  }
}

TEST(CurveSkeleton, CamelIsAQuadruped) {
  LOAD_ASSET(mesh, "camel.off", ImportOptions{});
  const Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
  ASSERT_TRUE(skeleton.ok()) << skeleton.error();
  const Result<RigDescription> description = DescribeFromCurveSkeleton(mesh, skeleton.value());
  ASSERT_TRUE(description.ok()) << description.error();
  EXPECT_EQ(ValidateRigDescription(description.value()), "");
  const std::multiset<std::string> names = Names(description.value());
  for (const char* name :
       {"torso", "head", "tail", "leg_front_left_upper", "leg_front_right_upper",
        "leg_back_left_upper", "leg_back_right_upper", "leg_front_left_lower",
        "leg_front_right_lower", "leg_back_left_lower", "leg_back_right_lower"}) {
    EXPECT_EQ(names.count(name), 1u) << name;
  }
  // The camel faces +Z.
  EXPECT_GT(Find(description.value(), "head")->central_curve.back().z(), 0.3);
  EXPECT_LT(Find(description.value(), "tail")->central_curve.back().z(), -0.3);
}

// Two ways a nearest-curve assignment tore the camel, and the clean-up of each
// (RigDescription::clean_assignment, set by automatic descriptions). The front legs' curves
// pass just under the base of the neck, whose skin is nearest to them in a few patches; those
// patches moved with a leg while the neck around them stayed, and a 60-degree swing of a front
// leg stretched an edge 93-95 times under every skinning method: islands now join the skin
// around them. The tail's curve runs past the rump, whose skin up to 5 tail radii away went to
// the tail: swung 60 degrees to a side it folded 26 and 38 edges and stretched one 8.4x; a
// child's vertices beyond 3 times its typical distance from its curve now go to the part above.
TEST(CurveSkeleton, CamelsLegsAndTailSwingWithoutTearingTheNeckOrTheRump) {
  LOAD_ASSET(mesh, "camel.off", ImportOptions{});
  const Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
  ASSERT_TRUE(skeleton.ok()) << skeleton.error();
  const Result<RigDescription> description = DescribeFromCurveSkeleton(mesh, skeleton.value());
  ASSERT_TRUE(description.ok()) << description.error();
  EXPECT_TRUE(description.value().clean_assignment);
  RigBuildOptions options;
  options.drop_parts_without_profiles = true;
  const Result<BuiltRig> rig = BuildRig(mesh, description.value(), "camel.off", options);
  ASSERT_TRUE(rig.ok()) << rig.error();
  RigModelOptions model_options;
  model_options.spine_kind = SpineKind::kRigid;
  const Result<BuiltRigModel> model = BuildRigModel(mesh, rig.value().rig, model_options);
  ASSERT_TRUE(model.ok()) << model.error();
  std::vector<std::size_t> joints;
  for (std::size_t i = 0; i < rig.value().rig.parts.size(); ++i) {
    const std::string& name = rig.value().rig.parts[i].name;
    if (name == "leg_front_left_upper" || name == "leg_front_right_upper" || name == "tail")
      joints.push_back(i);
  }
  ASSERT_EQ(joints.size(), 3u);
  std::size_t leg_swings = 0, tail_swings = 0;
  for (const JointSkinRow& row :
       MeasureJointSweep(model.value().model, mesh.welded_positions, joints)) {
    const SkinMeasures& wire = row.methods[0];
    if (row.joint == "tail" && (row.pose == "y+60" || row.pose == "y-60")) {
      ++tail_swings;
      EXPECT_LE(wire.folded_edges, 2u) << row.pose;
      EXPECT_LT(wire.worst_stretch, 3.0) << row.pose;
    } else if (row.joint != "tail" && row.pose.find("60") != std::string::npos) {
      ++leg_swings;
      EXPECT_LT(wire.worst_stretch, 10.0) << row.joint << " " << row.pose;
    }
  }
  EXPECT_GE(leg_swings, 4u);
  EXPECT_EQ(tail_swings, 2u);
}

TEST(CurveSkeleton, StandingManIsABiped) {
  // man.off stands along +Z; converted to +Y up.
  ImportOptions options;
  options.up_axis = UpAxis::kZ;
  LOAD_ASSET(mesh, "man.off", options);
  const Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
  ASSERT_TRUE(skeleton.ok()) << skeleton.error();
  const Result<RigDescription> result = DescribeFromCurveSkeleton(mesh, skeleton.value());
  ASSERT_TRUE(result.ok()) << result.error();
  const RigDescription& description = result.value();
  EXPECT_EQ(ValidateRigDescription(description), "");
  // Arms and legs as chains named as a game skeleton names them.
  const std::multiset<std::string> expected{
      "torso",     "head",    "clavicle_l", "upper_arm_l", "forearm_l", "clavicle_r", "upper_arm_r",
      "forearm_r", "thigh_l", "shin_l",     "foot_l",      "thigh_r",   "shin_r",     "foot_r"};
  EXPECT_EQ(Names(description), expected);
  // His arms' branches start in his chest: each hangs from a skinless collar bone that ends
  // where the arm's own length starts, 2 arm thicknesses from the surface.
  for (const char* side : {"l", "r"}) {
    const PartDescription* clavicle = Find(description, std::string("clavicle_") + side);
    const PartDescription* arm = Find(description, std::string("upper_arm_") + side);
    ASSERT_TRUE(clavicle && arm);
    EXPECT_FALSE(clavicle->skin);
    EXPECT_EQ(clavicle->parent, "torso");
    EXPECT_EQ(arm->parent, clavicle->name);
    EXPECT_LT((clavicle->central_curve.back() - arm->central_curve.front()).norm(), 1e-12);
    EXPECT_GT(std::abs(clavicle->central_curve.back().x()), 0.05) << "the shoulder, not the chest";
  }
  const PartDescription* torso = Find(description, "torso");
  const PartDescription* head = Find(description, "head");
  ASSERT_TRUE(torso && head);
  EXPECT_LT(torso->central_curve.front().y(), torso->central_curve.back().y());  // hips first
  EXPECT_GT(head->central_curve.back().y(), torso->central_curve.back().y());
  // The torso carries on into the chest above the shoulders: the head starts at the neck,
  // above every point of the arms' curves.
  for (const char* arm : {"upper_arm_l", "upper_arm_r"})
    for (const Vec3& p : Find(description, arm)->central_curve)
      EXPECT_GT(head->central_curve.front().y(), p.y()) << arm;
  // He faces +Z, so his left is +X.
  EXPECT_GT(Find(description, "forearm_l")->central_curve.back().x(), 0.05);
  EXPECT_LT(Find(description, "forearm_r")->central_curve.back().x(), -0.05);
  EXPECT_GT(Find(description, "shin_l")->central_curve.back().x(), 0.05);
  EXPECT_LT(Find(description, "shin_r")->central_curve.back().x(), -0.05);
  EXPECT_EQ(Find(description, "forearm_l")->parent, "upper_arm_l");
  EXPECT_EQ(Find(description, "shin_r")->parent, "thigh_r");
  for (const char* leg : {"shin_l", "shin_r"}) {
    EXPECT_LT(Find(description, leg)->central_curve.back().y(), -0.4) << leg;
  }
  // His feet: from the ankle, where the leg turns forwards (+Z), hanging from the shin; each
  // runs forwards more than it drops.
  for (const char* side : {"l", "r"}) {
    const PartDescription* foot = Find(description, std::string("foot_") + side);
    const PartDescription* shin = Find(description, std::string("shin_") + side);
    ASSERT_TRUE(foot && shin);
    EXPECT_EQ(foot->parent, shin->name);
    EXPECT_LT((shin->central_curve.back() - foot->central_curve.front()).norm(), 1e-12);
    const Vec3 run = foot->central_curve.back() - foot->central_curve.front();
    EXPECT_GT(run.z(), 0.03) << side;
    EXPECT_GT(run.z(), std::abs(run.y())) << side;
    // An ankle's limits, flexing about his left (+X): 20 degrees up, 45 down.
    ASSERT_TRUE(foot->joint.axis.has_value());
    EXPECT_EQ(*foot->joint.axis, Vec3::UnitX());
    EXPECT_EQ(foot->joint.min_degrees, Vec3(-20.0, -15.0, -20.0));
    EXPECT_EQ(foot->joint.max_degrees, Vec3(45.0, 15.0, 20.0));
  }
  // Elbows and knees where a body has them: 30-65% of the way down from the limb's top to its
  // end (a man's elbow about 40% down from the shoulder to the fingertips, the knee about half
  // way from the hip to the sole). His arms hang from a turn at the shoulder, which is no
  // elbow: the arm's branch starts in his chest and only its part beyond is the limb's length.
  for (const auto& [upper, lower] : {std::pair{"upper_arm_l", "forearm_l"},
                                     {"upper_arm_r", "forearm_r"},
                                     {"thigh_l", "shin_l"},
                                     {"thigh_r", "shin_r"}}) {
    double top = -1e9;
    for (const Vec3& p : Find(description, upper)->central_curve) top = std::max(top, p.y());
    const std::vector<Vec3>& below = Find(description, lower)->central_curve;
    const double down = (top - below.front().y()) / (top - below.back().y());
    EXPECT_GT(down, 0.3) << upper;
    EXPECT_LT(down, 0.65) << upper;
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
