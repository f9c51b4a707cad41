// Parsing JSON text for wirerig's loaders: a syntax error comes back as a Result error giving
// the line and column where it was found, never as an exception.
#pragma once

#include <cstddef>
#include <string_view>

#include <nlohmann/json.hpp>

#include "wirerig/io/result.h"

namespace wirerig {

struct TextPosition {
  std::size_t line = 1;    // 1-based
  std::size_t column = 1;  // 1-based, in bytes
};

// The line and column of byte `offset` (0-based) of `text`; an offset past the end is the
// position just after the last byte.
TextPosition PositionInText(std::string_view text, std::size_t offset);

// Errors read "<source_name>: not valid JSON: line 3, column 14: <what the parser expected>",
// the position being where the parser stopped (the last byte of the offending token).
// Floating-point traps are held while parsing (huge literals overflow).
Result<nlohmann::json> ParseJsonText(std::string_view text, std::string_view source_name);

// `text` as valid UTF-8: every byte that does not begin or continue a well-formed sequence
// becomes U+FFFD. JSON and glTF hold UTF-8 only (their writers throw on anything else), while
// names from mesh files (Assimp's bytes) and paths from the command line may be Latin-1 or
// anything.
std::string ValidUtf8(std::string_view text);

// `document` as JSON text (indented by `indent` spaces, or compact when negative), any string
// in it that is not UTF-8 written with U+FFFD: never throws for encoding.
std::string DumpJson(const nlohmann::json& document, int indent = -1);

}  // namespace wirerig
