#include "wirerig/procedural/props.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "wirerig/procedural/shapes.h"

namespace wirerig {
namespace {

bool Positive(double x) { return std::isfinite(x) && x > 0.0 && x < 1e6; }

std::string CheckCounts(int radial_segments, int profile_count, int points_per_profile) {
  if (radial_segments < 6 || radial_segments > 512) return "radial_segments: must be in [6, 512]";
  if (profile_count < 2 || profile_count > 1024) return "profile_count: must be in [2, 1024]";
  if (points_per_profile < 3 || points_per_profile > 1024)
    return "points_per_profile: must be in [3, 1024]";
  return {};
}

std::string CheckRings(int rings, int min_rings, const char* name) {
  if (rings >= min_rings && rings <= 4096) return {};
  return std::string(name) + ": must be in [" + std::to_string(min_rings) + ", 4096]";
}

// Moves a piece by p -> linear p + offset (normals by the inverse transpose), and names its
// one part.
void Place(Mesh& mesh, const Mat3& linear, const Vec3& offset, const std::string& name) {
  for (Vec3& p : mesh.positions) p = linear * p + offset;
  for (Vec3& p : mesh.welded_positions) p = linear * p + offset;
  const Mat3 normal_map = linear.inverse().transpose();
  for (Vec3& n : mesh.normals) n = (normal_map * n).normalized();
  for (MeshPart& part : mesh.parts) part.name = name;
}

// A straight tube from `a` to `b` of ring radii radius(s), s in [0, 1] (poles at the ends
// where the radius is 0), squashed by `squash` along the unit direction `across` (normal to
// b - a) about its axis: a cushion-like slab for squash < 1.
template <typename RadiusFn>
Mesh StraightTube(const Vec3& a, const Vec3& b, int rings, int radial_segments, RadiusFn radius,
                  const Vec3& across, double squash, const std::string& name) {
  std::vector<Vec3> centres;
  std::vector<double> radii;
  for (int k = 0; k <= rings; ++k) {
    const double s = static_cast<double>(k) / rings;
    centres.push_back(a + s * (b - a));
    radii.push_back(radius(s));
  }
  Mesh tube = MakeSweptTube(centres, radii, radial_segments, name);
  const Mat3 linear = Mat3::Identity() + (squash - 1.0) * across * across.transpose();
  Place(tube, linear, a - linear * a, name);
  return tube;
}

// 1 in the middle, falling to 0 at s = 0 and 1 like a superellipse of exponent p (boxy ends).
double BoxyEnds(double s, double p) {
  const double x = std::min(std::abs(2.0 * s - 1.0), 1.0);
  return std::pow(std::max(1.0 - std::pow(x, p), 0.0), 1.0 / p);
}

// 0 below e0, 1 above e1, smooth in between.
double SmoothStep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

PartDescription Part(const std::string& name, std::vector<Vec3> central_curve, int profiles,
                     int points, const std::string& parent) {
  PartDescription part;
  part.name = name;
  part.central_curve = std::move(central_curve);
  part.profile_count = profiles;
  part.points_per_profile = points;
  part.parent = parent;
  part.mesh_parts = {name};
  part.joint.blend_length = 0.0;  // props are separate solid pieces: no skin spans a joint
  return part;
}

}  // namespace

std::string ValidateCandleRowParameters(const CandleRowParameters& p) {
  if (p.count < 1 || p.count > 16) return "count: must be in [1, 16]";
  if (!Positive(p.radius)) return "radius: must be in (0, 1e6) m";
  if (!Positive(p.height)) return "height: must be in (0, 1e6) m";
  if (!Positive(p.spacing) || p.spacing <= 2.0 * p.radius)
    return "spacing: must exceed twice the radius (m)";
  if (std::string e = CheckRings(p.height_segments, 1, "height_segments"); !e.empty()) return e;
  return CheckCounts(p.radial_segments, p.profile_count, p.points_per_profile);
}

std::string ValidateBeamParameters(const BeamParameters& p) {
  if (!Positive(p.length)) return "length: must be in (0, 1e6) m";
  if (!Positive(p.radius) || p.radius >= 0.25 * p.length)
    return "radius: must be positive and below a quarter of the length";
  if (std::string e = CheckRings(p.rings, 8, "rings"); !e.empty()) return e;
  return CheckCounts(p.radial_segments, p.profile_count, p.points_per_profile);
}

std::string ValidateTrunkParameters(const TrunkParameters& p) {
  if (!Positive(p.height)) return "height: must be in (0, 1e6) m";
  if (!Positive(p.base_radius)) return "base_radius: must be in (0, 1e6) m";
  if (!Positive(p.top_radius) || p.top_radius >= p.base_radius)
    return "top_radius: must be positive and below base_radius";
  if (!(std::isfinite(p.flare) && p.flare >= 0.0 && p.flare <= 2.0))
    return "flare: must be in [0, 2]";
  if (std::string e = CheckRings(p.rings, 8, "rings"); !e.empty()) return e;
  return CheckCounts(p.radial_segments, p.profile_count, p.points_per_profile);
}

std::string ValidateLampPostParameters(const LampPostParameters& p) {
  if (!Positive(p.height)) return "height: must be in (0, 1e6) m";
  if (!Positive(p.pole_radius)) return "pole_radius: must be in (0, 1e6) m";
  if (!Positive(p.base_radius) || p.base_radius <= p.pole_radius)
    return "base_radius: must exceed pole_radius";
  if (!Positive(p.base_height) || p.base_height >= 0.5 * p.height)
    return "base_height: must be positive and below half the height";
  if (6.0 * p.pole_radius >= p.height - p.base_height)
    return "pole_radius: must be below a sixth of the height above the plinth";
  if (!Positive(p.lantern_radius)) return "lantern_radius: must be in (0, 1e6) m";
  if (!Positive(p.lantern_height)) return "lantern_height: must be in (0, 1e6) m";
  if (std::string e = CheckRings(p.rings, 24, "rings"); !e.empty()) return e;
  return CheckCounts(p.radial_segments, p.profile_count, p.points_per_profile);
}

std::string ValidateChairParameters(const ChairParameters& p) {
  if (!Positive(p.seat_width)) return "seat_width: must be in (0, 1e6) m";
  if (!Positive(p.seat_depth)) return "seat_depth: must be in (0, 1e6) m";
  if (!Positive(p.seat_thickness) || p.seat_thickness >= 0.5 * p.seat_depth)
    return "seat_thickness: must be positive and below half the seat depth";
  if (!Positive(p.seat_height) || p.seat_height <= 2.0 * p.seat_thickness)
    return "seat_height: must exceed twice the seat thickness";
  if (!Positive(p.leg_radius) || p.leg_radius >= 0.1 * std::min(p.seat_width, p.seat_depth))
    return "leg_radius: must be positive and below a tenth of the seat";
  if (!Positive(p.back_height)) return "back_height: must be in (0, 1e6) m";
  if (!Positive(p.back_thickness) || p.back_thickness >= 0.25 * p.seat_depth)
    return "back_thickness: must be positive and below a quarter of the seat depth";
  if (std::string e = CheckRings(p.rings, 8, "rings"); !e.empty()) return e;
  return CheckCounts(p.radial_segments, p.profile_count, p.points_per_profile);
}

Result<ProceduralRigSource> MakeCandleRow(const CandleRowParameters& p) {
  if (std::string error = ValidateCandleRowParameters(p); !error.empty()) return Error{error};
  ProceduralRigSource out;
  const double first_x = -0.5 * p.spacing * (p.count - 1);
  for (int i = 0; i < p.count; ++i) {
    const std::string name = "candle_" + std::to_string(i);
    const Vec3 base(first_x + p.spacing * i, 0.0, 0.0);
    Mesh candle = MakeCylinder(p.radius, p.height, p.radial_segments, p.height_segments);
    Place(candle, Mat3::Identity(), base, name);
    AppendMesh(out.mesh, candle);
    // The axis end to end: the profiles sit at its interior points, k / (profile_count + 1).
    out.description.parts.push_back(Part(name, {base, base + Vec3(0.0, p.height, 0.0)},
                                         p.profile_count, p.points_per_profile,
                                         i == 0 ? std::string() : "candle_0"));
  }
  out.description.mesh = "procedural:candles";
  return out;
}

Result<ProceduralRigSource> MakeBeam(const BeamParameters& p) {
  if (std::string error = ValidateBeamParameters(p); !error.empty()) return Error{error};
  ProceduralRigSource out;
  const Vec3 a(-0.5 * p.length, 0.0, 0.0), b(0.5 * p.length, 0.0, 0.0);
  // Flat ends: a pole right next to each end ring.
  AppendMesh(out.mesh, StraightTube(
                           a, b, p.rings, p.radial_segments,
                           [&](double s) { return s == 0.0 || s == 1.0 ? 0.0 : p.radius; },
                           Vec3::UnitY(), 1.0, "beam"));
  out.description.parts.push_back(Part("beam", {a, b}, p.profile_count, p.points_per_profile, ""));
  out.description.mesh = "procedural:beam";
  return out;
}

Result<ProceduralRigSource> MakeTrunk(const TrunkParameters& p) {
  if (std::string error = ValidateTrunkParameters(p); !error.empty()) return Error{error};
  ProceduralRigSource out;
  // A nearly flat bottom (a pole on the ground just below the first ring), a linear taper with
  // an exponential root flare and two gentle swellings, and a rounded top closed by a pole.
  std::vector<Vec3> centres = {Vec3::Zero()};
  std::vector<double> radii = {0.0};
  const int inner = p.rings - 1;
  for (int k = 0; k < inner; ++k) {
    const double s = 0.01 + 0.97 * k / (inner - 1.0);
    double r = p.top_radius + (p.base_radius - p.top_radius) * (1.0 - s);
    r += p.flare * p.base_radius * std::exp(-s / 0.05);
    r *= 1.0 + 0.04 * std::sin(2.0 * std::numbers::pi * 3.0 * s) * SmoothStep(0.05, 0.2, s);
    if (s > 0.94) r *= std::sqrt(std::max(1.0 - std::pow((s - 0.94) / 0.06, 2.0), 0.05));
    centres.emplace_back(0.0, s * p.height, 0.0);
    radii.push_back(r);
  }
  centres.emplace_back(0.0, p.height, 0.0);
  radii.push_back(0.0);
  AppendMesh(out.mesh, MakeSweptTube(centres, radii, p.radial_segments, "trunk"));
  out.description.parts.push_back(Part("trunk",
                                       {Vec3(0, 0.02 * p.height, 0), Vec3(0, 0.98 * p.height, 0)},
                                       p.profile_count, p.points_per_profile, ""));
  out.description.mesh = "procedural:trunk";
  return out;
}

Result<ProceduralRigSource> MakeLampPost(const LampPostParameters& p) {
  if (std::string error = ValidateLampPostParameters(p); !error.empty()) return Error{error};
  ProceduralRigSource out;
  // The post: a flat-bottomed plinth and a smooth taper to the pole. Its profiles lie between
  // the plinth and the lantern, so they all loop the plain pole (the plinth and the pole's top
  // follow the end profiles).
  auto post_radius = [&](double y) {
    return p.pole_radius +
           (p.base_radius - p.pole_radius) * (1.0 - SmoothStep(0.55, 1.0, y / p.base_height));
  };
  std::vector<Vec3> centres = {Vec3::Zero()};
  std::vector<double> radii = {0.0};
  // A third of the rings on the plinth and taper, the rest up the pole.
  const int base_rings = p.rings / 3, pole_rings = p.rings - 1 - base_rings;
  for (int k = 0; k < base_rings; ++k) {
    const double y = p.base_height * (0.01 + 1.29 * k / double(base_rings));
    centres.emplace_back(0.0, y, 0.0);
    radii.push_back(post_radius(y));
  }
  for (int k = 0; k < pole_rings; ++k) {
    const double y0 = 1.3 * p.base_height, y1 = p.height - 0.01 * p.base_height;
    const double y = y0 + (y1 - y0) * k / (pole_rings - 1.0);
    centres.emplace_back(0.0, y, 0.0);
    radii.push_back(post_radius(y));
  }
  centres.emplace_back(0.0, p.height, 0.0);
  radii.push_back(0.0);
  AppendMesh(out.mesh, MakeSweptTube(centres, radii, p.radial_segments, "post"));
  out.description.parts.push_back(
      Part("post", {Vec3(0, p.base_height, 0), Vec3(0, p.height - 3.0 * p.pole_radius, 0)},
           p.profile_count, p.points_per_profile, ""));

  // The lantern: an egg-shaped globe standing on the post's top.
  const Vec3 bottom(0.0, p.height - 0.2 * p.lantern_height, 0.0);
  const Vec3 top = bottom + Vec3(0.0, p.lantern_height, 0.0);
  AppendMesh(out.mesh, StraightTube(
                           bottom, top, std::max(p.rings / 3, 8), p.radial_segments,
                           [&](double s) {
                             if (s == 0.0 || s == 1.0) return 0.0;  // the poles
                             return p.lantern_radius *
                                    std::pow(std::sin(std::numbers::pi * s), 0.7) *
                                    (1.0 - 0.25 * s);
                           },
                           Vec3::UnitX(), 1.0, "lantern"));
  out.description.parts.push_back(
      Part("lantern", {bottom + 0.05 * (top - bottom), bottom + 0.95 * (top - bottom)}, 6,
           p.points_per_profile, "post"));
  out.description.mesh = "procedural:lamp_post";
  return out;
}

Result<ProceduralRigSource> MakeChair(const ChairParameters& p) {
  if (std::string error = ValidateChairParameters(p); !error.empty()) return Error{error};
  ProceduralRigSource out;
  const double w = p.seat_width, d = p.seat_depth, t = p.seat_thickness;
  // The seat: a tube along X of radius d/2, squashed along Y to the seat's thickness.
  const double seat_y = p.seat_height - 0.5 * t;
  AppendMesh(out.mesh, StraightTube(
                           Vec3(-0.5 * w, seat_y, 0.0), Vec3(0.5 * w, seat_y, 0.0), p.rings,
                           p.radial_segments, [&](double s) { return 0.5 * d * BoxyEnds(s, 6.0); },
                           Vec3::UnitY(), t / d, "seat"));
  out.description.parts.push_back(Part("seat",
                                       {Vec3(-0.47 * w, seat_y, 0.0), Vec3(0.47 * w, seat_y, 0.0)},
                                       p.profile_count, p.points_per_profile, ""));

  // The back: a tube up Y of radius w/2 at the seat's rear, squashed along Z.
  const double back_z = -0.5 * d + 0.5 * p.back_thickness;
  const Vec3 back0(0.0, p.seat_height - 0.5 * t, back_z);
  const Vec3 back1(0.0, p.seat_height + p.back_height, back_z);
  AppendMesh(out.mesh, StraightTube(
                           back0, back1, p.rings, p.radial_segments,
                           [&](double s) { return 0.5 * w * BoxyEnds(s, 6.0); }, Vec3::UnitZ(),
                           p.back_thickness / w, "back"));
  out.description.parts.push_back(Part("back",
                                       {Vec3(0.0, p.seat_height + 0.02 * p.back_height, back_z),
                                        Vec3(0.0, p.seat_height + 0.97 * p.back_height, back_z)},
                                       p.profile_count, p.points_per_profile, "seat"));

  // The legs: tapered round tubes from inside the seat down to the floor, root at the top.
  const double inset = 0.1 * std::min(w, d) + p.leg_radius;
  const double sx[4] = {1, -1, -1, 1}, sz[4] = {1, 1, -1, -1};
  for (int i = 0; i < 4; ++i) {
    const std::string name = "leg_" + std::to_string(i);
    const double x = sx[i] * (0.5 * w - inset), z = sz[i] * (0.5 * d - inset);
    const Vec3 top(x, seat_y, z), floor(x, 0.0, z);
    AppendMesh(out.mesh, StraightTube(
                             top, floor, p.rings, p.radial_segments,
                             [&](double s) {
                               // Flat ends: a pole right next to the end ring.
                               if (s == 0.0 || s == 1.0) return 0.0;
                               return p.leg_radius * (1.0 - 0.2 * s);
                             },
                             Vec3::UnitX(), 1.0, name));
    out.description.parts.push_back(Part(name,
                                         {Vec3(x, p.seat_height - t - 0.01, z), Vec3(x, 0.01, z)},
                                         p.profile_count, p.points_per_profile, "seat"));
  }
  out.description.mesh = "procedural:chair";
  return out;
}

}  // namespace wirerig
