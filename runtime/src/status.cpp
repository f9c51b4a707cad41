#include "wirerig/runtime/status.h"

namespace wirerig {

std::string ToString(const Status& status) {
  if (status.ok()) return "ok";
  // Appends only: GCC 12 reports a false -Wrestrict on chained operator+ at -O3.
  std::string text(status.field);
  if (status.index >= 0) text.append("[").append(std::to_string(status.index)).append("]");
  if (!status.member.empty()) text.append(".").append(status.member);
  text.append(": ").append(status.reason);
  return text;
}

}  // namespace wirerig
