#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test twice: optimised, then under
# AddressSanitizer + UndefinedBehaviorSanitizer (clang); runs each libFuzzer target of that same
# build for a short time on its seed corpus; then checks the build without CGAL.
# Env: WIRERIG_JOBS (parallel jobs), WIRERIG_FUZZ_SECONDS (per fuzz target, default 10; 0 skips).
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$repo_root/scripts/setup.sh"
jobs=${WIRERIG_JOBS:-$(nproc)}

echo "== release build and tests"
"$repo_root/scripts/build.sh" release
ctest --test-dir "$repo_root/build" --output-on-failure --parallel "$jobs"

echo "== ASan + UBSan build (clang, with the fuzzers) and tests"
"$repo_root/scripts/build.sh" asan
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Whole-character end-to-end tests (label end_to_end, tests/CMakeLists.txt) ran in the
# optimised pass above; here every other test runs.
ctest --test-dir "$repo_root/build-asan" --output-on-failure --parallel "$jobs" \
  --label-exclude end_to_end

fuzz_seconds=${WIRERIG_FUZZ_SECONDS:-10}
fuzz_failed=()
if [ "$fuzz_seconds" -gt 0 ]; then
  echo "== fuzzers, $fuzz_seconds s each on their seed corpora (docs/fuzzing.md)"
  for target in $("$repo_root/scripts/fuzz.sh" list); do
    WIRERIG_FUZZ_BUILD_DIR=$repo_root/build-asan "$repo_root/scripts/fuzz.sh" "$target" \
      "$fuzz_seconds" || fuzz_failed+=("$target")
  done
fi

echo "== build without CGAL (WIRERIG_WITH_CGAL=OFF)"
"$repo_root/scripts/build.sh" nocgal wirerig
"$repo_root/scripts/check_without_cgal.sh" "$repo_root/build-nocgal/cli/wirerig"

if [ ${#fuzz_failed[@]} -gt 0 ]; then
  echo "fuzzers that found a crash: ${fuzz_failed[*]} (inputs in build-asan/fuzz-runs/)" >&2
  exit 1
fi
