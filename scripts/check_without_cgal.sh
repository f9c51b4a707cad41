#!/usr/bin/env bash
# Checks a wirerig built without CGAL (scripts/build.sh nocgal): rigs from a description and from
# an asset's skeleton still work; a mesh that needs the curve skeleton is refused with the reason
# and nothing is written. Usage: scripts/check_without_cgal.sh PATH/TO/wirerig
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
wirerig=$1
assets=${WIRERIG_ASSET_DIR:-$repo_root/.cache/assets}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

"$wirerig" rig "$assets/assimp/Collada/human.zae" -d "$repo_root/samples/rigs/human.description.json" \
  -o "$out/human.rig.json" >/dev/null
"$wirerig" rig "$assets/assimp/X/anim_test.x" -o "$out/anim_test.rig.json" >/dev/null
if "$wirerig" rig "$assets/cow.off" -o "$out/cow.rig.json" >/dev/null 2>"$out/err.txt"; then
  echo "without CGAL: cow.off rigged, but it needs the curve skeleton" >&2; exit 1
fi
grep -q "this wirerig was built without CGAL (WIRERIG_WITH_CGAL=OFF)" "$out/err.txt" || {
  echo "without CGAL: unexpected error:" >&2; cat "$out/err.txt" >&2; exit 1; }
[ ! -e "$out/cow.rig.json" ] || { echo "without CGAL: a refused rig left a file" >&2; exit 1; }
for f in human anim_test; do
  [ -s "$out/$f.rig.json" ] || { echo "without CGAL: $f.rig.json missing" >&2; exit 1; }
done
echo "without CGAL: descriptions and skeletons rig; the curve skeleton is refused with its reason"
