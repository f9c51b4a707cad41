#include "wirerig/io/json_text.h"

#include <algorithm>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "wirerig/io/floating_point_hold.h"

namespace wirerig {

TextPosition PositionInText(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  const std::string_view before = text.substr(0, offset);
  TextPosition position;
  position.line = 1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  const std::size_t newline = before.rfind('\n');
  position.column = newline == std::string_view::npos ? offset + 1 : offset - newline;
  return position;
}

namespace {

// `text` with every byte outside printable ASCII as \xNN: the parser quotes what it read, and a
// binary file's bytes would otherwise go to the terminal as they are.
std::string Printable(std::string_view text) {
  std::string out;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7f) {
      out += c;
    } else {
      constexpr char kHex[] = "0123456789abcdef";
      out.append("\\x").append(1, kHex[byte >> 4]).append(1, kHex[byte & 15]);
    }
  }
  return out;
}

}  // namespace

std::string ValidUtf8(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char lead = byte(i);
    // The sequence's length and the range its second byte must lie in (RFC 3629: no overlong
    // forms, no surrogates, nothing above U+10FFFF).
    std::size_t length = 0;
    unsigned char low = 0x80, high = 0xbf;
    if (lead < 0x80)
      length = 1;
    else if (lead >= 0xc2 && lead <= 0xdf)
      length = 2;
    else if (lead == 0xe0)
      length = 3, low = 0xa0;
    else if (lead >= 0xe1 && lead <= 0xec)
      length = 3;
    else if (lead == 0xed)
      length = 3, high = 0x9f;
    else if (lead >= 0xee && lead <= 0xef)
      length = 3;
    else if (lead == 0xf0)
      length = 4, low = 0x90;
    else if (lead >= 0xf1 && lead <= 0xf3)
      length = 4;
    else if (lead == 0xf4)
      length = 4, high = 0x8f;
    bool whole = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; whole && k < length; ++k) {
      const unsigned char c = byte(i + k);
      whole = k == 1 ? c >= low && c <= high : c >= 0x80 && c <= 0xbf;
    }
    if (whole) {
      out.append(text.substr(i, length));
      i += length;
    } else {
      out.append("\xef\xbf\xbd");  // U+FFFD for the one byte
      ++i;
    }
  }
  return out;
}

std::string DumpJson(const nlohmann::json& document, int indent) {
  return document.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

Result<nlohmann::json> ParseJsonText(std::string_view text, std::string_view source_name) {
  // No JSON text holds a control byte other than tab, newline and return, not even in a string:
  // the first one says the file is not text (the parser would report "unexpected end of
  // input" at a NUL).
  const auto control = std::find_if(text.begin(), text.end(), [](char c) {
    const auto byte = static_cast<unsigned char>(c);
    return byte < 0x20 && c != '\t' && c != '\n' && c != '\r';
  });
  if (control != text.end()) {
    const std::size_t offset = std::size_t(control - text.begin());
    const TextPosition at = PositionInText(text, offset);
    return Error{std::string(source_name) + ": not valid JSON: line " + std::to_string(at.line) +
                 ", column " + std::to_string(at.column) + ": control byte " +
                 Printable(text.substr(offset, 1)) + " (a binary file, not JSON text)"};
  }
  // A key twice in one object: the parser would keep the last silently (a mapping's
  // "LeftHand" given twice drove the second part). Noted while parsing, with the keys of the
  // objects around it, and refused after.
  std::vector<std::set<std::string>> keys_of_open_objects;
  std::vector<std::string> path;  // the key each open object is under ("" at the top)
  std::string pending_key;
  std::optional<std::string> duplicate;
  const nlohmann::json::parser_callback_t note_duplicates =
      [&](int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
        using Event = nlohmann::json::parse_event_t;
        if (event == Event::object_start) {
          path.push_back(pending_key);
          keys_of_open_objects.emplace_back();
        } else if (event == Event::object_end && !keys_of_open_objects.empty()) {
          keys_of_open_objects.pop_back();
          path.pop_back();
        } else if (event == Event::key && !keys_of_open_objects.empty()) {
          pending_key = parsed.get<std::string>();
          if (!keys_of_open_objects.back().insert(pending_key).second && !duplicate) {
            std::string where;
            for (std::size_t i = 1; i < path.size(); ++i) where += "/" + path[i];
            duplicate = (where.empty() ? std::string("/") : where) + ": the key \"" + pending_key +
                        "\" appears twice in one object";
          }
        }
        return true;
      };
  try {
    const ScopedFloatingPointHold hold;
    nlohmann::json document = nlohmann::json::parse(text, note_duplicates);
    if (duplicate) return Error{std::string(source_name) + ": " + Printable(*duplicate)};
    return document;
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte counts the bytes read, the offending one included.
    const TextPosition at = PositionInText(text, e.byte > 0 ? e.byte - 1 : 0);
    // what(): "[json.exception.parse_error.101] parse error at line 1, column 2: <reason>".
    std::string reason = e.what();
    if (const std::size_t colon = reason.find(": "); colon != std::string::npos)
      reason.erase(0, colon + 2);
    return Error{std::string(source_name) + ": not valid JSON: line " + std::to_string(at.line) +
                 ", column " + std::to_string(at.column) + ": " + Printable(reason)};
  } catch (const nlohmann::json::exception& e) {
    // A number too large for a double: "[json.exception.out_of_range.406] number overflow
    // parsing '1e999'"; its first occurrence gives the position.
    std::string reason = e.what();
    if (const std::size_t bracket = reason.find("] "); bracket != std::string::npos)
      reason.erase(0, bracket + 2);
    std::string where;
    const std::size_t open = reason.find('\'');
    const std::size_t close = reason.rfind('\'');
    if (open != std::string::npos && close > open + 1) {
      const std::size_t at = text.find(std::string_view(reason).substr(open + 1, close - open - 1));
      if (at != std::string_view::npos) {
        const TextPosition position = PositionInText(text, at);
        where = "line " + std::to_string(position.line) + ", column " +
                std::to_string(position.column) + ": ";
      }
    }
    return Error{std::string(source_name) + ": not valid JSON: " + where + Printable(reason)};
  }
}

}  // namespace wirerig
