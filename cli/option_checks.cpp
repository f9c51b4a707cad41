#include "option_checks.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>

namespace wirerig::cli {
namespace {

std::string Number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%g", x);
  return buffer;
}

// A validator accepting finite numbers for which `ok` holds, else saying `bound`.
CLI::Validator NumberCheck(const std::string& bound, std::function<bool(double)> ok) {
  return CLI::Validator(
      [bound, ok](std::string& input) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(input.c_str(), &end);
        if (input.empty() || end == input.c_str() || *end != '\0' || !std::isfinite(value))
          return "must be a number " + bound + " (got \"" + input + "\")";
        if (!ok(value)) return "must be " + bound + " (got " + input + ")";
        return {};
      },
      bound);
}

}  // namespace

CLI::Validator InRange(double min, double max) {
  return NumberCheck("in [" + Number(min) + ", " + Number(max) + "]",
                     [min, max](double x) { return x >= min && x <= max; });
}

CLI::Validator AtLeast(double min) {
  return NumberCheck(">= " + Number(min), [min](double x) { return x >= min; });
}

CLI::Validator Above(double min) {
  return NumberCheck("> " + Number(min), [min](double x) { return x > min; });
}

bool ParseImageSize(const std::string& text, int* width, int* height) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x') return false;
  if (w < 16 || h < 16 || w > 8192 || h > 8192) return false;
  *width = w;
  *height = h;
  return true;
}

CLI::Validator ImageSize() {
  return CLI::Validator(
      [](std::string& input) -> std::string {
        int w = 0, h = 0;
        if (ParseImageSize(input, &w, &h)) return {};
        return std::string("must be ") + kImageSizeRule + " (got \"" + input + "\")";
      },
      "WIDTHxHEIGHT");
}

}  // namespace wirerig::cli
