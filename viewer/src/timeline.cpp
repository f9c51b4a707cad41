#include "wirerig/viewer/timeline.h"

#include <algorithm>
#include <cmath>

namespace wirerig {

void Timeline::Advance(double dt) {
  if (!playing || duration <= 0.0) return;
  double t = time + dt * speed;
  if (loop) {
    t = std::fmod(t, duration);
    if (t < 0.0) t += duration;
  } else if (t >= duration || t <= 0.0) {
    t = std::clamp(t, 0.0, duration);
    playing = false;
  }
  time = t;
}

void Timeline::Seek(double t) { time = std::clamp(t, 0.0, std::max(duration, 0.0)); }

}  // namespace wirerig
