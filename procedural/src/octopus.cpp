#include "wirerig/procedural/octopus.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "wirerig/procedural/shapes.h"

namespace wirerig {
namespace {

// The mantle's centre line and radii: an egg from a pole at y = 0 to a pole at the top,
// fuller below its middle.
void MantleShape(const OctopusParameters& p, std::vector<Vec3>* centres,
                 std::vector<double>* radii) {
  for (int k = 0; k <= p.rings; ++k) {
    const double s = static_cast<double>(k) / p.rings;
    centres->emplace_back(0.0, p.mantle_height * s, 0.0);
    // sin(pi s)^0.7 rounds both ends; the (1.15 - 0.3 s) factor fattens the lower half.
    const double shape = std::pow(std::sin(std::numbers::pi * s), 0.7) * (1.15 - 0.3 * s) / 1.15;
    radii->push_back(k == 0 || k == p.rings ? 0.0 : p.mantle_radius * shape);
  }
}

// Tentacle i's centre line, root (inside the mantle's lower half) to tip.
Vec3 TentaclePoint(const OctopusParameters& p, int i, double s) {
  const double angle = 2.0 * std::numbers::pi * (i + 0.5) / p.tentacle_count;
  const Vec3 out(std::cos(angle), 0.0, -std::sin(angle));
  const double root_radius = 0.45 * p.mantle_radius;
  const double root_height = 0.22 * p.mantle_height;
  const double l = p.tentacle_length;
  // Outwards quickly near the root, then mostly downwards: a quarter-ellipse arc.
  const double reach = p.spread * l * std::sin(0.5 * std::numbers::pi * s);
  const double drop =
      (1.0 - p.spread) * l * (1.0 - std::cos(0.5 * std::numbers::pi * s)) + 0.25 * l * s;
  return out * (root_radius + reach) + Vec3(0.0, root_height - drop, 0.0);
}

}  // namespace

std::string ValidateOctopusParameters(const OctopusParameters& p) {
  auto positive = [](double x) { return std::isfinite(x) && x > 0.0 && x < 1e6; };
  if (!positive(p.mantle_radius)) return "mantle_radius: must be in (0, 1e6) m";
  if (!positive(p.mantle_height)) return "mantle_height: must be in (0, 1e6) m";
  if (p.tentacle_count < 1 || p.tentacle_count > 64) return "tentacle_count: must be in [1, 64]";
  if (!positive(p.tentacle_length)) return "tentacle_length: must be in (0, 1e6) m";
  if (!positive(p.tentacle_radius)) return "tentacle_radius: must be in (0, 1e6) m";
  if (!positive(p.tip_radius) || p.tip_radius >= p.tentacle_radius)
    return "tip_radius: must be positive and below tentacle_radius";
  if (!(p.spread >= 0.0 && p.spread <= 1.0)) return "spread: must be in [0, 1]";
  if (p.radial_segments < 6 || p.radial_segments > 512)
    return "radial_segments: must be in [6, 512]";
  if (p.rings < 8 || p.rings > 4096) return "rings: must be in [8, 4096]";
  if (p.profile_count < 2 || p.profile_count > p.rings)
    return "profile_count: must be in [2, rings]";
  if (p.points_per_profile < 3 || p.points_per_profile > 1024)
    return "points_per_profile: must be in [3, 1024]";
  return {};
}

Result<ProceduralRigSource> MakeOctopus(const OctopusParameters& p) {
  if (std::string error = ValidateOctopusParameters(p); !error.empty()) return Error{error};
  ProceduralRigSource out;
  std::vector<Vec3> centres;
  std::vector<double> radii;
  MantleShape(p, &centres, &radii);
  AppendMesh(out.mesh, MakeSweptTube(centres, radii, p.radial_segments, "mantle"));
  PartDescription mantle;
  mantle.name = "mantle";
  mantle.central_curve = {Vec3(0, 0.02 * p.mantle_height, 0), Vec3(0, 0.98 * p.mantle_height, 0)};
  mantle.profile_count = 12;
  mantle.points_per_profile = p.points_per_profile;
  mantle.mesh_parts = {"mantle"};
  out.description.parts.push_back(mantle);

  for (int i = 0; i < p.tentacle_count; ++i) {
    const std::string name = "tentacle_" + std::to_string(i);
    centres.clear();
    radii.clear();
    // A pole just behind the root ring and one at the tip.
    for (int k = 0; k <= p.rings; ++k) {
      const double s = static_cast<double>(k) / p.rings;
      centres.push_back(TentaclePoint(p, i, s));
      const double taper = p.tentacle_radius + (p.tip_radius - p.tentacle_radius) * s;
      radii.push_back(k == 0 || k == p.rings ? 0.0 : taper);
    }
    AppendMesh(out.mesh, MakeSweptTube(centres, radii, p.radial_segments, name));
    PartDescription tentacle;
    tentacle.name = name;
    for (int k = 0; k <= 6; ++k) {
      // The central curve stays clear of the end poles, where profiles would be degenerate.
      const double s = 1.5 / p.rings + (1.0 - 3.0 / p.rings) * k / 6.0;
      tentacle.central_curve.push_back(TentaclePoint(p, i, s));
    }
    tentacle.profile_count = p.profile_count;
    tentacle.points_per_profile = p.points_per_profile;
    tentacle.parent = "mantle";
    tentacle.mesh_parts = {name};
    out.description.parts.push_back(tentacle);
  }
  out.description.mesh = "procedural:octopus";
  return out;
}

}  // namespace wirerig
