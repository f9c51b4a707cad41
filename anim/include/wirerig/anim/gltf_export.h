// ExportGltf: writes a BakedAnimation of a Mesh as an animated glTF 2.0 asset (tinygltf), either
// a single binary `.glb` or a `.gltf` JSON file with its `.bin` buffer next to it (same stem).
// Conventions of the asset are glTF's and wirerig's: metres, +Y up, column-major matrices,
// quaternions (x, y, z, w). Keys become animation keyframes at BakedAnimation::times, LINEAR.
//
// Two modes:
//  * kMorph: the mesh's rest (Mesh::positions / normals) is the base; every key k is a morph
//    target (POSITION and NORMAL deltas, bake - rest) and the mesh node's `weights` are animated
//    with weight k = 1 at key k and 0 elsewhere. At the keys the asset reproduces the bake up to
//    float rounding; between keys positions interpolate linearly.
//  * kSkin: a skeleton of few joints: one per rigid part, up to max_joints_per_part spread along
//    each deformable part, within max_joints; their translation + rotation keys and the
//    vertices' weights (4 per vertex) are fitted to the bake (a skinning decomposition,
//    gltf_skin_fit.h). What joints cannot do (a profile's bulge, a stretch) is carried by a few
//    corrective morph targets (PCA of the skin's residual over the keys) with animated weights,
//    added until every vertex is within corrective_error of the bake at every key. With
//    residual morph targets instead, the asset carries per key the delta that makes the skinned
//    mesh match the bake exactly (up to float rounding) at that key. The report gives the
//    skin's error and the corrected one at every key.
//
// Files are written atomically (temporary file in the same folder, then renamed); on any error
// no output file is created or left half-written. Morph targets are streamed to the file while
// it is written (never held in memory as a whole), on up to two threads; the bytes written do
// not depend on the thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "wirerig/anim/baked_animation.h"
#include "wirerig/io/result.h"
#include "wirerig/rig/mesh.h"

namespace wirerig {

enum class GltfAnimationMode : int { kMorph = 0, kSkin = 1 };

struct GltfExportOptions {
  GltfAnimationMode mode = GltfAnimationMode::kMorph;
  // kSkin only: add one residual morph target per key (bake minus the skinned reconstruction).
  bool residual_morph_targets = false;
  // kSkin: the skeleton's budget (joints per skin), and the most joints a deformable part gets
  // (0: a joint at every spine sample, within max_joints). A rigid part gets one joint.
  std::size_t max_joints = 64;
  std::size_t max_joints_per_part = 8;
  // kSkin: a bridge joint where each part hangs from its parent ("forearm_l_bridge", starting
  // half-way between the two sides), while max_joints allows once every part has its joints.
  bool bridge_joints = true;
  // kSkin: flesh joints where the fitted skin still misses the bake by more than
  // corrective_error (jiggling skin; gltf_flesh_joints.h), while max_joints allows once every
  // part and bridge has its joint.
  bool flesh_joints = true;
  // kSkin: joints per vertex, 4 (JOINTS_0 / WEIGHTS_0, what every engine reads) or 8 (also
  // JOINTS_1 / WEIGHTS_1: Blender, Babylon.js, Unity's glTFast and Godot read them; three.js
  // r187 reads the first set only).
  std::size_t influences = 4;
  // kSkin: fit the joints' transforms and the weights to the bake (gltf_skin_fit.h); false:
  // the baked spine frames and the bake's weights (BuildSpineSkin) as they are.
  bool fit_skin = true;
  // kSkin without residual targets: corrective blend shapes (PCA of the skin's residual over
  // all keys, gltf_correctives.h), added until every vertex is within corrective_error (m) of
  // the bake at every key, at most max_correctives of them (0: none).
  std::size_t max_correctives = 16;
  double corrective_error = 1e-3;
  // kSkin: a joint's key is left out of its track when interpolating its neighbours moves the
  // joint's vertices by at most key_tolerance (m; gltf_skin.h's KeyThinning); the correctives
  // are fitted to what remains. 0 keeps every key.
  double key_tolerance = 0.0;
  // Name of the mesh node (and mesh); empty: the clip's name, or "mesh" when that is empty.
  std::string node_name;
  // Folder the mesh's MeshMaterial::base_color_texture paths are relative to (the source file's
  // folder). Textures are referenced, not copied: the image URI is the texture's path relative
  // to the output file's folder. A texture that does not exist, is not PNG or JPEG, or whose
  // mesh has no UVs is left out with a report warning. Empty: no texture files are exported.
  // Textures the source held itself (MeshMaterial::base_color_image) are embedded in the buffer.
  std::filesystem::path texture_dir;
  // > 0: an embedded texture whose longer side exceeds this many pixels is downscaled to it
  // (aspect kept, filtered in sRGB) and re-encoded in its format (PNG, or JPEG at quality 90);
  // a texture file referenced by URI is left as it is, with a report warning. 0: unchanged.
  int max_texture_size = 0;
  // An embedded PNG texture re-encoded as JPEG at quality 90 when that is smaller (after
  // max_texture_size). JPEG has no alpha, and none is lost: every material the export writes is
  // opaque (glTF's default alphaMode), so readers ignore a texture's alpha. A PNG with a side
  // over 65,535 pixels (JPEG's limit) stays PNG. Files referenced by URI are left as they are,
  // with a report warning. Off: textures keep their format.
  bool jpeg_textures = false;
  // Morph targets (kMorph, and kSkin's residual targets) as KHR_mesh_quantization normalized
  // signed shorts (value / 32767, at an 8-byte stride) instead of float: a key's POSITION
  // deltas when every component lies within [-1, 1] m and the rounding bound per vertex,
  // sqrt(3) / 2 / 32767 m = 2.6e-5 m, is at most 1e-4 of the rest mesh's bounding-box diagonal
  // (diagonal >= 0.26 m); its NORMAL deltas when every component lies within [-1, 1]. Other keys
  // stay float. The extension is then required: readers without it (Assimp 5.2) cannot load the
  // file. Off by default: exact float deltas, readable everywhere.
  bool quantize = false;
  // kSkin only: EXT_meshopt_compression (meshoptimizer's codecs on every buffer view; rest
  // positions as normalized shorts (KHR_mesh_quantization; floats beside residual targets, whose
  // deltas are metres), normals, UVs, corrective deltas and
  // translation keys rounded first to what its filters store, so the reported errors are the
  // decoded file's). The vertices are stored in the order the codecs store in fewer bytes (the
  // mesh's own, or the order the triangles use them: GltfExportReport::vertex_order). The
  // extension is required: readers without a meshopt decoder (Assimp 5.2, Blender 3.4) cannot
  // load the file; three.js, Babylon.js and gltfpack can. Off by default.
  bool compress = false;
  // With compress: keep the mesh's vertex order (for a reader that matches file vertices to
  // its own data by index), whatever it costs.
  bool keep_vertex_order = false;
};

struct GltfExportReport {
  std::vector<std::filesystem::path> files;  // every file written: the .glb, or .gltf and .bin
  std::uintmax_t bytes_written = 0;          // sum of their sizes, bytes
  std::size_t vertex_count = 0;              // #V
  std::size_t triangle_count = 0;            // #F
  std::size_t primitive_count = 0;           // one per material of the parts with triangles
  std::size_t key_count = 0;                 // #K
  std::size_t morph_target_count = 0;        // #K in kMorph; #K, the correctives or 0 in kSkin
  std::size_t joint_count = 0;               // kSkin: the skeleton's joints
  std::size_t joint_keys = 0;  // kSkin: keys stored over all joints' tracks (#J x #K unthinned)
  std::size_t material_count = 0;
  std::size_t texture_count = 0;
  std::vector<std::string> warnings;  // what was left out, and why
  // File vertex -> the mesh's render vertex, when the file stores them in another order (with
  // options.compress: the order the triangles use them, for the codec); empty when the file
  // keeps the mesh's order.
  std::vector<std::uint32_t> vertex_order;

  // kSkin: error of the linear-blend-skinned positions against the bake at every key, computed
  // with the glTF skinning formula from the values as stored in the file (float). Metres, and
  // relative to the rest mesh's bounding-box diagonal (ComputeBounds). Max over keys and
  // vertices; RMS over all #K x #V vertex distances.
  double skin_max_error = 0.0;
  double skin_rms_error = 0.0;
  double skin_max_error_relative = 0.0;
  double skin_rms_error_relative = 0.0;
  // kSkin with residual morph targets: the same max error once the residuals are applied, m
  // (float residuals; quantized ones add at most quantization_max_error).
  double residual_max_error = 0.0;
  // kSkin with correctives: their count, and the error once they are applied (m; max over
  // keys and vertices, RMS over all). With none, the skin's errors.
  std::size_t corrective_count = 0;
  double corrected_max_error = 0.0;
  double corrected_rms_error = 0.0;
  // With options.quantize: the targets stored as shorts, and the bound of their position
  // rounding per vertex, m (sqrt(3) / 2 / 32767 = 2.6e-5 m; 0 when none is quantized).
  std::size_t quantized_position_targets = 0;
  std::size_t quantized_normal_targets = 0;
  double quantization_max_error = 0.0;
};

// The most bytes an export may take, either form: a .glb's lengths are 32-bit, and a .gltf's
// .bin beyond that is more than engines load (and than the export may hold in memory).
inline constexpr double kMaxGltfBytes = 4294967295.0;

// A lower bound of the bytes ExportGltf writes for `keys` keys of a mesh of `vertex_count`
// render vertices (normals baked when `normals`) and `joint_count` spine samples: the morph
// targets' deltas (kMorph, or kSkin with residuals; at the quantized stride when
// options.quantize) and their weights (keys^2 floats), and, in kSkin, the joints' keys. For
// refusing, before baking, an export that cannot be written (over kMaxGltfBytes); ExportGltf
// refuses it too.
double EstimateGltfBytes(std::size_t vertex_count, std::size_t joint_count, double keys,
                         bool normals, const GltfExportOptions& options);

// "the export needs at least N GB, more than a glTF buffer may hold (4.29 GB)".
std::string GltfTooLargeMessage(double bytes);

// Exports `bake` of `mesh` to `out` (".glb", or ".gltf" plus "<stem>.bin"; the extension is
// matched case-insensitively). Refuses, naming the field: another extension; a mesh without
// positions or triangles, or with non-finite coordinates, out-of-range triangle indices or
// normals/uvs of the wrong size; a bake with zero keys, non-finite or non-increasing times
// (also once rounded to float), vertex_count or positions/normals sizes that do not match the
// mesh, non-finite positions or normals; in kSkin: missing or mis-sized spines, skin_joints or
// skin_weights, joint indices out of range, negative or non-finite weights or ones summing to
// zero, non-finite spine points or rotations, a parent or parent_joint out of range; `compress`
// in kMorph.
Result<GltfExportReport> ExportGltf(const Mesh& mesh, const BakedAnimation& bake,
                                    const GltfExportOptions& options,
                                    const std::filesystem::path& out);

}  // namespace wirerig
