// Checks that a command's output is none of the files it reads, so that no command replaces
// its own input (a bake written over the scene's mesh, a rig over its description).
#pragma once

#include <filesystem>

#include "wirerig/anim/scene.h"
#include "wirerig/io/result.h"

namespace wirerig::cli {

// Refuses an `output` that is the scene file or a file the scene reads (SceneInputFiles: its
// mesh, rig or description, motion files and mappings). A scene that cannot be read passes:
// loading it reports why.
Result<bool> CheckOutputIsNoSceneInput(const std::filesystem::path& output,
                                       const std::filesystem::path& scene_file);
// The same with the scene already read (nothing parsed again).
Result<bool> CheckOutputIsNoSceneInput(const std::filesystem::path& output,
                                       const std::filesystem::path& scene_file,
                                       const SceneDescription& scene);

}  // namespace wirerig::cli
