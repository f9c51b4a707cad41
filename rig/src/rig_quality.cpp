#include "wirerig/rig/rig_quality.h"

#include <algorithm>

namespace wirerig {
namespace {

constexpr double kCrossingFraction = 0.1;  // "usable" allows fewer crossing profiles than this

}  // namespace

RigQuality AssessRig(const BuiltRig& built) {
  RigQuality q;
  q.vertices = built.rig.mesh_vertices;
  for (std::size_t i = 0; i < built.rig.parts.size(); ++i) {
    const PartReport& r = built.report.parts[i];
    const std::size_t kept = built.rig.parts[i].profiles.size();
    q.bound_vertices += r.vertices;
    q.profiles += kept;
    q.crossing_profiles += r.profiles.self_intersecting + r.profiles.crossing_neighbour;
    q.escaped_rays += r.profiles.misses;
    q.dropped_profiles += r.profiles.outside_profiles + r.profiles.empty_profiles;
    if (kept < 2 && built.rig.parts[i].skin)  // a skinless bone has none by design
      q.parts_without_profiles.push_back(built.rig.parts[i].name);
  }
  q.warnings = built.report.warnings.size();
  std::vector<std::string> reasons;
  if (q.bound_vertices < q.vertices)
    reasons.push_back(std::to_string(q.vertices - q.bound_vertices) + " vertices unbound");
  if (!q.parts_without_profiles.empty())
    reasons.push_back(std::to_string(q.parts_without_profiles.size()) + " parts without profiles");
  const bool many_crossing = double(q.crossing_profiles) >=
                             kCrossingFraction * double(std::max<std::size_t>(q.profiles, 1));
  if (many_crossing)
    reasons.push_back(std::to_string(q.crossing_profiles) + " of " + std::to_string(q.profiles) +
                      " profiles cross");
  if (q.warnings == 0) {
    q.verdict = "good";
  } else if (reasons.empty()) {
    q.verdict = "usable: " + std::to_string(q.warnings) + " warnings";
  } else {
    q.verdict = "poor:";
    for (std::size_t i = 0; i < reasons.size(); ++i)
      q.verdict += (i == 0 ? " " : ", ") + reasons[i];
  }
  return q;
}

}  // namespace wirerig
