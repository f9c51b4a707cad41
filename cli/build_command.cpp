#include "build_command.h"

#include <ostream>

#include <CLI/CLI.hpp>

#include "wirerig/anim/scene.h"
#include "wirerig/rig/atomic_file.h"
#include "wirerig/runtime/rig_asset.h"

namespace wirerig::cli {

CLI::App* AddBuildCommand(CLI::App& app, BuildCommandOptions& options) {
  CLI::App* build =
      app.add_subcommand("build", "Build a scene's rig into a runtime asset (.wrig) for engines");
  build->add_option("scene", options.scene, "Scene file (JSON)")->required();
  build->add_option("-o,--output", options.output, "Output file (.wrig)")->required();
  return build;
}

int RunBuildCommand(const BuildCommandOptions& options, std::ostream& out, std::ostream& err) {
  auto fail = [&](const std::string& message) {
    err << "wirerig build: " << message << "\n";
    return 1;
  };
  if (std::filesystem::path(options.output).extension() != ".wrig")
    return fail(options.output + ": the output must be a .wrig file");
  Result<BuiltScene> built = LoadAndBuildScene(options.scene);
  if (!built) return fail(built.error());
  RigAsset asset;
  asset.model = std::move(built.value().model);
  asset.vertex_order = std::move(built.value().mesh.weld_map);
  if (Status valid = ValidateRigModel(asset.model); !valid)
    return fail(options.scene + ": the built rig is not valid: " + ToString(valid));
  const std::vector<std::uint8_t> bytes = SerializeRigAsset(asset);
  const auto written = WriteFileAtomically(
      options.output, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  if (!written) return fail(written.error());
  out << "rig asset: " << asset.model.parts.size() << " parts, " << asset.model.vertices.size()
      << " welded vertices (" << asset.vertex_order.size() << " in the source order), "
      << asset.model.triangles.size() << " triangles, " << bytes.size() << " bytes\n"
      << "written: " << options.output << "\n";
  return 0;
}

}  // namespace wirerig::cli
