// Procedural meshes: surfaces of revolution about +Y, built from a profile of (radius, y)
// points. A profile point on the axis (radius 0) becomes a single pole vertex, any other point a
// ring of `radial_segments` vertices; consecutive profile points are joined by a band of quads
// (two triangles each) or, next to a pole, a triangle fan. Every ring vertex is shared by all
// triangles around it (including across the angular seam), so the meshes are closed and
// watertight, and render and welded vertices coincide.
//
// Conventions:
//   - Ring vertex i sits at angle phi_i = 2 pi i / radial_segments, counter-clockwise seen from
//     +Y, starting at +X: (r cos phi, y, -r sin phi). Rings are stored one after another in
//     profile order (bottom to top), a pole as one vertex.
//   - Triangles face outwards (counter-clockwise seen from outside).
//   - Normals are smooth: the area-weighted average of the incident triangles' normals.
//   - Segment counts are clamped to sane minimums: radial/ring/tube segments >= 3,
//     height segments >= 1, cap rings >= 1. Lengths are checked with assert (radii and
//     heights positive; a cone needs r0, r1 >= 0 with at least one positive; a torus needs
//     0 < minor < major; a capsule's height may be 0, making it a sphere).
#include "wirerig/procedural/shapes.h"

#include "wirerig/runtime/curve.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace wirerig {
namespace {

struct ProfilePoint {
  double radius;  // 0: a pole on the axis
  double y;
};

std::uint32_t Index(std::size_t i) { return static_cast<std::uint32_t>(i); }

// Smooth normals, the parts and the (identity) welding; positions and triangles are set.
void Finish(Mesh& mesh, const std::string& name) {
  mesh.normals.assign(mesh.positions.size(), Vec3::Zero());
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.positions[t[0]];
    const Vec3 n = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);
    for (std::uint32_t v : t) mesh.normals[v] += n;
  }
  for (Vec3& n : mesh.normals) {
    const double length = n.norm();
    if (length > 0.0) n /= length;
  }
  mesh.parts = {MeshPart{name, 0, Index(mesh.triangles.size()), -1}};
  mesh.weld_map.resize(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.weld_map.size(); ++i) mesh.weld_map[i] = Index(i);
  mesh.welded_positions = mesh.positions;
  mesh.welded_triangles = mesh.triangles;
}

// Quad (v00, v10, v11, v01), counter-clockwise seen from outside, as two triangles.
void AddQuad(Mesh& mesh, std::uint32_t v00, std::uint32_t v10, std::uint32_t v11,
             std::uint32_t v01) {
  mesh.triangles.push_back({v00, v10, v11});
  mesh.triangles.push_back({v00, v11, v01});
}

// Surface of revolution of an open profile whose consecutive points are joined; the profile
// must run so that the solid lies on its left in the (radius, y) half-plane (upwards on the
// outside). Its ends are poles or rings; a ring at an end is left open.
Mesh Revolve(const std::vector<ProfilePoint>& profile, int segments, const std::string& name) {
  Mesh mesh;
  const auto n = static_cast<std::size_t>(segments);
  std::vector<std::size_t> first(profile.size());  // first vertex of each profile point
  for (std::size_t j = 0; j < profile.size(); ++j) {
    first[j] = mesh.positions.size();
    const ProfilePoint& p = profile[j];
    if (p.radius == 0.0) {
      mesh.positions.emplace_back(0.0, p.y, 0.0);
      continue;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double phi = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
      mesh.positions.emplace_back(p.radius * std::cos(phi), p.y, -p.radius * std::sin(phi));
    }
  }
  for (std::size_t j = 0; j + 1 < profile.size(); ++j) {
    const bool pole0 = profile[j].radius == 0.0, pole1 = profile[j + 1].radius == 0.0;
    assert(!(pole0 && pole1));
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t i1 = (i + 1) % n;
      const std::uint32_t v00 = Index(first[j] + (pole0 ? 0 : i));
      const std::uint32_t v10 = Index(first[j] + (pole0 ? 0 : i1));
      const std::uint32_t v01 = Index(first[j + 1] + (pole1 ? 0 : i));
      const std::uint32_t v11 = Index(first[j + 1] + (pole1 ? 0 : i1));
      if (pole0) {
        mesh.triangles.push_back({v00, v11, v01});
      } else if (pole1) {
        mesh.triangles.push_back({v00, v10, v11});
      } else {
        AddQuad(mesh, v00, v10, v11, v01);
      }
    }
  }
  Finish(mesh, name);
  return mesh;
}

// Fraction j / count, exactly 1 at j == count.
double Fraction(int j, int count) { return static_cast<double>(j) / static_cast<double>(count); }

}  // namespace

Mesh MakeCylinder(double radius, double height, int radial_segments, int height_segments) {
  assert(radius > 0.0 && height > 0.0);
  radial_segments = std::max(radial_segments, 3);
  height_segments = std::max(height_segments, 1);
  std::vector<ProfilePoint> profile = {{0.0, 0.0}};
  for (int j = 0; j <= height_segments; ++j)
    profile.push_back({radius, height * Fraction(j, height_segments)});
  profile.push_back({0.0, height});
  return Revolve(profile, radial_segments, "cylinder");
}

Mesh MakeCone(double r0, double r1, double height, int radial_segments, int height_segments) {
  assert(r0 >= 0.0 && r1 >= 0.0 && r0 + r1 > 0.0 && height > 0.0);
  radial_segments = std::max(radial_segments, 3);
  height_segments = std::max(height_segments, 1);
  std::vector<ProfilePoint> profile;
  if (r0 > 0.0) profile.push_back({0.0, 0.0});  // bottom cap centre
  for (int j = 0; j <= height_segments; ++j) {
    const double s = Fraction(j, height_segments);
    // r0 (1 - s) + r1 s is exactly r0 at s = 0 and r1 at s = 1 (0 there: the apex).
    profile.push_back({r0 * (1.0 - s) + r1 * s, height * s});
  }
  if (r1 > 0.0) profile.push_back({0.0, height});  // top cap centre
  return Revolve(profile, radial_segments, "cone");
}

Mesh MakeCapsule(double radius, double height, int radial_segments, int height_segments,
                 int cap_rings) {
  assert(radius > 0.0 && height >= 0.0);
  radial_segments = std::max(radial_segments, 3);
  height_segments = std::max(height_segments, 1);
  cap_rings = std::max(cap_rings, 1);
  // Each hemisphere has cap_rings bands of equal polar angle between the equator ring (shared
  // with the body) and its pole; the body has height_segments bands (none when height is 0).
  std::vector<ProfilePoint> profile;
  for (int l = cap_rings; l >= 1; --l) {  // south pole (l = cap_rings) up to above the equator
    const double elevation = -0.5 * std::numbers::pi * Fraction(l, cap_rings);
    profile.push_back({l == cap_rings ? 0.0 : radius * std::cos(elevation),
                       l == cap_rings ? -radius : radius * std::sin(elevation)});
  }
  const int body_segments = height > 0.0 ? height_segments : 0;
  for (int j = 0; j <= body_segments; ++j)
    profile.push_back({radius, body_segments == 0 ? 0.0 : height * Fraction(j, body_segments)});
  for (int l = 1; l <= cap_rings; ++l) {
    const double elevation = 0.5 * std::numbers::pi * Fraction(l, cap_rings);
    profile.push_back({l == cap_rings ? 0.0 : radius * std::cos(elevation),
                       l == cap_rings ? height + radius : height + radius * std::sin(elevation)});
  }
  return Revolve(profile, radial_segments, "capsule");
}

Mesh MakeTorus(double major_radius, double minor_radius, int ring_segments, int tube_segments) {
  assert(minor_radius > 0.0 && major_radius > minor_radius);
  // Ring k (a circle of the tube) lies at phi_k = 2 pi k / ring_segments, counter-clockwise
  // seen from +Y starting at +X; its vertex l at theta_l = 2 pi l / tube_segments from the
  // outer equator towards +Y: position (rho cos phi, r sin theta, -rho sin phi) with
  // rho = R + r cos theta. Vertex index k * tube_segments + l.
  const auto rings = static_cast<std::size_t>(std::max(ring_segments, 3));
  const auto tube = static_cast<std::size_t>(std::max(tube_segments, 3));
  Mesh mesh;
  std::vector<double> cos_theta(tube), sin_theta(tube);
  for (std::size_t l = 0; l < tube; ++l) {
    const double theta =
        2.0 * std::numbers::pi * static_cast<double>(l) / static_cast<double>(tube);
    cos_theta[l] = std::cos(theta);
    sin_theta[l] = std::sin(theta);
  }
  for (std::size_t k = 0; k < rings; ++k) {
    const double phi = 2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(rings);
    const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
    for (std::size_t l = 0; l < tube; ++l) {
      const double rho = major_radius + minor_radius * cos_theta[l];
      mesh.positions.emplace_back(rho * cos_phi, minor_radius * sin_theta[l], -rho * sin_phi);
    }
  }
  for (std::size_t k = 0; k < rings; ++k) {
    const std::size_t k1 = (k + 1) % rings;
    for (std::size_t l = 0; l < tube; ++l) {
      const std::size_t l1 = (l + 1) % tube;
      AddQuad(mesh, Index(k * tube + l), Index(k1 * tube + l), Index(k1 * tube + l1),
              Index(k * tube + l1));
    }
  }
  Finish(mesh, "torus");
  return mesh;
}

}  // namespace wirerig

namespace wirerig {

Mesh MakeSweptTube(const std::vector<Vec3>& centres, const std::vector<double>& radii,
                   int radial_segments, const std::string& name) {
  const std::size_t count = centres.size();
  if (count < 2 || radii.size() != count) return {};
  const bool pole0 = radii.front() == 0.0, pole1 = radii.back() == 0.0;
  if (count < (pole0 || pole1 ? 3u : 2u)) return {};
  for (std::size_t k = 0; k < count; ++k) {
    const bool end_pole = (k == 0 && pole0) || (k + 1 == count && pole1);
    if (!end_pole && !(radii[k] > 0.0)) return {};
  }
  Curve curve;
  if (!Curve::Build(centres, false, CurveInterpolation::kCubic, &curve).ok()) return {};
  const auto n = static_cast<std::size_t>(std::max(radial_segments, 3));
  // Frames at the centres: the curve's frame at the centre's arc-length parameter.
  std::vector<double> v(count, 0.0);
  double total = 0.0;
  for (std::size_t k = 1; k < count; ++k) v[k] = total += (centres[k] - centres[k - 1]).norm();
  Mesh mesh;
  std::vector<std::size_t> first(count);
  for (std::size_t k = 0; k < count; ++k) {
    first[k] = mesh.positions.size();
    if (radii[k] == 0.0) {
      mesh.positions.push_back(centres[k]);
      continue;
    }
    const Frame frame = curve.FrameAt(v[k] / total);
    for (std::size_t i = 0; i < n; ++i) {
      const double phi = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
      mesh.positions.push_back(
          centres[k] + radii[k] * (std::cos(phi) * frame.normal + std::sin(phi) * frame.binormal));
    }
  }
  for (std::size_t k = 0; k + 1 < count; ++k) {
    const bool p0 = radii[k] == 0.0, p1 = radii[k + 1] == 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t i1 = (i + 1) % n;
      const std::uint32_t v00 = Index(first[k] + (p0 ? 0 : i));
      const std::uint32_t v10 = Index(first[k] + (p0 ? 0 : i1));
      const std::uint32_t v01 = Index(first[k + 1] + (p1 ? 0 : i));
      const std::uint32_t v11 = Index(first[k + 1] + (p1 ? 0 : i1));
      // Ring order turns about the tangent as Revolve's turns about +Y: same windings.
      if (p0) {
        mesh.triangles.push_back({v00, v11, v01});
      } else if (p1) {
        mesh.triangles.push_back({v00, v10, v11});
      } else {
        AddQuad(mesh, v00, v10, v11, v01);
      }
    }
  }
  Finish(mesh, name);
  return mesh;
}

void AppendMesh(Mesh& mesh, const Mesh& piece) {
  const auto render_offset = Index(mesh.positions.size());
  const auto welded_offset = Index(mesh.welded_positions.size());
  const auto triangle_offset = Index(mesh.triangles.size());
  mesh.positions.insert(mesh.positions.end(), piece.positions.begin(), piece.positions.end());
  mesh.normals.insert(mesh.normals.end(), piece.normals.begin(), piece.normals.end());
  mesh.uvs.insert(mesh.uvs.end(), piece.uvs.begin(), piece.uvs.end());
  for (Triangle t : piece.triangles) {
    for (std::uint32_t& i : t) i += render_offset;
    mesh.triangles.push_back(t);
  }
  for (MeshPart part : piece.parts) {
    part.first_triangle += triangle_offset;
    mesh.parts.push_back(part);
  }
  for (std::uint32_t w : piece.weld_map) mesh.weld_map.push_back(w + welded_offset);
  mesh.welded_positions.insert(mesh.welded_positions.end(), piece.welded_positions.begin(),
                               piece.welded_positions.end());
  for (Triangle t : piece.welded_triangles) {
    for (std::uint32_t& i : t) i += welded_offset;
    mesh.welded_triangles.push_back(t);
  }
}

}  // namespace wirerig
