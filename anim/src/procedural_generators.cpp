#include "procedural_generators.h"

#include <cmath>
#include <utility>

#include "wirerig/procedural/octopus.h"
#include "wirerig/procedural/props.h"
#include "wirerig/procedural/shapes.h"

namespace wirerig::detail {
namespace {

double Parameter(const MeshSource& source, const std::string& name, double fallback) {
  const auto it = source.parameters.find(name);
  return it == source.parameters.end() ? fallback : it->second;
}

// A parameter that must be a positive length (m) or a count in [lo, hi].
std::string CheckLength(double value, const char* name) {
  if (std::isfinite(value) && value > 0.0 && value < 1e6) return {};
  return std::string("/mesh/parameters/") + name + ": must be a positive length (m)";
}
std::string CheckCount(double value, const char* name, double lo, double hi) {
  if (value >= lo && value <= hi && value == std::floor(value)) return {};
  return std::string("/mesh/parameters/") + name + ": must be a whole number in [" +
         std::to_string(int(lo)) + ", " + std::to_string(int(hi)) + "]";
}
// A generator's count before its own check: a whole number, at least 1. Every generator's own
// range ends at or below 4096 (what any generator may allocate), so a larger count is handed on
// as 4097 (kCountPastEveryRange) for the generator to refuse with its own range, rather than a
// bound that is not the one that holds (radial_segments: "at most 4096", then "[6, 512]").
constexpr int kCountPastEveryRange = 4097;
std::string CheckAnyCount(double value, const char* name) {
  if (!(value == std::floor(value)) || value < 1.0)
    return std::string("/mesh/parameters/") + name + ": must be a whole number >= 1";
  return {};
}
std::string FirstError(std::initializer_list<std::string> errors) {
  for (const std::string& e : errors)
    if (!e.empty()) return e;
  return {};
}

// A generator with its own rig description (wirerig/procedural/octopus.h, props.h):
// its lengths (m, or fractions) and counts by name over its defaults, then the generator,
// which checks them (its error names the parameter).
template <typename Parameters>
struct DescribedShape {
  std::vector<std::pair<const char*, double Parameters::*>> lengths;
  std::vector<std::pair<const char*, int Parameters::*>> counts;
  Result<ProceduralRigSource> (*make)(const Parameters&);

  std::vector<std::string> Names() const {
    std::vector<std::string> names;
    for (const auto& [name, field] : lengths) names.emplace_back(name);
    for (const auto& [name, field] : counts) names.emplace_back(name);
    return names;
  }

  Result<GeneratedMesh> Generate(const MeshSource& source) const {
    Parameters parameters;
    for (auto [name, field] : lengths)
      parameters.*field = Parameter(source, name, parameters.*field);
    for (auto [name, field] : counts) {
      const double value = Parameter(source, name, parameters.*field);
      if (std::string e = CheckAnyCount(value, name); !e.empty()) return Error{e};
      parameters.*field =
          value < kCountPastEveryRange ? static_cast<int>(value) : kCountPastEveryRange;
    }
    Result<ProceduralRigSource> made = make(parameters);
    if (!made) return Error{"/mesh/parameters/" + made.error()};
    return GeneratedMesh{std::move(made.value().mesh), std::move(made.value().description)};
  }
};

// The sampling counts every prop shares.
template <typename P>
std::vector<std::pair<const char*, int P::*>> PropCounts() {
  return {{"radial_segments", &P::radial_segments},
          {"rings", &P::rings},
          {"profile_count", &P::profile_count},
          {"points_per_profile", &P::points_per_profile}};
}

const DescribedShape<OctopusParameters>& Octopus() {
  using P = OctopusParameters;
  static const DescribedShape<P> shape{{{"mantle_radius", &P::mantle_radius},
                                        {"mantle_height", &P::mantle_height},
                                        {"tentacle_length", &P::tentacle_length},
                                        {"tentacle_radius", &P::tentacle_radius},
                                        {"tip_radius", &P::tip_radius},
                                        {"spread", &P::spread}},
                                       {{"tentacle_count", &P::tentacle_count},
                                        {"radial_segments", &P::radial_segments},
                                        {"rings", &P::rings},
                                        {"profile_count", &P::profile_count},
                                        {"points_per_profile", &P::points_per_profile}},
                                       &MakeOctopus};
  return shape;
}

const DescribedShape<CandleRowParameters>& Candles() {
  using P = CandleRowParameters;
  static const DescribedShape<P> shape{
      {{"radius", &P::radius}, {"height", &P::height}, {"spacing", &P::spacing}},
      {{"count", &P::count},
       {"radial_segments", &P::radial_segments},
       {"height_segments", &P::height_segments},
       {"profile_count", &P::profile_count},
       {"points_per_profile", &P::points_per_profile}},
      &MakeCandleRow};
  return shape;
}

const DescribedShape<BeamParameters>& Beam() {
  using P = BeamParameters;
  static const DescribedShape<P> shape{
      {{"length", &P::length}, {"radius", &P::radius}}, PropCounts<P>(), &MakeBeam};
  return shape;
}

const DescribedShape<TrunkParameters>& Trunk() {
  using P = TrunkParameters;
  static const DescribedShape<P> shape{{{"height", &P::height},
                                        {"base_radius", &P::base_radius},
                                        {"top_radius", &P::top_radius},
                                        {"flare", &P::flare}},
                                       PropCounts<P>(),
                                       &MakeTrunk};
  return shape;
}

const DescribedShape<LampPostParameters>& LampPost() {
  using P = LampPostParameters;
  static const DescribedShape<P> shape{{{"height", &P::height},
                                        {"pole_radius", &P::pole_radius},
                                        {"base_radius", &P::base_radius},
                                        {"base_height", &P::base_height},
                                        {"lantern_radius", &P::lantern_radius},
                                        {"lantern_height", &P::lantern_height}},
                                       PropCounts<P>(),
                                       &MakeLampPost};
  return shape;
}

const DescribedShape<ChairParameters>& Chair() {
  using P = ChairParameters;
  static const DescribedShape<P> shape{{{"seat_width", &P::seat_width},
                                        {"seat_depth", &P::seat_depth},
                                        {"seat_height", &P::seat_height},
                                        {"seat_thickness", &P::seat_thickness},
                                        {"leg_radius", &P::leg_radius},
                                        {"back_height", &P::back_height},
                                        {"back_thickness", &P::back_thickness}},
                                       PropCounts<P>(),
                                       &MakeChair};
  return shape;
}

// The plain shapes (wirerig/procedural/shapes.h): no rig of their own.
Result<GeneratedMesh> Shape(std::string error, auto make) {
  if (!error.empty()) return Error{std::move(error)};
  return GeneratedMesh{make(), {}};
}

Result<GeneratedMesh> GenerateCylinder(const MeshSource& s) {
  const double radius = Parameter(s, "radius", 0.1), height = Parameter(s, "height", 1.0);
  const double radial = Parameter(s, "radial_segments", 32);
  const double segments = Parameter(s, "height_segments", 16);
  return Shape(FirstError({CheckLength(radius, "radius"), CheckLength(height, "height"),
                           CheckCount(radial, "radial_segments", 3, 4096),
                           CheckCount(segments, "height_segments", 1, 4096)}),
               [&] { return MakeCylinder(radius, height, int(radial), int(segments)); });
}

Result<GeneratedMesh> GenerateCone(const MeshSource& s) {
  const double r0 = Parameter(s, "r0", 0.1), r1 = Parameter(s, "r1", 0.05);
  const double height = Parameter(s, "height", 1.0);
  const double radial = Parameter(s, "radial_segments", 32);
  const double segments = Parameter(s, "height_segments", 16);
  return Shape(
      FirstError({CheckLength(r0, "r0"), r1 == 0.0 ? std::string() : CheckLength(r1, "r1"),
                  CheckLength(height, "height"), CheckCount(radial, "radial_segments", 3, 4096),
                  CheckCount(segments, "height_segments", 1, 4096)}),
      [&] { return MakeCone(r0, r1, height, int(radial), int(segments)); });
}

Result<GeneratedMesh> GenerateCapsule(const MeshSource& s) {
  const double radius = Parameter(s, "radius", 0.1), height = Parameter(s, "height", 1.0);
  const double radial = Parameter(s, "radial_segments", 32);
  const double segments = Parameter(s, "height_segments", 16);
  const double rings = Parameter(s, "cap_rings", 8);
  return Shape(FirstError({CheckLength(radius, "radius"),
                           height == 0.0 ? std::string() : CheckLength(height, "height"),
                           CheckCount(radial, "radial_segments", 3, 4096),
                           CheckCount(segments, "height_segments", 1, 4096),
                           CheckCount(rings, "cap_rings", 1, 4096)}),
               [&] { return MakeCapsule(radius, height, int(radial), int(segments), int(rings)); });
}

Result<GeneratedMesh> GenerateTorus(const MeshSource& s) {
  const double major = Parameter(s, "major_radius", 0.5), minor = Parameter(s, "minor_radius", 0.1);
  const double rings = Parameter(s, "ring_segments", 48), tube = Parameter(s, "tube_segments", 24);
  return Shape(
      FirstError({CheckLength(major, "major_radius"), CheckLength(minor, "minor_radius"),
                  minor < major
                      ? std::string()
                      : std::string("/mesh/parameters/minor_radius: must be below major_radius"),
                  CheckCount(rings, "ring_segments", 3, 4096),
                  CheckCount(tube, "tube_segments", 3, 4096)}),
      [&] { return MakeTorus(major, minor, int(rings), int(tube)); });
}

// Plain shapes: a light clay; the samples each get a colour of their own.
const Vec4 kClay(0.60, 0.60, 0.62, 1.0);

std::vector<ProceduralGenerator> MakeRegistry() {
  return {
      {"octopus", Octopus().Names(), true, Vec4(0.62, 0.16, 0.09, 1.0),
       [](const MeshSource& s) { return Octopus().Generate(s); }},
      {"cylinder",
       {"radius", "height", "radial_segments", "height_segments"},
       false,
       kClay,
       &GenerateCylinder},
      {"cone",
       {"r0", "r1", "height", "radial_segments", "height_segments"},
       false,
       kClay,
       &GenerateCone},
      {"capsule",
       {"radius", "height", "radial_segments", "height_segments", "cap_rings"},
       false,
       kClay,
       &GenerateCapsule},
      {"torus",
       {"major_radius", "minor_radius", "ring_segments", "tube_segments"},
       false,
       kClay,
       &GenerateTorus},
      // The paper's props (wirerig/procedural/props.h), each with its own rig description.
      {"candles", Candles().Names(), true, Vec4(0.85, 0.78, 0.60, 1.0),
       [](const MeshSource& s) { return Candles().Generate(s); }},
      {"beam", Beam().Names(), true, Vec4(0.50, 0.52, 0.55, 1.0),
       [](const MeshSource& s) { return Beam().Generate(s); }},
      {"trunk", Trunk().Names(), true, Vec4(0.23, 0.13, 0.06, 1.0),
       [](const MeshSource& s) { return Trunk().Generate(s); }},
      {"lamp_post", LampPost().Names(), true, Vec4(0.05, 0.06, 0.06, 1.0),
       [](const MeshSource& s) { return LampPost().Generate(s); }},
      {"chair", Chair().Names(), true, Vec4(0.40, 0.22, 0.10, 1.0),
       [](const MeshSource& s) { return Chair().Generate(s); }},
  };
}

}  // namespace

std::span<const ProceduralGenerator> ProceduralGenerators() {
  static const std::vector<ProceduralGenerator> registry = MakeRegistry();
  return registry;
}

const ProceduralGenerator* FindProceduralGenerator(std::string_view name) {
  for (const ProceduralGenerator& generator : ProceduralGenerators())
    if (generator.name == name) return &generator;
  return nullptr;
}

std::string ProceduralGeneratorNames(bool describing_rig_only) {
  std::string names;
  for (const ProceduralGenerator& generator : ProceduralGenerators()) {
    if (describing_rig_only && !generator.describes_rig) continue;
    if (!names.empty()) names += ", ";
    names += generator.name;
  }
  return names;
}

}  // namespace wirerig::detail
