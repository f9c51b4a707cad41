// The parts' parent links as indices (-1 for the root), and walks along them.
#pragma once

#include <cstddef>
#include <vector>

namespace wirerig {

// Whether `part` is `ancestor` or lies below it.
inline bool AtOrBelow(const std::vector<int>& parent, int part, int ancestor) {
  for (int p = part; p >= 0; p = parent[std::size_t(p)])
    if (p == ancestor) return true;
  return false;
}

}  // namespace wirerig
