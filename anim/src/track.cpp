#include "wirerig/anim/track.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "wirerig/io/finite.h"

namespace wirerig {
namespace {

template <typename T>
T ZeroValue() {
  if constexpr (std::is_same_v<T, Vec3>) {
    return Vec3::Zero();
  } else {
    return T(0);
  }
}

// Cubic Hermite on [0, 1] with end values a, b and end derivatives ta, tb (already scaled
// by the segment's duration).
template <typename T>
T Hermite(const T& a, const T& b, const T& ta, const T& tb, double u) {
  const double u2 = u * u, u3 = u2 * u;
  const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u;
  const double h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
  return T(h00 * a + h10 * ta + h01 * b + h11 * tb);
}

}  // namespace

std::string_view ToString(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::kStep:
      return "step";
    case Interpolation::kLinear:
      return "linear";
    case Interpolation::kCubic:
      return "cubic";
  }
  return "unknown";
}

bool ParseInterpolation(std::string_view name, Interpolation* out) {
  for (Interpolation i : {Interpolation::kStep, Interpolation::kLinear, Interpolation::kCubic}) {
    if (name == ToString(i)) {
      *out = i;
      return true;
    }
  }
  return false;
}

template <typename T>
std::string ValidateRawTrack(const RawTrack<T>& raw) {
  if (raw.keys.empty()) return "keys: a track needs at least one key";
  for (std::size_t i = 0; i < raw.keys.size(); ++i) {
    const RawKey<T>& key = raw.keys[i];
    std::string where = "keys[";
    where.append(std::to_string(i)).append("].");
    if (!IsFinite(key.time)) return where.append("time: must be finite");
    if (i > 0 && !(key.time > raw.keys[i - 1].time)) {
      return where.append("time: key times must be strictly increasing");
    }
    if (!IsFinite(key.value)) return where.append("value: must be finite");
    const int interpolation = static_cast<int>(key.interpolation);
    if (interpolation < 0 || interpolation > 2) return where.append("interpolation: unknown");
  }
  return {};
}

template <typename T>
Result<Track<T>> BuildTrack(const RawTrack<T>& raw) {
  if (std::string error = ValidateRawTrack(raw); !error.empty()) return Error{std::move(error)};
  Track<T> track;
  const std::size_t n = raw.keys.size();
  track.times_.reserve(n);
  track.values_.reserve(n);
  track.interpolations_.reserve(n);
  for (const RawKey<T>& key : raw.keys) {
    track.times_.push_back(key.time);
    track.values_.push_back(key.value);
    track.interpolations_.push_back(key.interpolation);
  }
  // Catmull-Rom tangents (value per second); one-sided at the ends, zero for a single key.
  track.tangents_.assign(n, ZeroValue<T>());
  for (std::size_t i = 0; i < n && n > 1; ++i) {
    const std::size_t lo = i == 0 ? 0 : i - 1, hi = i + 1 == n ? n - 1 : i + 1;
    track.tangents_[i] =
        T((track.values_[hi] - track.values_[lo]) / (track.times_[hi] - track.times_[lo]));
  }
  return track;
}

template <typename T>
T Track<T>::Sample(double t) const {
  if (times_.empty()) return ZeroValue<T>();
  if (!(t > times_.front())) return values_.front();  // also NaN time: the first value
  if (t >= times_.back()) return values_.back();
  // The segment [times_[i], times_[i + 1]) holding t.
  const std::size_t i =
      static_cast<std::size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin()) -
      1;
  const double t0 = times_[i], t1 = times_[i + 1], span = t1 - t0;
  const double u = (t - t0) / span;
  switch (interpolations_[i]) {
    case Interpolation::kStep:
      return values_[i];
    case Interpolation::kLinear:
      return T((1.0 - u) * values_[i] + u * values_[i + 1]);
    case Interpolation::kCubic:
      return Hermite<T>(values_[i], values_[i + 1], T(span * tangents_[i]),
                        T(span * tangents_[i + 1]), u);
  }
  return values_[i];
}

template <typename T>
Track<T> ConstantTrack(const T& value) {
  RawTrack<T> raw;
  raw.keys.push_back({0.0, value, Interpolation::kStep});
  return BuildTrack(raw).value();
}

template std::string ValidateRawTrack(const RawTrack<double>&);
template std::string ValidateRawTrack(const RawTrack<Vec3>&);
template Result<Track<double>> BuildTrack(const RawTrack<double>&);
template Result<Track<Vec3>> BuildTrack(const RawTrack<Vec3>&);
template Track<double> ConstantTrack(const double&);
template Track<Vec3> ConstantTrack(const Vec3&);
template class Track<double>;
template class Track<Vec3>;

}  // namespace wirerig
