#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the worked wire example.
# (Until the octopus demo lands, the main job solves one wire and prints a table.)
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$repo_root/scripts/setup.sh"
"$repo_root/scripts/build.sh" release >/dev/null
"$repo_root/build/cli/wirerig" wire "$repo_root/samples/worked_wire/steel_cantilever.json" --format table
