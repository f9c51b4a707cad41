// Status: the runtime's one error policy. Validate() and Run() return a Status that is
// either ok or names the offending input and says what is wrong with it. All strings
// are static: making or copying a Status never allocates.
#pragma once

#include <string>
#include <string_view>

namespace wirerig {

struct Status {
  // The input at fault, e.g. "length" or "point_loads"; empty when ok.
  std::string_view field;
  // Index into an array input (e.g. which point load), or -1.
  int index = -1;
  // Member of that element, e.g. "at"; may be empty.
  std::string_view member;
  // What is wrong, e.g. "must lie in [0, 1]"; empty when ok.
  std::string_view reason;

  bool ok() const { return reason.empty(); }
  explicit operator bool() const { return ok(); }

  static Status Ok() { return {}; }
  static Status Invalid(std::string_view field, std::string_view reason) {
    return {field, -1, {}, reason};
  }
  static Status InvalidElement(std::string_view field, int index, std::string_view member,
                               std::string_view reason) {
    return {field, index, member, reason};
  }
};

// "field[index].member: reason", for messages. Allocates; not for hot paths.
std::string ToString(const Status& status);

}  // namespace wirerig
