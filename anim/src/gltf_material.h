// Materials of the source mesh as glTF PBR materials: the base colour factor (clamped to
// [0, 1]), metallic 0 and roughness 1 (wirerig meshes carry no PBR parameters; a matte,
// non-metal surface shows the base colour as authored), and the base colour texture: a file
// next to the source as an external image referenced by a URI relative to the output file
// (never copied); one the source held itself (MeshMaterial::base_color_image: an archive
// entry, an embedded texture) embedded in the output's buffer.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "gltf_texture_size.h"
#include "wirerig/rig/mesh.h"

namespace wirerig::gltf {

struct MaterialsAdded {
  std::vector<int> material;  // glTF material index per Mesh::materials entry
  std::size_t texture_count = 0;
};

// `texture_dir`: the folder MeshMaterial::base_color_texture is relative to (empty: no texture
// files; held images are embedded still); `out_dir`: the output file's folder. A texture is
// left out, with a warning, when the mesh has no UVs, the file does not exist, or it is not PNG
// or JPEG. Embedded images are stored as `images` says (StoreImage); referenced files it would
// change are left as they are, with a warning.
MaterialsAdded AddMaterials(tinygltf::Model& model, const Mesh& mesh,
                            const std::filesystem::path& texture_dir,
                            const std::filesystem::path& out_dir, const ImageStorage& images,
                            std::vector<std::string>* warnings);

}  // namespace wirerig::gltf
