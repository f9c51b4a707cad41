// Keyframed tracks: one input of the runtime (a load's magnitude, a direction, a position along
// a wire, a boundary condition, ...) as a function of time. Raw description -> Build -> an
// immutable Track that samples at any time (random access, no allocation).
//
// RawTrack rules (checked by ValidateRawTrack): at least one key; times finite and strictly
// increasing; values finite. A key's interpolation governs the segment from that key to the
// next one:
//   kStep    holds the key's value until the next key;
//   kLinear  straight line to the next key's value;
//   kCubic   cubic Hermite with Catmull-Rom tangents (non-uniform: the finite difference over
//            the two neighbouring keys; one-sided at the first and last key), C1 across keys.
// Before the first key a track holds the first value; after the last, the last value.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "wirerig/io/result.h"
#include "wirerig/runtime/conventions.h"

namespace wirerig {

enum class Interpolation : int { kStep = 0, kLinear = 1, kCubic = 2 };

// Names used in files: "step", "linear", "cubic".
std::string_view ToString(Interpolation interpolation);
bool ParseInterpolation(std::string_view name, Interpolation* out);

template <typename T>
struct RawKey {
  double time = 0.0;  // s
  T value = T();      // finite
  Interpolation interpolation = Interpolation::kLinear;
};

template <typename T>
struct RawTrack {
  std::vector<RawKey<T>> keys;
};

using RawScalarTrack = RawTrack<double>;
using RawVectorTrack = RawTrack<Vec3>;

// Empty when valid, else "keys[i].field: reason" naming the first broken rule.
template <typename T>
std::string ValidateRawTrack(const RawTrack<T>& raw);

// A built track: keys in struct-of-arrays form with precomputed Hermite tangents.
template <typename T>
class Track {
 public:
  Track() = default;  // a track that samples T{} (zero) everywhere; IsEmpty() is true

  bool IsEmpty() const { return times_.empty(); }
  double StartTime() const { return times_.empty() ? 0.0 : times_.front(); }
  double EndTime() const { return times_.empty() ? 0.0 : times_.back(); }
  std::span<const double> KeyTimes() const { return times_; }

  // The value at time t (s). Never allocates; O(log #keys).
  T Sample(double t) const;

 private:
  template <typename U>
  friend Result<Track<U>> BuildTrack(const RawTrack<U>& raw);

  std::vector<double> times_;
  std::vector<T> values_;
  std::vector<T> tangents_;  // dvalue/dt at each key, for cubic segments
  std::vector<Interpolation> interpolations_;
};

using ScalarTrack = Track<double>;
using VectorTrack = Track<Vec3>;

// Validates, then builds. The error is ValidateRawTrack's message.
template <typename T>
Result<Track<T>> BuildTrack(const RawTrack<T>& raw);

// A track holding one value at all times.
template <typename T>
Track<T> ConstantTrack(const T& value);

}  // namespace wirerig
