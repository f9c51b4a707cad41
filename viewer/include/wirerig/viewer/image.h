// Image: 8-bit RGBA pixels, row-major, origin at the top-left (as PNG files), sRGB-encoded as
// the renderer writes them; and PNG reading and writing.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "wirerig/io/result.h"

namespace wirerig {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes

  // The pixel at column x, row y (0 <= x < width, 0 <= y < height): r, g, b, a.
  std::array<std::uint8_t, 4> At(int x, int y) const {
    const std::size_t i = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
    return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
  }
};

// The most pixels SavePng writes: stb's PNG encoder sizes its buffers in int, and 4 bytes a
// pixel (a gigabyte here) stay well below 2^31.
inline constexpr std::int64_t kMaxPngPixels = std::int64_t{1} << 28;

// Writes `image` as a PNG atomically (a temporary file in the same folder renamed over
// `path`). Returns the path, or an error naming the file (an image of more than kMaxPngPixels
// is refused).
Result<std::filesystem::path> SavePng(const Image& image, const std::filesystem::path& path);

// Reads a PNG (or any format stb_image reads) as RGBA. The error names the file.
Result<Image> LoadPng(const std::filesystem::path& path);

}  // namespace wirerig
