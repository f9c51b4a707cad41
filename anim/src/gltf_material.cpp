#include "gltf_material.h"

#include <algorithm>
#include <iterator>
#include <map>
#include <system_error>

#include "gltf_buffers.h"
#include "gltf_paths.h"
#include "gltf_texture_size.h"

namespace wirerig::gltf {
namespace {

namespace fs = std::filesystem;

std::string MimeType(const fs::path& file) {
  const std::string ext = LowerCaseExtension(file);
  if (ext == ".png") return "image/png";
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  return {};
}

// PNG or JPEG by the bytes' signature, else empty.
std::string MimeTypeOf(const std::vector<unsigned char>& bytes) {
  static constexpr unsigned char kPng[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() > sizeof kPng && std::equal(std::begin(kPng), std::end(kPng), bytes.begin()))
    return "image/png";
  if (bytes.size() > 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff)
    return "image/jpeg";
  return {};
}

// The image for a material's texture, or the reason it is left out: a file referenced by its
// URI, or bytes the source held (embedded in the output's buffer; `uri` empty).
struct ImageRef {
  std::string uri;
  std::string mime_type;
  std::string problem;
};

ImageRef ResolveTexture(const Mesh& mesh, const MeshMaterial& material, const fs::path& texture_dir,
                        const fs::path& out_dir) {
  ImageRef ref;
  const fs::path file = texture_dir / material.base_color_texture;
  std::error_code error;
  if (mesh.uvs.empty()) {
    ref.problem = "the mesh has no UVs";
  } else if (!material.base_color_image.empty()) {
    ref.mime_type = MimeTypeOf(material.base_color_image);
    if (ref.mime_type.empty()) ref.problem = "not PNG or JPEG";
  } else if (!fs::is_regular_file(file, error)) {
    ref.problem = "file not found";
  } else if (ref.mime_type = MimeType(file); ref.mime_type.empty()) {
    ref.problem = "not PNG or JPEG";
  } else {
    const fs::path relative =
        fs::relative(fs::absolute(file, error), fs::absolute(out_dir, error), error);
    if (error || relative.empty()) {
      ref.problem = "no path relative to the output folder";
    } else {
      ref.uri = PathToUri(relative);
    }
  }
  return ref;
}

}  // namespace

MaterialsAdded AddMaterials(tinygltf::Model& model, const Mesh& mesh, const fs::path& texture_dir,
                            const fs::path& out_dir, const ImageStorage& images,
                            std::vector<std::string>* warnings) {
  MaterialsAdded added;
  std::map<std::string, int> texture_of_uri;  // one image and texture per distinct file
  for (std::size_t m = 0; m < mesh.materials.size(); ++m) {
    const MeshMaterial& source = mesh.materials[m];
    tinygltf::Material material;
    material.name = source.name;
    const Vec4 color = source.base_color.cwiseMax(0.0).cwiseMin(1.0);
    if (color != source.base_color) {
      warnings->push_back("material '" + source.name + "': base colour clamped to [0, 1]");
    }
    material.pbrMetallicRoughness.baseColorFactor = {color[0], color[1], color[2], color[3]};
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 1.0;
    const bool held = !source.base_color_image.empty();
    if (held || (!texture_dir.empty() && !source.base_color_texture.empty())) {
      const ImageRef ref = ResolveTexture(mesh, source, texture_dir, out_dir);
      if (!ref.problem.empty()) {
        std::string warning = "material '";
        warning.append(source.name)
            .append("': texture '")
            .append(source.base_color_texture)
            .append("' left out: ")
            .append(ref.problem);
        warnings->push_back(std::move(warning));
      } else {
        // Held images are told apart by their material (each is embedded once).
        const std::string key = held ? "held:" + std::to_string(m) : ref.uri;
        auto [it, inserted] = texture_of_uri.try_emplace(key, -1);
        if (inserted) {
          if (model.samplers.empty()) {
            tinygltf::Sampler sampler;
            sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
            sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
            model.samplers.push_back(sampler);
          }
          tinygltf::Image image;
          image.uri = ref.uri;
          image.mimeType = ref.mime_type;
          if (held) {
            image.name = fs::path(source.base_color_texture).stem().string();
            Result<StoredImage> stored = StoreImage(source.base_color_image, ref.mime_type, images);
            if (!stored) {
              warnings->push_back("material '" + source.name + "': texture '" +
                                  source.base_color_texture +
                                  "' embedded as the source held it: " + stored.error());
            } else {
              image.mimeType = stored.value().mime_type;
            }
            image.bufferView = AddBytesView(
                model, stored ? std::span<const unsigned char>(stored.value().bytes)
                              : std::span<const unsigned char>(source.base_color_image));
          } else {
            int width = 0, height = 0;
            const bool too_large =
                images.max_size > 0 &&
                ImageSize(texture_dir / source.base_color_texture, &width, &height) &&
                std::max(width, height) > images.max_size;
            if (too_large) {
              warnings->push_back("material '" + source.name + "': texture '" +
                                  source.base_color_texture + "' (" + std::to_string(width) +
                                  " x " + std::to_string(height) +
                                  ") is referenced, not embedded: left at its size");
            }
            if (images.as_jpeg && ref.mime_type != "image/jpeg") {
              warnings->push_back("material '" + source.name + "': texture '" +
                                  source.base_color_texture +
                                  "' is referenced, not embedded: left as PNG");
            }
          }
          model.images.push_back(image);
          tinygltf::Texture texture;
          texture.sampler = 0;
          texture.source = static_cast<int>(model.images.size()) - 1;
          model.textures.push_back(texture);
          it->second = static_cast<int>(model.textures.size()) - 1;
        }
        material.pbrMetallicRoughness.baseColorTexture.index = it->second;
      }
    }
    model.materials.push_back(std::move(material));
    added.material.push_back(static_cast<int>(model.materials.size()) - 1);
  }
  added.texture_count = model.textures.size();
  return added;
}

}  // namespace wirerig::gltf
