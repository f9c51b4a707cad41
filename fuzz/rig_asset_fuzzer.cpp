// libFuzzer target: built rig assets (.wrig, runtime/rig_asset.h) through ParseRigAsset, as is
// and with a consistent envelope (asset_header.h). A rig that parses passed ValidateRigModel,
// which promises it is safe to evaluate: it is evaluated at rest, into doubles and floats, then
// posed (every joint turned, spines loaded, rotated normals, interleaved buffers), and must
// serialize back to bytes that parse again.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "asset_header.h"
#include "fuzz_support.h"
#include "wirerig/runtime/joint.h"
#include "wirerig/runtime/rig_asset.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace {

const wirerig::PointLoad kLoad{0.6, wirerig::Vec3(0.0, 2.0, 1.0)};  // N, at 60% of the spine

void Evaluate(const wirerig::RigAsset& asset) {
  const wirerig::RigModel& model = asset.model;
  // Hostile counts stay within the input's size, but a frame of a large model is slow.
  if (model.vertices.size() > 20000) return;
  wirerig::RigWorkspace workspace = wirerig::MakeRigWorkspace(model);
  std::vector<wirerig::PartPose> poses(model.parts.size());
  std::vector<wirerig::Vec3> positions(model.vertices.size()), normals(model.vertices.size());
  wirerig::EvaluateRigJob job;
  job.model = &model;
  job.poses = poses;
  job.workspace = &workspace;
  job.positions = positions;
  job.normals = normals;
  const wirerig::Status doubles = job.Run();
  FUZZ_CHECK(doubles.ok(), "a validated rig does not evaluate: " + wirerig::ToString(doubles));

  const std::size_t outputs =
      asset.vertex_order.empty() ? model.vertices.size() : asset.vertex_order.size();
  std::vector<float> float_positions(outputs * 3), float_normals(outputs * 3);
  job.positions = {};
  job.normals = {};
  job.float_positions = float_positions;
  job.float_normals = float_normals;
  job.float_vertex_order = asset.vertex_order;
  const wirerig::Status floats = job.Run();
  FUZZ_CHECK(floats.ok(),
             "a validated rig does not evaluate into floats: " + wirerig::ToString(floats));

  // Posed as an engine poses it: every joint turned (JointRotation clamps to its limits), a
  // point load on every deformable spine, rotated normals, interleaved buffers (stride 6). The
  // frame may be refused (loads too large for a soft spine), but then it names the field and
  // writes nothing; evaluated, every output is finite.
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const wirerig::PartModel& part = model.parts[p];
    if (part.parent >= 0)
      poses[p].rotation = wirerig::JointRotation(
          part.joint, wirerig::Vec3(37.0 + double(p), -23.0, 11.0 * double(p % 3)));
    if (part.kind == wirerig::SpineKind::kDeformable)
      poses[p].loads.bending_point_loads = std::span(&kLoad, 1);
  }
  std::vector<float> interleaved(outputs * 6, -7.0f);
  job.float_positions = interleaved;
  job.float_position_stride = 6;
  job.float_normals = std::span(interleaved).subspan(3);
  job.float_normal_stride = 6;
  job.normal_mode = wirerig::NormalMode::kRotated;
  const wirerig::Status posed = job.Run();
  if (!posed.ok()) {
    FUZZ_CHECK(!posed.field.empty(), "a refused frame names no field");
    for (const float value : interleaved) FUZZ_CHECK(value == -7.0f, "a refused frame wrote");
    return;
  }
  for (const float value : interleaved)
    FUZZ_CHECK(std::isfinite(value), "a posed frame wrote a value that is not finite");
}

void ParseOne(std::span<const std::uint8_t> bytes) {
  wirerig::RigAsset asset;
  if (!wirerig::ParseRigAsset(bytes, &asset)) return;
  Evaluate(asset);
  const std::vector<std::uint8_t> written = wirerig::SerializeRigAsset(asset);
  wirerig::RigAsset again;
  const wirerig::Status reparsed = wirerig::ParseRigAsset(written, &again);
  FUZZ_CHECK(reparsed.ok(),
             "a parsed rig written back does not parse: " + wirerig::ToString(reparsed));
  FUZZ_CHECK(wirerig::SerializeRigAsset(again) == written, "a rig does not parse back exactly");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return wirerig::fuzz::ParseAsItIsAndConsistent(data, size, ParseOne);
}
