#include "output_checks.h"

#include "wirerig/anim/scene.h"
#include "wirerig/io/output_file.h"

namespace wirerig::cli {

Result<bool> CheckOutputIsNoSceneInput(const std::filesystem::path& output,
                                       const std::filesystem::path& scene_file) {
  if (Result<bool> checked = CheckNotAnInput(output, scene_file, "the scene file"); !checked)
    return checked;
  const Result<SceneDescription> scene = LoadScene(scene_file);
  if (!scene) return true;
  for (const auto& [input, what] : SceneInputFiles(scene.value()))
    if (Result<bool> checked = CheckNotAnInput(output, input, what); !checked) return checked;
  return true;
}

}  // namespace wirerig::cli
