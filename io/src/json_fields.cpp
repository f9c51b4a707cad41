#include "wirerig/io/json_fields.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "wirerig/io/name_hint.h"

namespace wirerig {

JsonObject::JsonObject(const nlohmann::json& value, std::string path)
    : json_(value), path_(std::move(path)) {
  if (!json_.is_object()) throw FieldError(path_.empty() ? "/" : path_, "must be an object");
}

std::string JsonObject::PathOf(std::string_view key) const {
  return path_ + "/" + std::string(key);
}

bool JsonObject::Has(std::string_view key) const { return json_.contains(key); }

void JsonObject::RejectUnknownKeys(std::initializer_list<std::string_view> allowed) const {
  for (const auto& item : json_.items()) {
    if (std::find(allowed.begin(), allowed.end(), item.key()) == allowed.end()) {
      const std::vector<std::string> known(allowed.begin(), allowed.end());
      throw FieldError(PathOf(item.key()),
                       "unknown field" + NameHint(item.key(), known, "known fields"));
    }
  }
}

const nlohmann::json& JsonObject::Required(std::string_view key) const {
  const auto it = json_.find(key);
  if (it == json_.end()) throw FieldError(PathOf(key), "is required");
  return *it;
}

JsonObject JsonObject::Object(std::string_view key) const {
  return JsonObject(Required(key), PathOf(key));
}

double JsonObject::Number(std::string_view key) const {
  const nlohmann::json& value = Required(key);
  if (!value.is_number()) throw FieldError(PathOf(key), "must be a number");
  return value.get<double>();
}

double JsonObject::Number(std::string_view key, double fallback) const {
  return Has(key) ? Number(key) : fallback;
}

int JsonObject::Integer(std::string_view key, int fallback) const {
  if (!Has(key)) return fallback;
  const nlohmann::json& value = Required(key);
  constexpr int kLow = std::numeric_limits<int>::min(), kHigh = std::numeric_limits<int>::max();
  const auto out_of_range = [&] {
    return FieldError(PathOf(key), "is out of range (an integer within [" + std::to_string(kLow) +
                                       ", " + std::to_string(kHigh) + "])");
  };
  // Integers too large for 64 bits arrive as floating-point numbers: out of range, not "not an
  // integer"; unsigned ones above 2^63 must not wrap to negative values.
  if (value.is_number_float()) {
    const double x = value.get<double>();
    if (std::isfinite(x) && x == std::floor(x)) throw out_of_range();
    throw FieldError(PathOf(key), "must be an integer");
  }
  if (!value.is_number_integer()) throw FieldError(PathOf(key), "must be an integer");
  if (value.is_number_unsigned()) {
    if (value.get<unsigned long long>() > static_cast<unsigned long long>(kHigh))
      throw out_of_range();
    return static_cast<int>(value.get<unsigned long long>());
  }
  const auto wide = value.get<long long>();
  if (wide < kLow || wide > kHigh) throw out_of_range();
  return static_cast<int>(wide);
}

bool JsonObject::Bool(std::string_view key) const {
  const nlohmann::json& value = Required(key);
  if (!value.is_boolean()) throw FieldError(PathOf(key), "must be true or false");
  return value.get<bool>();
}

bool JsonObject::Bool(std::string_view key, bool fallback) const {
  return Has(key) ? Bool(key) : fallback;
}

std::string JsonObject::String(std::string_view key) const {
  const nlohmann::json& value = Required(key);
  if (!value.is_string()) throw FieldError(PathOf(key), "must be a string");
  return value.get<std::string>();
}

Vec3 JsonObject::Vector3(std::string_view key, const Vec3& fallback) const {
  return Has(key) ? ReadVector3(Required(key), PathOf(key)) : fallback;
}

const nlohmann::json& RequireArray(const nlohmann::json& value, const std::string& path) {
  if (!value.is_array()) throw FieldError(path, "must be an array");
  return value;
}

std::size_t ArraySize(const nlohmann::json& array) { return array.size(); }

const nlohmann::json& ArrayElement(const nlohmann::json& array, std::size_t index) {
  return array[index];
}

std::vector<Vec3> ReadVector3Array(const nlohmann::json& value, const std::string& path) {
  RequireArray(value, path);
  std::vector<Vec3> points;
  points.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i)
    points.push_back(ReadVector3(value[i], path + "/" + std::to_string(i)));
  return points;
}

Vec3 ReadVector3(const nlohmann::json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 3)
    throw FieldError(path, "must be an array of 3 numbers [x, y, z]");
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    if (!value[i].is_number()) throw FieldError(path + "/" + std::to_string(i), "must be a number");
    v[i] = value[i].get<double>();
  }
  return v;
}

std::string MustBeOneOf(std::span<const std::string_view> names) {
  std::string out = "must be ";
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
    out += '"';
    out.append(names[i]);
    out += '"';
  }
  return out;
}

}  // namespace wirerig
