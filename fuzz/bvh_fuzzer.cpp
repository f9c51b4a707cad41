// libFuzzer target: BVH motion capture (a scene clip's "motion", docs/motion-import.md) through
// ParseBvh; every frame of a parsed motion is posed.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "fuzz_support.h"
#include "wirerig/anim/motion_capture.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const wirerig::Result<wirerig::MotionCapture> motion = wirerig::ParseBvh(text, "fuzz.bvh");
  if (!motion) {
    FUZZ_CHECK(motion.error().rfind("fuzz.bvh", 0) == 0,
               "error does not name the source: " + motion.error());
    return 0;
  }
  std::vector<wirerig::BvhPose> pose;
  (void)wirerig::BvhRestPositions(motion.value());
  for (std::size_t frame = 0; frame < motion.value().frame_count && frame < 64; ++frame)
    wirerig::PoseBvhFrame(motion.value(), frame, pose);
  return 0;
}
