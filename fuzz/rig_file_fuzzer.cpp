// libFuzzer target: rig files (`wirerig rig -o X.rig.json`, docs/rig-formats.md) through
// LoadRig, from a file in the fuzzer's scratch folder. A rig that loads must write back to JSON
// that loads again to the same JSON (rig_file.h: a saved rig loads back exactly).
#include <cstddef>
#include <cstdint>

#include <nlohmann/json.hpp>

#include "fuzz_support.h"
#include "wirerig/rig/rig_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = wirerig::fuzz::WriteInput(data, size, "fuzz.rig.json");
  const wirerig::Result<wirerig::Rig> rig = wirerig::LoadRig(path);
  if (!rig) {
    wirerig::fuzz::CheckNamesFile(rig.error(), path);
    return 0;
  }
  const nlohmann::json written = wirerig::RigToJson(rig.value());
  const wirerig::Result<wirerig::Rig> again = wirerig::RigFromJson(written);
  FUZZ_CHECK(again.ok(), "a loaded rig written back does not load: " + again.error());
  FUZZ_CHECK(wirerig::RigToJson(again.value()) == written, "a rig does not load back exactly");
  return 0;
}
