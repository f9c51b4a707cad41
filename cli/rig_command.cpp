#include "rig_command.h"
#include "option_checks.h"
#include "text_format.h"

#include <cstdio>
#include <ostream>

#include <CLI/CLI.hpp>

#include "wirerig/io/output_file.h"
#include "wirerig/rig/automatic_description.h"
#include "wirerig/rig/joint_skin_report.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/mesh_statistics.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_file.h"
#include "wirerig/rig/rig_model_builder.h"
#include "wirerig/rig/rig_quality.h"

namespace wirerig::cli {
namespace {

void PrintMeshSummary(std::ostream& out, const std::string& path, const ImportedMesh& imported) {
  const Mesh& mesh = imported.mesh;
  const ImportReport& r = imported.report;
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  out << Format("mesh: %s (%s): %zu vertices (welded from %zu), %zu triangles, %zu mesh parts\n",
                path.c_str(), r.format.c_str(), stats.vertices, stats.render_vertices,
                stats.triangles, mesh.parts.size());
  out << Format("  up axis +%s (%s), %g m per unit (%s)\n",
                std::string(ToString(r.source_up)).c_str(), r.up_source.c_str(), r.unit_scale,
                r.unit_source.c_str());
  out << Format(
      "  %zu components, %zu boundary edges, %zu non-manifold edges, %zu degenerate "
      "triangles, %zu joints\n",
      stats.connected_components, stats.boundary_edges, stats.non_manifold_edges,
      stats.degenerate_triangles, mesh.joints.size());
}

void PrintRigSummary(std::ostream& out, const BuiltRig& built, const std::string& source) {
  out << "rig: " << built.rig.parts.size() << " parts from " << source << "\n";
  out << Format("  %-22s %-16s %8s %9s %8s %7s %6s %6s %5s %5s\n", "part", "parent", "vertices",
                "triangles", "profiles", "points", "misses", "other", "open", "cross");
  for (std::size_t i = 0; i < built.rig.parts.size(); ++i) {
    const RigPart& part = built.rig.parts[i];
    const PartReport& r = built.report.parts[i];
    std::size_t points = 0;
    for (const ProfileCurve& p : part.profiles) points += p.points.size();
    const std::string parent = part.parent >= 0 ? built.rig.parts[part.parent].name : "-";
    out << Format("  %-22s %-16s %8zu %9zu %5zu/%-2d %7zu %6zu %6zu %5zu %5zu\n", part.name.c_str(),
                  parent.c_str(), r.vertices, r.triangles, part.profiles.size(), part.profile_count,
                  points, r.profiles.misses, r.profiles.other_part_hits, r.profiles.open_profiles,
                  r.profiles.crossing_neighbour + r.profiles.self_intersecting);
  }
  if (built.report.warnings.empty()) {
    out << "warnings: none\n";
  } else {
    out << "warnings:\n";
    for (const std::string& w : built.report.warnings) out << "  " << w << "\n";
  }
  for (const std::string& note : built.report.notes) out << "note: " << note << "\n";
  const RigQuality q = AssessRig(built);
  std::string without;
  for (const std::string& name : q.parts_without_profiles) without += " " + name;
  out << Format(
      "quality: %.1f%% of the vertices bound (%zu of %zu), %zu of %zu profiles cross, "
      "%zu rays left the surface, %zu profiles dropped, %zu parts without profiles%s\n",
      100.0 * double(q.bound_vertices) / double(std::max<std::size_t>(q.vertices, 1)),
      q.bound_vertices, q.vertices, q.crossing_profiles, q.profiles, q.escaped_rays,
      q.dropped_profiles, q.parts_without_profiles.size(),
      without.empty() ? "" : (":" + without).c_str());
  out << "verdict: " << q.verdict << "\n";
}

// Per joint, the worst case over its sweep for each method, and the worst over all joints.
void PrintJointReport(std::ostream& out, const std::vector<JointSkinRow>& rows) {
  out << "joint skin (worst over each joint's sweep: folded edges / worst stretch / limb volume "
         "ratio / smallest perimeter ratio):\n";
  out << Format("  %-14s", "joint");
  for (int m = 0; m < kSkinMethods; ++m) out << Format(" | %-27s", SkinMethodName(m));
  out << "\n";
  std::array<SkinMeasures, kSkinMethods> all;
  auto print = [&](const std::string& name, const std::array<SkinMeasures, kSkinMethods>& w) {
    out << Format("  %-14s", name.c_str());
    for (const SkinMeasures& m : w)
      out << Format(" | %4zu %6.2f %6.3f %6.3f   ", m.folded_edges, m.worst_stretch, m.volume_ratio,
                    m.smallest_perimeter);
    out << "\n";
  };
  for (std::size_t i = 0; i < rows.size();) {
    std::array<SkinMeasures, kSkinMethods> worst;
    const std::string& joint = rows[i].joint;
    for (; i < rows.size() && rows[i].joint == joint; ++i)
      for (int m = 0; m < kSkinMethods; ++m) worst[m].Worst(rows[i].methods[m]);
    for (int m = 0; m < kSkinMethods; ++m) all[m].Worst(worst[m]);
    print(joint, worst);
  }
  print("all joints", all);
}

// The targets of the articulated-characters issue: no folded edge, no edge beyond 2x, limb
// volume within 3%, smallest perimeter above 90%.
bool MeetsSkinTargets(const SkinMeasures& m) {
  return m.folded_edges == 0 && m.worst_stretch <= 2.0 && std::abs(m.volume_ratio - 1.0) <= 0.03 &&
         m.smallest_perimeter >= 0.9;
}

// Each pose whose wire-rig skin misses a target, with its measures.
void PrintMissedPoses(std::ostream& out, const std::vector<JointSkinRow>& rows) {
  out << "poses where the wire rig misses a target (folded edges / worst stretch / limb volume "
         "ratio / smallest perimeter ratio):\n";
  for (const JointSkinRow& row : rows) {
    const SkinMeasures& m = row.methods[0];
    if (MeetsSkinTargets(m)) continue;
    out << Format("  %-14s %-10s %4zu %6.2f %6.3f %6.3f\n", row.joint.c_str(), row.pose.c_str(),
                  m.folded_edges, m.worst_stretch, m.volume_ratio, m.smallest_perimeter);
  }
}

}  // namespace

CLI::App* AddRigCommand(CLI::App& app, RigCommandOptions& options) {
  CLI::App* rig = app.add_subcommand("rig", "Build a rig (profile and spine curves) from a mesh");
  rig->add_option("mesh", options.mesh, "Mesh file (any format Assimp reads)")->required();
  rig->add_option("-d,--description", options.description,
                  "Rig description (JSON): parts and rough central curves");
  rig->add_option("-o,--output", options.output, "Rig file to write (JSON)")->required();
  rig->add_option("--up", options.up_axis, "Source up axis, overriding the file")
      ->check(CLI::IsMember({"x", "y", "z"}));
  rig->add_option("--unit-scale", options.unit_scale, "Metres per source unit, overriding the file")
      ->check(InRange(1e-12, 1e12));  // the importer's range (ImportOptions::unit_scale)
  rig->add_option("--skin-thickness", options.skin_thickness,
                  "Skin thickness for wire sections (m)")
      ->check(Above(0))
      ->capture_default_str();
  rig->add_flag("--strict", options.strict,
                "Refuse the rig (write nothing, exit 1) when its build has any warning");
  rig->add_flag("--ignore-skeleton", options.ignore_skeleton,
                "Without a description: rig from the surface even if the file has bones");
  rig->add_option("--wrap-alpha", options.wrap_alpha,
                  "Without a description, for an open, non-manifold or many-piece mesh: the size "
                  "(m) of the watertight wrap its skeleton is taken from (default: its bounding "
                  "box diagonal / 60; at least the diagonal / 200)")
      ->check(Above(0));
  rig->add_flag("--joint-report", options.joint_report,
                "Bend every joint through 30-120 degrees and a 90-degree twist; print folded "
                "edges, stretch, limb volume and cross-section perimeters per skinning method");
  rig->add_flag("--joint-poses", options.joint_poses,
                "With --joint-report: also list each pose where the wire rig misses a target");
  // Options that do not apply are refused, not ignored.
  rig->callback([rig, &options] {
    if (options.joint_poses && !options.joint_report)
      throw CLI::ValidationError("--joint-poses", "lists the poses of --joint-report: give both");
    if (!options.description.empty())
      for (const char* name : {"--ignore-skeleton", "--wrap-alpha"})
        if (rig->count(name) > 0)
          throw CLI::ValidationError(name,
                                     "applies without a description only (the "
                                     "description gives the parts)");
  });
  AddImportLimitOptions(rig, options.import_limits);
  return rig;
}

int RunRigCommand(const RigCommandOptions& options, std::ostream& out, std::ostream& err) {
  auto fail = [&](const std::string& message) {
    err << "wirerig rig: " << message << "\n";
    return 1;
  };
  // Where the rig goes is checked before any work.
  if (Result<bool> writable = CheckOutputFile(options.output, {".json"}); !writable)
    return fail(writable.error());
  for (const auto& [input, what] :
       {std::pair{options.mesh, "the mesh"}, std::pair{options.description, "the rig description"}})
    if (Result<bool> own = CheckNotAnInput(options.output, input, what); !own)
      return fail(own.error());
  RigDescription description;
  std::string source;
  if (!options.description.empty()) {
    Result<RigDescription> loaded = LoadRigDescription(options.description);
    if (!loaded) return fail(loaded.error());
    description = std::move(loaded).value();
    source = options.description;
  }
  ImportOptions import = description.import;
  if (!options.up_axis.empty()) {
    UpAxis axis;
    ParseUpAxis(options.up_axis, &axis);
    import.up_axis = axis;
  }
  if (options.unit_scale > 0.0) import.unit_scale = options.unit_scale;
  import.isolation =
      options.import_limits.Isolation();  // a crash or hang of Assimp must not take wirerig down
  Result<ImportedMesh> imported = ImportMesh(options.mesh, import);
  if (!imported) return fail(imported.error());
  const Mesh& mesh = imported.value().mesh;
  PrintMeshSummary(out, options.mesh, imported.value());

  std::optional<Mesh> wrap;  // the watertight stand-in of an open mesh, if the rig came from one
  if (options.description.empty()) {
    AutomaticOptions automatic_options;
    automatic_options.ignore_skeleton = options.ignore_skeleton;
    automatic_options.wrap_alpha = options.wrap_alpha;
    Result<AutomaticDescription> automatic = DescribeAutomatically(mesh, automatic_options);
    if (!automatic) return fail(options.mesh + ": " + automatic.error());
    source = automatic.value().source;
    wrap = std::move(automatic.value().wrap);
    if (!wrap && options.wrap_alpha > 0.0)
      out << "note: --wrap-alpha unused: this rig needed no wrap (" << source << ")\n";
    description = std::move(automatic).value().description;
    description.import = import;
  }
  RigBuildOptions build_options;
  build_options.skin_thickness = options.skin_thickness;
  build_options.wrap = wrap ? &*wrap : nullptr;
  build_options.drop_parts_without_profiles = options.description.empty();
  Result<BuiltRig> built = BuildRig(mesh, description, options.mesh, build_options);
  if (!built) return fail(options.mesh + ": " + built.error());
  PrintRigSummary(out, built.value(), source);
  if (options.strict && !built.value().report.warnings.empty())
    return fail(options.mesh +
                ": --strict: " + std::to_string(built.value().report.warnings.size()) +
                " warnings (listed above); nothing written");
  if (options.joint_report) {
    RigModelOptions model_options;
    model_options.spine_kind = SpineKind::kRigid;
    Result<BuiltRigModel> model = BuildRigModel(mesh, built.value().rig, model_options);
    if (!model) return fail(options.mesh + ": " + model.error());
    const std::vector<JointSkinRow> rows =
        MeasureJointSweep(model.value().model, mesh.welded_positions);
    PrintJointReport(out, rows);
    if (options.joint_poses) PrintMissedPoses(out, rows);
  }
  const auto saved = SaveRig(built.value().rig, options.output);
  if (!saved) return fail(saved.error());
  out << "written: " << options.output << "\n";
  return 0;
}

}  // namespace wirerig::cli
