// libFuzzer target: scene files (`wirerig bake`, docs/scene-format.md) through LoadScene, from a
// file in the fuzzer's scratch folder (nothing is built: no mesh is imported). A scene that
// loads must write back (SceneToJson) to a document that parses again.
#include <cstddef>
#include <cstdint>

#include <nlohmann/json.hpp>

#include "fuzz_support.h"
#include "wirerig/anim/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = wirerig::fuzz::WriteInput(data, size, "fuzz.scene.json");
  const wirerig::Result<wirerig::SceneDescription> scene = wirerig::LoadScene(path);
  if (!scene) {
    wirerig::fuzz::CheckNamesFile(scene.error(), path);
    return 0;
  }
  const nlohmann::json written = wirerig::SceneToJson(scene.value());
  const wirerig::Result<wirerig::SceneDescription> again =
      wirerig::ParseScene(written, scene.value().folder);
  FUZZ_CHECK(again.ok(), "a loaded scene written back does not parse: " + again.error() +
                             "\n  written: " + written.dump());
  return 0;
}
