#!/usr/bin/env bash
# Configures and builds wirerig. Usage: scripts/build.sh [release|asan|nocgal]
#   release  ->  build/        optimised, with tests, benchmarks and the CLI
#   asan     ->  build-asan/   AddressSanitizer + UndefinedBehaviorSanitizer, no benchmarks or viewer
#   nocgal   ->  build-nocgal/ optimised, without CGAL (WIRERIG_WITH_CGAL=OFF): libraries and CLI
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
kind=${1:-release}
jobs=${WIRERIG_JOBS:-$(nproc)}

case "$kind" in
  release) dir=$repo_root/build
           flags=(-DCMAKE_BUILD_TYPE=Release) ;;
  # The sanitizer pass covers the libraries, the CLI and their tests; the OpenGL viewer and
  # the benchmarks are left to the release pass (Mesa's own code is not ours to sanitize).
  # -O1 -g1 (line tables only) keeps the build quick and the reports symbolized.
  asan)    dir=$repo_root/build-asan
           flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1"
                  -DWIRERIG_SANITIZE=ON -DWIRERIG_BUILD_BENCHMARKS=OFF
                  -DWIRERIG_BUILD_VIEWER=OFF) ;;
  nocgal)  dir=$repo_root/build-nocgal
           flags=(-DCMAKE_BUILD_TYPE=Release -DWIRERIG_WITH_CGAL=OFF -DWIRERIG_BUILD_TESTS=OFF
                  -DWIRERIG_BUILD_BENCHMARKS=OFF -DWIRERIG_BUILD_VIEWER=OFF) ;;
  *) echo "usage: $0 [release|asan|nocgal]" >&2; exit 2 ;;
esac

generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
if [ ! -f "$dir/CMakeCache.txt" ]; then
  cmake -S "$repo_root" -B "$dir" "${generator[@]}" "${flags[@]}" -DWIRERIG_WARNINGS_AS_ERRORS=ON >/dev/null
fi
cmake --build "$dir" --parallel "$jobs"
