// File names in glTF terms: URI references and extensions.
#pragma once

#include <filesystem>
#include <string>

namespace wirerig::gltf {

// `path` as a URI reference: '/' separators, bytes other than unreserved characters and '/'
// percent-encoded (RFC 3986).
std::string PathToUri(const std::filesystem::path& path);

// The extension of `path` in lower case, with its dot (".glb"), or empty.
std::string LowerCaseExtension(const std::filesystem::path& path);

}  // namespace wirerig::gltf
