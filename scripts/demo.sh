#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the octopus demo with no display:
# bakes the procedural octopus's 10 s swim to out/octopus.glb and draws out/octopus.png.
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$repo_root/scripts/setup.sh"
"$repo_root/scripts/build.sh" release >/dev/null
"$repo_root/build/cli/wirerig" demo --output "$repo_root/out"
