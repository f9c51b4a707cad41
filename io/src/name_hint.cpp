#include "wirerig/io/name_hint.h"

#include <algorithm>
#include <numeric>

namespace wirerig {

std::size_t EditDistance(std::string_view a, std::string_view b) {
  // One row of the dynamic programme at a time.
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string NearestName(std::string_view name, const std::vector<std::string>& known) {
  const std::size_t reach = std::max<std::size_t>(1, name.size() / 3);
  std::string best;
  std::size_t best_distance = reach + 1;
  for (const std::string& candidate : known) {
    const std::size_t distance = EditDistance(name, candidate);
    if (distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

std::string NameHint(std::string_view name, const std::vector<std::string>& known,
                     std::string_view plural) {
  if (known.empty()) return " (there are no " + std::string(plural) + ")";
  std::string hint;
  if (const std::string nearest = NearestName(name, known); !nearest.empty())
    hint = "; did you mean \"" + nearest + "\"?";
  constexpr std::size_t kMaxListed = 20;
  hint += " (" + std::string(plural) + ": ";
  for (std::size_t i = 0; i < known.size() && i < kMaxListed; ++i) {
    if (i > 0) hint += ", ";
    hint += known[i];
  }
  if (known.size() > kMaxListed)
    hint += ", and " + std::to_string(known.size() - kMaxListed) + " more";
  return hint + ")";
}

}  // namespace wirerig
