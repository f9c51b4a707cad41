// libFuzzer target: rig descriptions (`wirerig rig --description`, docs/rig-formats.md) through
// LoadRigDescription, from a file in the fuzzer's scratch folder.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "wirerig/rig/rig_description.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = wirerig::fuzz::WriteInput(data, size, "rig.description.json");
  const wirerig::Result<wirerig::RigDescription> description = wirerig::LoadRigDescription(path);
  if (!description) {
    wirerig::fuzz::CheckNamesFile(description.error(), path);
    return 0;
  }
  // What loads is valid by the same rules the builders check.
  const std::string problem = wirerig::ValidateRigDescription(description.value());
  FUZZ_CHECK(problem.empty(), "a loaded description fails validation: " + problem);
  return 0;
}
