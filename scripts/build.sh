#!/usr/bin/env bash
# Configures and builds wirerig. Usage: scripts/build.sh [release|asan|nocgal|fuzz] [TARGET...]
#   release  ->  build/        optimised, with tests, benchmarks and the CLI (tests and the
#                              larger libraries compiled in batches: WIRERIG_UNITY_BUILD)
#   asan     ->  build-asan/   clang, AddressSanitizer + UndefinedBehaviorSanitizer, with the
#                              libFuzzer targets (fuzz/); no benchmarks or viewer
#   nocgal   ->  build-nocgal/ optimised, without CGAL (WIRERIG_WITH_CGAL=OFF): libraries and CLI
#                              (scripts/test.sh builds the CLI target alone: all its check runs)
#   fuzz     ->  build-fuzz/   clang, the libFuzzer targets and the libraries they need only
#                              (no tests, CLI or CGAL): what scripts/fuzz.sh builds
# TARGETs (default: all) are built instead of everything. A folder configured with other
# settings (an older build-asan made by GCC, say) is configured afresh.
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
kind=${1:-release}
shift || true
jobs=${WIRERIG_JOBS:-$(nproc)}

# The sanitizer passes build with clang: libFuzzer (fuzz/) is clang's, and its coverage
# instrumentation (-fsanitize=fuzzer-no-link) goes into the same libraries the tests use, so
# the fuzzers come out of the sanitizer build instead of a build of their own.
clang_flags=(-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang)
case "$kind" in
  release) dir=$repo_root/build
           flags=(-DCMAKE_BUILD_TYPE=Release -DWIRERIG_UNITY_BUILD=ON) ;;
  # The sanitizer pass covers the libraries, the CLI and their tests; the OpenGL viewer and
  # the benchmarks are left to the release pass (Mesa's own code is not ours to sanitize).
  # -O1 -g1 (line tables only) keeps the build quick and the reports symbolized.
  asan)    dir=$repo_root/build-asan
           flags=("${clang_flags[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo
                  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1"
                  -DWIRERIG_SANITIZE=ON -DWIRERIG_BUILD_FUZZERS=ON -DWIRERIG_UNITY_BUILD=ON
                  -DWIRERIG_BUILD_BENCHMARKS=OFF -DWIRERIG_BUILD_VIEWER=OFF) ;;
  # Batched like the release build, so that with ccache (below) every object the two share
  # (runtime, anim, most of rig) comes from the cache.
  nocgal)  dir=$repo_root/build-nocgal
           flags=(-DCMAKE_BUILD_TYPE=Release -DWIRERIG_UNITY_BUILD=ON -DWIRERIG_WITH_CGAL=OFF
                  -DWIRERIG_BUILD_TESTS=OFF
                  -DWIRERIG_BUILD_BENCHMARKS=OFF -DWIRERIG_BUILD_VIEWER=OFF) ;;
  fuzz)    dir=$repo_root/build-fuzz
           flags=("${clang_flags[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo
                  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1"
                  -DWIRERIG_SANITIZE=ON -DWIRERIG_BUILD_FUZZERS=ON -DWIRERIG_WITH_CGAL=OFF
                  -DWIRERIG_BUILD_TESTS=OFF -DWIRERIG_BUILD_CLI=OFF
                  -DWIRERIG_BUILD_BENCHMARKS=OFF -DWIRERIG_BUILD_VIEWER=OFF) ;;
  *) echo "usage: $0 [release|asan|nocgal|fuzz] [TARGET...]" >&2; exit 2 ;;
esac

generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
# ccache (scripts/setup.sh installs it) when present: paths hashed relative to the repository,
# so build/ and build-nocgal/ share objects compiled alike.
if command -v ccache >/dev/null 2>&1; then
  flags+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR=$repo_root CCACHE_NOHASHDIR=true
fi
flags+=(-DWIRERIG_WARNINGS_AS_ERRORS=ON)
stamp="${generator[*]} ${flags[*]}"
if [ -f "$dir/CMakeCache.txt" ]; then
  if [ -f "$dir/.wirerig-configure" ]; then
    [ "$(cat "$dir/.wirerig-configure")" = "$stamp" ] || stale=1
  else
    # Configured before the settings were recorded: only a sanitizer folder made without the
    # fuzzers (GCC's) is out of date; any other is adopted as it is.
    stale=0
    if [[ $kind == asan || $kind == fuzz ]] &&
       ! grep -q '^WIRERIG_BUILD_FUZZERS:BOOL=ON' "$dir/CMakeCache.txt"; then
      stale=1
    else
      printf '%s' "$stamp" >"$dir/.wirerig-configure"
    fi
  fi
  if [ "${stale:-0}" -eq 1 ]; then
    echo "build: $dir was configured with other settings; configuring it afresh"
    rm -rf "$dir"
  fi
fi
if [ ! -f "$dir/CMakeCache.txt" ]; then
  cmake -S "$repo_root" -B "$dir" "${generator[@]}" "${flags[@]}" >/dev/null
  printf '%s' "$stamp" >"$dir/.wirerig-configure"
fi
targets=()
[ $# -gt 0 ] && targets=(--target "$@")
cmake --build "$dir" --parallel "$jobs" "${targets[@]}"
