// File names in glTF terms: URI references and extensions.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace wirerig::gltf {

// `path` as a URI reference: '/' separators, bytes other than unreserved characters and '/'
// percent-encoded (RFC 3986).
std::string PathToUri(const std::filesystem::path& path);

// The path a URI reference names, percent-decoded; nullopt when an escape is malformed.
std::optional<std::string> UriToPath(const std::string& uri);

// The extension of `path` in lower case, with its dot (".glb"), or empty.
std::string LowerCaseExtension(const std::filesystem::path& path);

}  // namespace wirerig::gltf
