#include "output_checks.h"

#include "wirerig/io/output_file.h"

namespace wirerig::cli {

Result<bool> CheckOutputIsNoSceneInput(const std::filesystem::path& output,
                                       const std::filesystem::path& scene_file,
                                       const SceneDescription& scene) {
  if (Result<bool> checked = CheckNotAnInput(output, scene_file, "the scene file"); !checked)
    return checked;
  for (const auto& [input, what] : SceneInputFiles(scene))
    if (Result<bool> checked = CheckNotAnInput(output, input, what); !checked) return checked;
  return true;
}

Result<bool> CheckOutputIsNoSceneInput(const std::filesystem::path& output,
                                       const std::filesystem::path& scene_file) {
  const Result<SceneDescription> scene = LoadScene(scene_file);
  if (!scene) return CheckNotAnInput(output, scene_file, "the scene file");
  return CheckOutputIsNoSceneInput(output, scene_file, scene.value());
}

}  // namespace wirerig::cli
