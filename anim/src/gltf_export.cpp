// ExportGltf: checks the input, builds the tinygltf model (mesh and materials, then the mode's
// morph targets or skeleton and skin, all keyed on one time accessor) and writes it.
#include "wirerig/anim/gltf_export.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>

#include "gltf_buffers.h"
#include "gltf_correctives.h"
#include "gltf_input.h"
#include "gltf_material.h"
#include "gltf_mesh.h"
#include "gltf_meshopt.h"
#include "gltf_morph.h"
#include "gltf_paths.h"
#include "gltf_skin.h"
#include "gltf_skin_fit.h"
#include "gltf_skinning.h"
#include "gltf_vertex_order.h"
#include "gltf_write.h"

namespace wirerig {
namespace {

namespace fs = std::filesystem;

// Quantized position deltas may round each vertex by at most this fraction of the rest mesh's
// bounding-box diagonal (the round-trip tolerance of the tests).
constexpr double kQuantizationTolerance = 1e-4;

// Morph mode's targets: per key, bake - base (positions; normals when both sides have them).
gltf::MorphTargetSet KeyDeltas(const gltf::BaseVertices& base, const BakedAnimation& bake) {
  gltf::MorphTargetSet set;
  set.key_count = bake.KeyCount();
  set.vertex_count = base.Count();
  set.normals = !base.normals.empty() && !bake.normals.empty();
  static_assert(sizeof(Vec3f) == 3 * sizeof(float), "bake vectors are read as float arrays");
  set.deltas = [&base, &bake](std::size_t k, std::span<float> positions, std::span<float> normals) {
    const std::size_t values = base.positions.size();
    const float* baked = bake.positions[k * base.Count()].data();
    const float* rest = base.positions.data();
    for (std::size_t i = 0; i < values; ++i) positions[i] = baked[i] - rest[i];
    if (normals.empty()) return;
    const float* baked_normals = bake.normals[k * base.Count()].data();
    const float* rest_normals = base.normals.data();
    for (std::size_t i = 0; i < values; ++i) normals[i] = baked_normals[i] - rest_normals[i];
  };
  return set;
}

// Skin mode's residual targets, copied from the fit (#K x #V x 3 each).
gltf::MorphTargetSet ResidualDeltas(gltf::SkinFit fit, std::size_t keys, std::size_t vertices) {
  gltf::MorphTargetSet set;
  set.key_count = keys;
  set.vertex_count = vertices;
  set.normals = !fit.residual_normals.empty();
  const auto shared = std::make_shared<const gltf::SkinFit>(std::move(fit));
  set.deltas = [shared, vertices](std::size_t k, std::span<float> positions,
                                  std::span<float> normals) {
    const std::size_t values = vertices * 3;
    std::copy_n(shared->residual_positions.begin() + static_cast<std::ptrdiff_t>(k * values),
                values, positions.begin());
    if (normals.empty()) return;
    std::copy_n(shared->residual_normals.begin() + static_cast<std::ptrdiff_t>(k * values), values,
                normals.begin());
  };
  return set;
}

// Adds the skeleton, skin and (optionally) residual targets; fills the skin numbers of `report`.
// Returns the residual targets (none without residuals).
Result<gltf::MorphTargetsAdded> AddSkinMode(
    tinygltf::Model& model, tinygltf::Animation& animation, const Mesh& mesh,
    const BakedAnimation& bake, const gltf::BaseVertices& base, const GltfExportOptions& options,
    const gltf::MorphQuantization& quantization, const gltf::PositionQuantization& stored_positions,
    int mesh_index, std::span<const float> times, int time_accessor, GltfExportReport* report) {
  gltf::SkinFitOptions fit_options;
  fit_options.max_joints = options.max_joints;
  fit_options.max_joints_per_part = options.max_joints_per_part;
  fit_options.key_tolerance = options.key_tolerance;
  fit_options.bridge_joints = options.bridge_joints;
  fit_options.flesh_joints = options.flesh_joints;
  fit_options.flesh_error = options.corrective_error;
  fit_options.influences = options.influences;
  // Files made small (quantized or compressed) store the weights as bytes.
  fit_options.byte_weights = options.quantize || options.compress;
  if (options.compress) {
    fit_options.translation_bits = gltf::kTranslationBits;
    fit_options.rotation_bits = gltf::kRotationBits;
  }
  if (!options.fit_skin) fit_options.iterations = fit_options.weight_rounds = 0;
  Result<gltf::FittedSkin> fitted = gltf::FitSkeleton(bake, base, fit_options);
  if (!fitted) return Error{fitted.error()};
  const gltf::Skeleton& skeleton = fitted.value().skeleton;
  const gltf::SkinInfluences& influences = fitted.value().influences;
  const bool residuals = options.residual_morph_targets;
  std::vector<int> roots;
  model.nodes[0].skin = gltf::AddSkeleton(model, animation, skeleton, times, time_accessor, &roots,
                                          stored_positions.Dequantization());
  model.scenes[0].nodes.insert(model.scenes[0].nodes.end(), roots.begin(), roots.end());
  gltf::AddSkinAttributes(model, mesh_index, influences, skeleton.JointCount());
  const bool correct = !residuals && options.max_correctives > 0;
  gltf::SkinFit fit =
      gltf::FitSkin(skeleton, influences, base, bake, residuals || correct, residuals);
  report->joint_count = skeleton.JointCount();
  report->joint_keys = skeleton.StoredKeyCount();
  report->skin_max_error = fit.max_error;
  report->skin_rms_error = fit.rms_error;
  report->corrected_max_error = fit.max_error;
  report->corrected_rms_error = fit.rms_error;
  const double diagonal = ComputeBounds(mesh).Diagonal();
  if (diagonal > 0.0) {
    report->skin_max_error_relative = fit.max_error / diagonal;
    report->skin_rms_error_relative = fit.rms_error / diagonal;
  }
  if (residuals) {
    report->morph_target_count = bake.KeyCount();
    report->residual_max_error = fit.residual_max_error;
    // The weights' keys first: the targets are the last (streamed) part of the buffer.
    gltf::AddKeyWeightsChannel(model, animation, 0, time_accessor, bake.KeyCount());
    return gltf::AddMorphTargets(model, mesh_index,
                                 ResidualDeltas(std::move(fit), bake.KeyCount(), base.Count()),
                                 quantization);
  }
  if (!correct || fit.max_error <= options.corrective_error) return gltf::MorphTargetsAdded{};
  gltf::CorrectiveOptions corrective_options;
  corrective_options.max_shapes = options.max_correctives;
  corrective_options.max_error = options.corrective_error;
  if (options.compress) corrective_options.delta_bits = gltf::kDeltaBits;
  // Quantized or compressed files store the shapes as bytes (KHR_mesh_quantization).
  corrective_options.byte_shapes = options.quantize || options.compress;
  auto correctives = std::make_shared<const gltf::Correctives>(
      gltf::FitCorrectives(skeleton, influences, base, bake, fit, corrective_options));
  report->corrective_count = correctives->shape_count;
  report->morph_target_count = correctives->shape_count;
  report->corrected_max_error = correctives->max_error;
  report->corrected_rms_error = correctives->rms_error;
  if (correctives->shape_count == 0) return gltf::MorphTargetsAdded{};
  // The shapes' deltas in stored position units: their weights over the quantization's scale.
  std::vector<float> weights = correctives->weights;
  if (stored_positions.enabled)
    for (float& w : weights) w = static_cast<float>(double(w) / stored_positions.scale);
  gltf::AddWeightsChannel(model, animation, 0, time_accessor, weights);
  gltf::MorphTargetSet set;
  set.key_count = correctives->shape_count;
  set.vertex_count = base.Count();
  set.name_prefix = "corrective_";  // POSITION deltas only (gltf_correctives.h)
  set.byte_positions = correctives->byte_shapes;
  set.deltas = [correctives](std::size_t s, std::span<float> positions, std::span<float>) {
    const std::size_t values = positions.size();
    std::copy_n(correctives->positions.begin() + static_cast<std::ptrdiff_t>(s * values), values,
                positions.begin());
  };
  return gltf::AddMorphTargets(model, mesh_index, std::move(set), quantization);
}

// Builds and writes the checked input (ExportGltf's checks passed).
Result<GltfExportReport> WriteExport(const Mesh& mesh, const BakedAnimation& bake,
                                     const GltfExportOptions& options, const fs::path& out,
                                     bool binary) {
  const fs::path out_dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
  const std::string name =
      !options.node_name.empty() ? options.node_name : (!bake.name.empty() ? bake.name : "mesh");

  GltfExportReport report;
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "wirerig";
  const gltf::MaterialsAdded materials = gltf::AddMaterials(
      model, mesh, options.texture_dir, out_dir,
      gltf::ImageStorage{options.max_texture_size, options.jpeg_textures}, &report.warnings);
  gltf::BaseVertices base = gltf::MakeBaseVertices(mesh);
  // Quantized skin files without residual targets store POSITION as shorts and NORMAL as bytes
  // (no normal target is measured against them); compressed files store NORMAL as bytes too
  // (octahedral, rounded below), and POSITION as shorts unless residual targets (deltas in
  // metres at weight 1) are added to it.
  const bool skin_without_residuals =
      options.mode == GltfAnimationMode::kSkin && !options.residual_morph_targets;
  const bool quantized_skin = options.quantize && skin_without_residuals && !options.compress;
  const bool short_positions = skin_without_residuals && (options.quantize || options.compress);
  gltf::BaseMeshStorage storage;
  storage.reorder_triangles = options.compress;
  storage.byte_normals = options.compress || quantized_skin;
  storage.short_uvs = quantized_skin;
  if (short_positions) storage.positions = gltf::QuantizePositions(&base);
  if (options.compress) {
    if (!short_positions) gltf::RoundLikeExpFilter(base.positions, 3, gltf::kPositionBits);
    gltf::RoundLikeOctFilter(base.normals, gltf::kOctahedralBits);
    gltf::RoundLikeExpFilter(base.uvs, 2, gltf::kUvBits);
  }
  if (base.zero_normals > 0) {
    report.warnings.push_back(std::to_string(base.zero_normals) +
                              " zero-length normals written as +Y");
  }
  if (!bake.normals.empty() && mesh.normals.empty()) {
    report.warnings.emplace_back("bake.normals left out: the mesh has no normals");
  }
  const int mesh_index = gltf::AddBaseMesh(model, mesh, base, materials.material, name, storage);
  tinygltf::Node node;
  node.name = name;
  node.mesh = mesh_index;
  model.nodes.push_back(std::move(node));
  model.scenes.emplace_back();
  model.scenes[0].nodes.push_back(0);
  model.defaultScene = 0;

  std::vector<float> times;
  for (double t : bake.times) times.push_back(static_cast<float>(t));
  const int time_accessor =
      gltf::AddFloatAccessor(model, times, TINYGLTF_TYPE_SCALAR, 0, /*min_max=*/true);
  tinygltf::Animation animation;
  animation.name = bake.name.empty() ? name : bake.name;
  gltf::MorphQuantization quantization;
  quantization.enabled = options.quantize;
  quantization.max_position_error = kQuantizationTolerance * ComputeBounds(mesh).Diagonal();
  gltf::MorphTargetsAdded targets;
  if (options.mode == GltfAnimationMode::kMorph) {
    // The weights' keys first: the targets are the last (streamed) part of the buffer.
    gltf::AddKeyWeightsChannel(model, animation, 0, time_accessor, bake.KeyCount());
    targets = gltf::AddMorphTargets(model, mesh_index, KeyDeltas(base, bake), quantization);
    report.morph_target_count = bake.KeyCount();
  } else {
    Result<gltf::MorphTargetsAdded> skinned =
        AddSkinMode(model, animation, mesh, bake, base, options, quantization, storage.positions,
                    mesh_index, times, time_accessor, &report);
    if (!skinned) return Error{out.string() + ": skin: " + skinned.error()};
    targets = std::move(skinned).value();
  }
  model.animations.push_back(std::move(animation));
  report.quantized_position_targets = targets.quantized_position_targets;
  report.quantized_normal_targets = targets.quantized_normal_targets;
  report.quantization_max_error = targets.quantization_max_error;
  report.primitive_count = model.meshes[static_cast<std::size_t>(mesh_index)].primitives.size();
  report.material_count = model.materials.size();

  gltf::BufferTail tail;
  gltf::MeshoptJson meshopt;
  if (options.compress) {
    meshopt = gltf::CompressBuffers(model, targets.stream);
  } else {
    tail.size = targets.stream.Size();
    tail.write = [&targets](const gltf::ByteSink& sink) { return targets.stream.Write(sink); };
  }
  Result<std::vector<fs::path>> files =
      gltf::WriteModel(std::move(model), tail, out, binary, meshopt);
  if (!files) return Error{files.error()};
  report.files = std::move(files.value());
  for (const fs::path& file : report.files) {
    std::error_code error;
    report.bytes_written += fs::file_size(file, error);
  }
  report.vertex_count = mesh.positions.size();
  report.triangle_count = mesh.triangles.size();
  report.key_count = bake.KeyCount();
  report.texture_count = materials.texture_count;
  return report;
}

}  // namespace

double EstimateGltfBytes(std::size_t vertex_count, std::size_t joint_count, double keys,
                         bool normals, const GltfExportOptions& options) {
  const bool skin = options.mode == GltfAnimationMode::kSkin;
  const bool morph = !skin || options.residual_morph_targets;
  // Per vertex and attribute: 3 floats, or 4 shorts when quantized (the smallest it can be).
  const double stride = options.quantize ? 4.0 * sizeof(std::int16_t) : 3.0 * sizeof(float);
  const double morph_bytes = morph ? stride * (normals ? 2.0 : 1.0) * double(vertex_count) : 0.0;
  // Per joint: a translation (3 floats) and a rotation (4 floats) per key.
  const double joint_bytes = skin ? 7.0 * sizeof(float) * double(joint_count) : 0.0;
  // One morph target per key, and every key weighs all of them: keys^2 floats.
  const double weight_bytes = morph ? sizeof(float) * keys : 0.0;
  return keys * (morph_bytes + joint_bytes + weight_bytes);
}

std::string GltfTooLargeMessage(double bytes) {
  if (!std::isfinite(bytes))
    return "the export needs more bytes than can be counted, more than a glTF buffer may hold";
  char message[200];
  std::snprintf(message, sizeof message,
                "the export needs at least %.3g GB, more than a glTF buffer may hold (%.3g GB)",
                bytes / 1e9, kMaxGltfBytes / 1e9);
  return message;
}

Result<GltfExportReport> ExportGltf(const Mesh& mesh, const BakedAnimation& bake,
                                    const GltfExportOptions& options, const fs::path& out) {
  const std::string extension = gltf::LowerCaseExtension(out);
  if (extension != ".glb" && extension != ".gltf") {
    std::string message = out.string();
    message.append(": unsupported extension '")
        .append(out.extension().string())
        .append("' (use .glb or .gltf)");
    return Error{std::move(message)};
  }
  if (auto problem = gltf::CheckExportInput(mesh, bake, options.mode)) {
    return Error{out.string() + ": " + *problem};
  }
  if (options.influences != 4 && options.influences != gltf::kMaxInfluences) {
    return Error{out.string() + ": influences must be 4 or 8, not " +
                 std::to_string(options.influences)};
  }
  if (options.influences != 4 && options.mode != GltfAnimationMode::kSkin) {
    return Error{out.string() + ": influences applies to skin mode (morph files have no skin)"};
  }
  if (options.compress && options.mode != GltfAnimationMode::kSkin) {
    return Error{out.string() +
                 ": compress applies to skin mode (morph files are for offline tools, which lack "
                 "a meshopt decoder)"};
  }
  // The size before any buffer is built: a long morph export grows with keys^2 (the weights).
  std::size_t joints = 0;
  for (const BakedSpine& spine : bake.spines) joints += spine.SampleCount();
  if (const double bytes = EstimateGltfBytes(mesh.positions.size(), joints, double(bake.KeyCount()),
                                             !bake.normals.empty(), options);
      bytes > kMaxGltfBytes) {
    return Error{out.string() + ": " + GltfTooLargeMessage(bytes)};
  }
  const bool binary = extension == ".glb";
  if (options.keep_vertex_order && !options.compress) {
    return Error{out.string() +
                 ": keep_vertex_order applies to compressed files (the others "
                 "keep it)"};
  }
  if (!options.compress || options.keep_vertex_order)
    return WriteExport(mesh, bake, options, out, binary);
  // Compressed files store the vertices in the order the codecs store in fewer bytes.
  std::vector<std::uint32_t> order = gltf::SmallerVertexOrder(mesh, bake);
  if (std::is_sorted(order.begin(), order.end())) {
    return WriteExport(mesh, bake, options, out, binary);
  }
  Result<GltfExportReport> report = WriteExport(
      gltf::ReorderVertices(mesh, order), gltf::ReorderVertices(bake, order), options, out, binary);
  if (report) report.value().vertex_order = std::move(order);
  return report;
}

}  // namespace wirerig
