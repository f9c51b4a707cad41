#include "gltf_texture_size.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>

#include <stb_image.h>
#include <stb_image_resize.h>
#include <stb_image_write.h>

// Debian's libstb ships the stb implementations compiled (libstb.so): linked, not defined here.

namespace wirerig::gltf {
namespace {

constexpr int kJpegQuality = 90;
constexpr const char* kJpeg = "image/jpeg";
// JPEG stores each side in 16 bits; stb_image_write would truncate a longer one unchecked.
constexpr int kJpegMaxSide = 65535;

void Append(void* context, void* data, int size) {
  auto* sink = static_cast<std::vector<unsigned char>*>(context);
  const auto* begin = static_cast<const unsigned char*>(data);
  sink->insert(sink->end(), begin, begin + size);
}

using Pixels = std::unique_ptr<unsigned char, void (*)(void*)>;

}  // namespace

Result<StoredImage> StoreImage(std::span<const unsigned char> bytes, const std::string& mime_type,
                               const ImageStorage& storage) {
  StoredImage stored{std::vector<unsigned char>(bytes.begin(), bytes.end()), mime_type};
  const int length = static_cast<int>(std::min<std::size_t>(bytes.size(), 0x7fffffff));
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), length, &width, &height, &channels))
    return Error{std::string("cannot read the image: ") + stbi_failure_reason()};
  const int longer = std::max(width, height);
  const bool fit = storage.max_size > 0 && longer > storage.max_size;
  const bool to_jpeg = storage.as_jpeg && mime_type != kJpeg;
  if (!fit && !to_jpeg) return stored;
  int read = 0;
  Pixels pixels(stbi_load_from_memory(bytes.data(), length, &width, &height, &read, channels),
                stbi_image_free);
  if (!pixels) return Error{std::string("cannot decode the image: ") + stbi_failure_reason()};
  if (fit) {
    const double scale = double(storage.max_size) / double(longer);
    const int fitted_width = std::max(1, static_cast<int>(std::lround(width * scale)));
    const int fitted_height = std::max(1, static_cast<int>(std::lround(height * scale)));
    auto* resized = static_cast<unsigned char*>(std::malloc(
        std::size_t(fitted_width) * std::size_t(fitted_height) * std::size_t(channels)));
    if (!resized) return Error{"cannot resize the image: out of memory"};
    Pixels owned(resized, std::free);
    const int alpha = channels == 4 ? 3 : channels == 2 ? 1 : STBIR_ALPHA_CHANNEL_NONE;
    if (!stbir_resize_uint8_srgb(pixels.get(), width, height, 0, resized, fitted_width,
                                 fitted_height, 0, channels, alpha, 0))
      return Error{"cannot resize the image"};
    pixels = std::move(owned);
    width = fitted_width;
    height = fitted_height;
    stored.bytes.clear();
    const int ok = mime_type == kJpeg
                       ? stbi_write_jpg_to_func(Append, &stored.bytes, width, height, channels,
                                                pixels.get(), kJpegQuality)
                       : stbi_write_png_to_func(Append, &stored.bytes, width, height, channels,
                                                pixels.get(), width * channels);
    if (!ok) return Error{"cannot encode the resized image"};
  }
  if (to_jpeg && std::max(width, height) <= kJpegMaxSide) {
    // JPEG has no alpha: stb_image_write leaves the alpha channel out. Kept only when smaller;
    // an encoding that fails keeps the PNG (resized, if it was).
    std::vector<unsigned char> jpeg;
    if (stbi_write_jpg_to_func(Append, &jpeg, width, height, channels, pixels.get(),
                               kJpegQuality) &&
        jpeg.size() < stored.bytes.size())
      stored = StoredImage{std::move(jpeg), kJpeg};
  }
  return stored;
}

bool ImageSize(const std::filesystem::path& file, int* width, int* height) {
  int channels = 0;
  return stbi_info(file.string().c_str(), width, height, &channels) != 0;
}

}  // namespace wirerig::gltf
