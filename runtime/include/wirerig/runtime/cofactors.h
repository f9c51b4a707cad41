// The cofactor matrix of a 3x3 linear map: how it turns normals.
#pragma once

#include "wirerig/runtime/conventions.h"

namespace wirerig {

// For columns c0, c1, c2 of `l`: [c1 x c2, c2 x c0, c0 x c1], det(l) times the inverse
// transpose, computed without dividing. Turns a surface's normals as `l` turns its points, up to
// length (and, where det(l) < 0, sign).
inline Mat3 Cofactors(const Mat3& l) {
  Mat3 cof;
  cof.col(0) = l.col(1).cross(l.col(2));
  cof.col(1) = l.col(2).cross(l.col(0));
  cof.col(2) = l.col(0).cross(l.col(1));
  return cof;
}

}  // namespace wirerig
