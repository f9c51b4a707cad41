// `wirerig rig MESH [--description DESC.json] -o RIG.json`: the whole rig-building pipeline.
// Central curves come from the description when given, else from the asset's skeleton, else
// from the mesh's curve skeleton. Prints a diagnostic summary; writes the rig atomically.
// --joint-report: every joint bent through its sweep (joint_skin_report.h), the skin measured
// for the wire rig and for linear blend, dual-quaternion and centre-of-rotation skinning.
#pragma once

#include <iosfwd>
#include <string>

#include <CLI/App.hpp>

#include "import_limits.h"

namespace wirerig::cli {

struct RigCommandOptions {
  std::string mesh;
  std::string description;  // optional
  std::string output;       // required
  std::string up_axis;      // optional override: x, y or z
  double unit_scale = 0.0;  // optional override (metres per unit), 0 = unset
  double skin_thickness = 0.005;
  bool joint_report = false;     // sweep every joint; print the skin measures per method
  bool joint_poses = false;      // with joint_report: also each pose where the wire rig misses
  bool strict = false;           // warnings are errors: nothing written
  bool ignore_skeleton = false;  // automatic: describe from the surface, not the file's bones
  double wrap_alpha = 0.0;       // automatic, open meshes: the wrap's alpha (m); 0 = from the mesh
  ImportLimitOptions import_limits;
};

CLI::App* AddRigCommand(CLI::App& app, RigCommandOptions& options);

// 0 on success; 1 with a message naming the file and problem on `err` otherwise (and no
// output file).
int RunRigCommand(const RigCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace wirerig::cli
