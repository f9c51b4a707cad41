// Typed, path-aware reading of JSON objects for wirerig's file formats. Every accessor either
// returns the value or throws FieldError carrying the JSON pointer of the field at fault
// ("/bending/point_loads/2/at") and what is wrong. Loaders catch FieldError at their boundary
// and turn it into a Result error, so exceptions never cross the public API.
#pragma once

#include <initializer_list>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "wirerig/runtime/conventions.h"

namespace wirerig {

struct FieldError : std::runtime_error {
  FieldError(std::string field_path, const std::string& reason)
      : std::runtime_error(field_path + ": " + reason), path(std::move(field_path)) {}
  std::string path;
};

// "must be \"a\", \"b\" or \"c\"": the message of a keyword that is none of `names`.
std::string MustBeOneOf(std::span<const std::string_view> names);

// A view of one JSON object at a path. The referenced json must outlive the view.
class JsonObject {
 public:
  // Throws FieldError unless `value` is an object.
  JsonObject(const nlohmann::json& value, std::string path);

  const std::string& path() const { return path_; }
  std::string PathOf(std::string_view key) const;
  bool Has(std::string_view key) const;

  // Throws FieldError if a key is not among `allowed` (catches misspelt fields); the message
  // suggests the nearest allowed key and lists them (name_hint.h).
  void RejectUnknownKeys(std::initializer_list<std::string_view> allowed) const;

  // Required and optional fields of each type; a present field of the wrong type throws.
  const nlohmann::json& Required(std::string_view key) const;
  JsonObject Object(std::string_view key) const;
  double Number(std::string_view key) const;
  double Number(std::string_view key, double fallback) const;
  int Integer(std::string_view key, int fallback) const;
  bool Bool(std::string_view key) const;
  bool Bool(std::string_view key, bool fallback) const;
  std::string String(std::string_view key) const;
  Vec3 Vector3(std::string_view key, const Vec3& fallback) const;
  // The optional keyword field `key`: the value paired with its name in `choices`, `fallback`
  // when absent; any other string throws FieldError ("must be \"a\", \"b\" or \"c\"").
  template <class T>
  T Keyword(std::string_view key, std::initializer_list<std::pair<std::string_view, T>> choices,
            T fallback) const {
    if (!Has(key)) return fallback;
    const std::string name = String(key);
    std::vector<std::string_view> names;
    for (const auto& [choice, value] : choices) {
      if (choice == name) return value;
      names.push_back(choice);
    }
    throw FieldError(PathOf(key), MustBeOneOf(names));
  }

 private:
  const nlohmann::json& json_;
  std::string path_;
};

// Element access for arrays: throws FieldError unless `value` is an array.
const nlohmann::json& RequireArray(const nlohmann::json& value, const std::string& path);
std::size_t ArraySize(const nlohmann::json& array);
const nlohmann::json& ArrayElement(const nlohmann::json& array, std::size_t index);
// [x, y, z] of finite-or-not numbers; range checks are the runtime's job.
Vec3 ReadVector3(const nlohmann::json& value, const std::string& path);
// An array of [x, y, z].
std::vector<Vec3> ReadVector3Array(const nlohmann::json& value, const std::string& path);

// Calls read(JsonObject element) for every element of the optional array `key` of `object`.
template <typename Read>
void ForEachElement(const JsonObject& object, std::string_view key, Read read) {
  if (!object.Has(key)) return;
  const std::string path = object.PathOf(key);
  const nlohmann::json& array = RequireArray(object.Required(key), path);
  for (std::size_t i = 0; i < ArraySize(array); ++i)
    read(JsonObject(ArrayElement(array, i), path + "/" + std::to_string(i)));
}

}  // namespace wirerig
