// libFuzzer target: built rig assets (.wrig, runtime/rig_asset.h) through ParseRigAsset, as is
// and with a consistent envelope (asset_header.h). A rig that parses passed ValidateRigModel,
// which promises it is safe to evaluate: it is evaluated at rest, into doubles and floats, and
// must serialize back to bytes that parse again.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "asset_header.h"
#include "fuzz_support.h"
#include "wirerig/runtime/rig_asset.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace {

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
