#include "wirerig/runtime/status.h"

namespace wirerig {

std::string ToString(const Status& status) {
  if (status.ok()) return "ok";
  std::string text(status.field);
  if (status.index >= 0) text += "[" + std::to_string(status.index) + "]";
  if (!status.member.empty()) {
    text += ".";
    text += status.member;
  }
  text += ": ";
  text += status.reason;
  return text;
}

}  // namespace wirerig
