// Embedded textures fitted within a size (GltfExportOptions::max_texture_size): decoded with
// stb_image, downscaled in sRGB (stb_image_resize, alpha not premultiplied), re-encoded in their
// own format with stb_image_write (PNG; JPEG at quality 90).
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "wirerig/io/result.h"

namespace wirerig::gltf {

// `bytes` (a PNG or JPEG, `mime_type` "image/png" or "image/jpeg") with its longer side at most
// `max_size` pixels (aspect kept, each side at least 1): the same bytes when it fits already or
// `max_size` is 0. Fails, with the reason, when the image cannot be decoded or encoded.
Result<std::vector<unsigned char>> FitImage(std::span<const unsigned char> bytes,
                                            const std::string& mime_type, int max_size);

// The size of the image in `file`, pixels; false when stb_image cannot read its header.
bool ImageSize(const std::filesystem::path& file, int* width, int* height);

}  // namespace wirerig::gltf
