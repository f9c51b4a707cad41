// libFuzzer target: clips in JSON (a scene's "clips" entries, anim/clip_json.h) read by
// ReadClip, checked by ValidateRawClip, built by BuildClip against a two-part rig (deformable
// and rigid spines: fuzz_rigs.h) and sampled at a few times; a clip that reads must write back
// (ClipToJson) to JSON that reads to the same JSON.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "fuzz_rigs.h"
#include "fuzz_support.h"
#include "wirerig/anim/clip.h"
#include "wirerig/anim/clip_json.h"
#include "wirerig/anim/clip_sampling.h"
#include "wirerig/io/json_text.h"

namespace {

const wirerig::RigModel& Model(wirerig::SpineKind kind) {
  static const wirerig::RigModel deformable =
      wirerig::fuzz::MakeJointedCylinderModel(wirerig::SpineKind::kDeformable);
  static const wirerig::RigModel rigid =
      wirerig::fuzz::MakeJointedCylinderModel(wirerig::SpineKind::kRigid);
  return kind == wirerig::SpineKind::kRigid ? rigid : deformable;
}

void BuildAndSample(const wirerig::RawClip& raw, const wirerig::RigModel& model) {
  const wirerig::Result<wirerig::Clip> clip = wirerig::BuildClip(raw, model);
  if (!clip) return;
  wirerig::ClipSample sample = wirerig::MakeClipSample(clip.value(), model);
  const double d = clip.value().duration;
  for (double t : {-1.0, 0.0, 0.25 * d, 0.5 * d, d, 1.5 * d, 1e300}) {
    const double local = clip.value().LocalTime(t);
    wirerig::SampleClip(clip.value(), local, &sample);
    // A finite rotation vector (keys interpolated without overflow) gives a unit quaternion.
    for (std::size_t p = 0; p < sample.poses.size(); ++p) {
      if (!clip.value().parts[p].rotation.Sample(local).allFinite()) continue;
      const wirerig::Quat& q = sample.poses[p].rotation;
      FUZZ_CHECK(q.coeffs().allFinite() && std::abs(q.norm() - 1.0) < 1e-9,
                 "a finite rotation vector sampled to a rotation that is not a unit quaternion");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const wirerig::Result<nlohmann::json> document = wirerig::ParseJsonText(text, "fuzz.clip.json");
  if (!document) return 0;
  wirerig::RawClip raw;
  try {
    raw = wirerig::ReadClip(wirerig::JsonObject(document.value(), ""));
  } catch (const wirerig::FieldError&) {
    return 0;
  }
  if (!wirerig::ValidateRawClip(raw).empty()) return 0;

  const nlohmann::json written = wirerig::ClipToJson(raw);
  try {
    const wirerig::RawClip again = wirerig::ReadClip(wirerig::JsonObject(written, ""));
    FUZZ_CHECK(wirerig::ClipToJson(again) == written, "a clip does not read back exactly");
  } catch (const wirerig::FieldError& e) {
    FUZZ_CHECK(false, std::string("a clip written back does not read: ") + e.what());
  }

  BuildAndSample(raw, Model(wirerig::SpineKind::kDeformable));
  BuildAndSample(raw, Model(wirerig::SpineKind::kRigid));
  return 0;
}
