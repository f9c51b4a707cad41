// Embedded textures fitted within a size (GltfExportOptions::max_texture_size) and stored as
// JPEG (jpeg_textures): decoded with stb_image, downscaled in sRGB (stb_image_resize,
// alpha not premultiplied), re-encoded with stb_image_write (PNG; JPEG at quality 90).
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "wirerig/io/result.h"

namespace wirerig::gltf {

// How embedded images are stored (GltfExportOptions::max_texture_size, jpeg_textures).
struct ImageStorage {
  int max_size = 0;      // longer side at most this many pixels; 0: any
  bool as_jpeg = false;  // a PNG as JPEG (its alpha dropped), when smaller
};

struct StoredImage {
  std::vector<unsigned char> bytes;
  std::string mime_type;  // "image/png" or "image/jpeg"
};

// `bytes` (a PNG or JPEG, `mime_type` "image/png" or "image/jpeg") stored as `storage` says: its
// longer side fitted within max_size (aspect kept, each side at least 1; re-encoded in its own
// format), then, with as_jpeg, a PNG re-encoded as JPEG (quality 90, no alpha) if that takes
// fewer bytes and JPEG can hold its sides (at most 65,535 pixels). The same bytes when nothing
// applies. Fails, with the reason, when the image cannot be decoded or resized; a JPEG that
// cannot be encoded leaves the PNG.
Result<StoredImage> StoreImage(std::span<const unsigned char> bytes, const std::string& mime_type,
                               const ImageStorage& storage);

// The size of the image in `file`, pixels; false when stb_image cannot read its header.
bool ImageSize(const std::filesystem::path& file, int* width, int* height);

}  // namespace wirerig::gltf
