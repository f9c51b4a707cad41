// libFuzzer target: sampled clip assets (.wclip, runtime/clip_asset.h) through ParseClipAsset,
// as is and with a consistent envelope (asset_header.h). A clip that parses passed
// ValidateSampledClip: it is played (SampleClipJob) at times before, inside and after it, and
// must serialize back to bytes that parse again.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "asset_header.h"
#include "fuzz_support.h"
#include "wirerig/runtime/clip_asset.h"

namespace {

void ParseOne(std::span<const std::uint8_t> bytes) {
  wirerig::SampledClip clip;
  if (!wirerig::ParseClipAsset(bytes, &clip)) return;
  wirerig::ClipPlaybackBuffers buffers = wirerig::MakeClipPlaybackBuffers(clip);
  const double d = clip.duration;
  for (double t : {-1.0, 0.0, 0.3 * d, 0.5 * d, d, 1.7 * d, 1e300}) {
    wirerig::SampleClipJob job;
    job.clip = &clip;
    job.time = t;
    job.buffers = &buffers;
    const wirerig::Status played = job.Run();
    FUZZ_CHECK(played.ok(), "a validated clip does not play: " + wirerig::ToString(played));
  }
  const std::vector<std::uint8_t> written = wirerig::SerializeClipAsset(clip);
  wirerig::SampledClip again;
  const wirerig::Status reparsed = wirerig::ParseClipAsset(written, &again);
  FUZZ_CHECK(reparsed.ok(),
             "a parsed clip written back does not parse: " + wirerig::ToString(reparsed));
  FUZZ_CHECK(wirerig::SerializeClipAsset(again) == written, "a clip does not parse back exactly");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return wirerig::fuzz::ParseAsItIsAndConsistent(data, size, ParseOne);
}
