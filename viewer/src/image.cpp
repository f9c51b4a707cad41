#include "wirerig/viewer/image.h"

#include <cstring>
#include <string>

#include <stb_image.h>
#include <stb_image_write.h>

#include "wirerig/io/atomic_file.h"

// Debian's libstb ships stb_image and stb_image_write compiled (libstb.so): the
// implementations are linked, not defined here.

namespace wirerig {

Result<std::filesystem::path> SavePng(const Image& image, const std::filesystem::path& path) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != std::size_t(image.width) * std::size_t(image.height) * 4) {
    return Error{path.string() + ": cannot write an empty or inconsistent image (" +
                 std::to_string(image.width) + "x" + std::to_string(image.height) + ")"};
  }
  if (std::int64_t(image.width) * image.height > kMaxPngPixels) {
    return Error{path.string() + ": a " + std::to_string(image.width) + "x" +
                 std::to_string(image.height) + " image is more than the " +
                 std::to_string(kMaxPngPixels) + " pixels a PNG is written with"};
  }
  std::string bytes;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<std::size_t>(size));
  };
  const int ok = stbi_write_png_to_func(append, &bytes, image.width, image.height, 4,
                                        image.rgba.data(), image.width * 4);
  if (ok == 0) return Error{path.string() + ": PNG encoding failed"};
  return WriteFileAtomically(path, bytes);
}

Result<Image> LoadPng(const std::filesystem::path& path) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.string().c_str(), &w, &h, &channels, 4);
  if (data == nullptr) {
    std::string reason = stbi_failure_reason() != nullptr ? stbi_failure_reason() : "unknown";
    return Error{path.string() + ": cannot read the image: " + reason};
  }
  Image image;
  image.width = w;
  image.height = h;
  image.rgba.resize(std::size_t(w) * std::size_t(h) * 4);
  std::memcpy(image.rgba.data(), data, image.rgba.size());
  stbi_image_free(data);
  return image;
}

}  // namespace wirerig
