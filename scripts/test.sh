#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test twice: optimised, then under
# AddressSanitizer + UndefinedBehaviorSanitizer; then checks the build without CGAL.
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$repo_root/scripts/setup.sh"
jobs=${WIRERIG_JOBS:-$(nproc)}

echo "== release build and tests"
"$repo_root/scripts/build.sh" release
ctest --test-dir "$repo_root/build" --output-on-failure --parallel "$jobs"

echo "== ASan + UBSan build and tests"
"$repo_root/scripts/build.sh" asan
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir "$repo_root/build-asan" --output-on-failure --parallel "$jobs"

echo "== build without CGAL (WIRERIG_WITH_CGAL=OFF)"
"$repo_root/scripts/build.sh" nocgal
"$repo_root/scripts/check_without_cgal.sh" "$repo_root/build-nocgal/cli/wirerig"
