// Hints for a name that matches none of the known ones (a misspelt JSON field, part or clip):
// the nearest known name when it is close enough to be a likely misspelling, and the list of
// the known names.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace wirerig {

// Levenshtein distance: single-byte insertions, deletions and substitutions.
std::size_t EditDistance(std::string_view a, std::string_view b);

// The known name nearest to `name` if its edit distance is at most max(1, |name| / 3), else
// empty. Ties go to the first in `known`.
std::string NearestName(std::string_view name, const std::vector<std::string>& known);

// `; did you mean "<nearest>"? (<plural>: a, b, c)`, or ` (<plural>: a, b, c)` with no near
// name, or ` (there are no <plural>)`. At most 20 names are listed ("..., and 12 more").
std::string NameHint(std::string_view name, const std::vector<std::string>& known,
                     std::string_view plural);

}  // namespace wirerig
