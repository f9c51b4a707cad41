#include "gltf_texture_size.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <stb_image.h>
#include <stb_image_resize.h>
#include <stb_image_write.h>

// Debian's libstb ships the stb implementations compiled (libstb.so): linked, not defined here.

namespace wirerig::gltf {
namespace {

constexpr int kJpegQuality = 90;

}  // namespace

Result<std::vector<unsigned char>> FitImage(std::span<const unsigned char> bytes,
                                            const std::string& mime_type, int max_size) {
  const int length = static_cast<int>(std::min<std::size_t>(bytes.size(), 0x7fffffff));
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), length, &width, &height, &channels))
    return Error{std::string("cannot read the image: ") + stbi_failure_reason()};
  const int longer = std::max(width, height);
  if (max_size <= 0 || longer <= max_size)
    return std::vector<unsigned char>(bytes.begin(), bytes.end());
  int read = 0;
  const std::unique_ptr<unsigned char, void (*)(void*)> pixels(
      stbi_load_from_memory(bytes.data(), length, &width, &height, &read, channels),
      stbi_image_free);
  if (!pixels) return Error{std::string("cannot decode the image: ") + stbi_failure_reason()};
  const double scale = double(max_size) / double(longer);
  const int fitted_width = std::max(1, static_cast<int>(std::lround(width * scale)));
  const int fitted_height = std::max(1, static_cast<int>(std::lround(height * scale)));
  std::vector<unsigned char> resized(std::size_t(fitted_width) * std::size_t(fitted_height) *
                                     std::size_t(channels));
  const int alpha = channels == 4 ? 3 : channels == 2 ? 1 : STBIR_ALPHA_CHANNEL_NONE;
  if (!stbir_resize_uint8_srgb(pixels.get(), width, height, 0, resized.data(), fitted_width,
                               fitted_height, 0, channels, alpha, 0))
    return Error{"cannot resize the image"};
  std::vector<unsigned char> out;
  auto append = [](void* context, void* data, int size) {
    auto* sink = static_cast<std::vector<unsigned char>*>(context);
    const auto* begin = static_cast<const unsigned char*>(data);
    sink->insert(sink->end(), begin, begin + size);
  };
  const int ok = mime_type == "image/jpeg"
                     ? stbi_write_jpg_to_func(append, &out, fitted_width, fitted_height, channels,
                                              resized.data(), kJpegQuality)
                     : stbi_write_png_to_func(append, &out, fitted_width, fitted_height, channels,
                                              resized.data(), fitted_width * channels);
  if (!ok) return Error{"cannot encode the resized image"};
  return out;
}

bool ImageSize(const std::filesystem::path& file, int* width, int* height) {
  int channels = 0;
  return stbi_info(file.string().c_str(), width, height, &channels) != 0;
}

}  // namespace wirerig::gltf
