#!/usr/bin/env bash
# Runs one libFuzzer target (fuzz/, docs/fuzzing.md) for a while on a copy of its seed corpus.
# Usage: scripts/fuzz.sh TARGET SECONDS [libFuzzer options...]
#   TARGET   wire_problem, rig_description, rig_file, scene, clip, bvh, rig_asset, clip_asset,
#            mesh_import (the _fuzzer suffix may be given too); "list" lists them
#   SECONDS  how long to fuzz (-max_total_time)
# Builds the target in build-fuzz/ (clang, configured by scripts/build.sh fuzz when missing), or
# in WIRERIG_FUZZ_BUILD_DIR when set (CI points it at build-asan/, which holds the fuzzers too).
# The run works in <build dir>/fuzz-runs/TARGET/: corpus/ starts as a copy of
# fuzz/corpus/TARGET/ (the checked-in corpus is never written) and gathers what the run finds.
# Exit status: 0 when nothing crashed; 1 when the fuzzer found a crash, leak, timeout or
# out-of-memory input, left in the run folder as crash-*, leak-*, timeout-* or oom-* (the
# message says how to replay it); 2 for a usage error.
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
targets=(wire_problem rig_description rig_file scene clip bvh rig_asset clip_asset mesh_import)

usage() {
  echo "usage: $0 TARGET SECONDS [libFuzzer options...]; TARGET one of: ${targets[*]}" >&2
  exit 2
}
[ $# -ge 1 ] || usage
if [ "$1" = list ]; then printf '%s\n' "${targets[@]}"; exit 0; fi
[ $# -ge 2 ] || usage
target=${1%_fuzzer}
seconds=$2
shift 2
[[ " ${targets[*]} " == *" $target "* ]] || { echo "$0: unknown target '$target'" >&2; usage; }
[[ $seconds =~ ^[0-9]+$ ]] && [ "$seconds" -ge 1 ] ||
  { echo "$0: SECONDS must be a whole number >= 1 (got '$seconds')" >&2; usage; }

if [ -n "${WIRERIG_FUZZ_BUILD_DIR:-}" ]; then
  build_dir=$(cd "$WIRERIG_FUZZ_BUILD_DIR" && pwd)
  cmake --build "$build_dir" --parallel "${WIRERIG_JOBS:-$(nproc)}" --target "${target}_fuzzer"
else
  build_dir=$repo_root/build-fuzz
  "$repo_root/scripts/build.sh" fuzz "${target}_fuzzer"
fi
fuzzer=$build_dir/fuzz/${target}_fuzzer
[ -x "$fuzzer" ] || { echo "$0: $fuzzer was not built" >&2; exit 1; }

run_dir=$build_dir/fuzz-runs/$target
rm -rf "$run_dir"
mkdir -p "$run_dir/corpus"
cp -R "$repo_root/fuzz/corpus/$target/." "$run_dir/corpus/"
options=(-max_total_time="$seconds" -timeout=25 -rss_limit_mb=4096 -print_final_stats=1
         -artifact_prefix="$run_dir/")
case $target in
  wire_problem|rig_description|rig_file|scene|clip) options+=(-dict="$repo_root/fuzz/json.dict") ;;
esac
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

echo "fuzz: $target for $seconds s on a copy of fuzz/corpus/$target ($run_dir)"
status=0
(cd "$run_dir" && "$fuzzer" "${options[@]}" "$@" corpus) >"$run_dir/fuzz.log" 2>&1 || status=$?
tail -n 15 "$run_dir/fuzz.log"

# A crash inside the mesh importer's child process leaves its file while the fuzzer goes on.
shopt -s nullglob
found=("$run_dir"/crash-* "$run_dir"/leak-* "$run_dir"/timeout-* "$run_dir"/oom-*)
if [ $status -ne 0 ] || [ ${#found[@]} -gt 0 ]; then
  echo "fuzz: $target FAILED (exit status $status); full log: $run_dir/fuzz.log" >&2
  # What the sanitizers said, and small inputs in base64: a CI log is all a fresh clone keeps.
  grep -E "ERROR: |SUMMARY: |runtime error: |FATAL: |deadly signal" "$run_dir/fuzz.log" |
    head -n 20 >&2 || true
  for f in "${found[@]}"; do
    echo "fuzz: input left in $f; replay: $fuzzer $f" >&2
    if [ "$(stat -c %s "$f")" -le 65536 ]; then
      echo "fuzz: the input in base64 (base64 -d > input):" >&2
      base64 -w 120 "$f" >&2
    fi
  done
  exit 1
fi
echo "fuzz: $target: no crash in $seconds s ($(ls "$run_dir/corpus" | wc -l) inputs in the run's corpus)"
