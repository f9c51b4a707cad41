#!/usr/bin/env bash
# Rigs every test asset of docs ASSETS.md and every character, animal and figure among the
# Assimp test models and the CGAL demo meshes automatically (no description), one at a time,
# and prints one line per mesh:
#   asset | exit code | the "rig: N parts from ..." line | "quality:" | "verdict:" | wall time
# or, for a mesh that is refused, its error message in place of the rig, quality and verdict.
# Results are in docs/rig-formats.md ("Automatic rigs of the test assets").
#
# Usage:  scripts/survey_rigs.sh [ASSET ...]   (from anywhere; ASSET relative to the asset dir,
#                                               e.g. assimp/X/Testwuson.X or cow.off)
# Needs:  build/cli/wirerig (scripts/build.sh) and the assets (scripts/setup.sh).
# Env:    WIRERIG            the binary       (default: <repo>/build/cli/wirerig)
#         WIRERIG_ASSET_DIR  the assets       (default: <repo>/.cache/assets, as scripts/setup.sh)
#         SURVEY_OUT         rigs, logs, TSV  (default: /tmp/survey)
#         SURVEY_TIMEOUT     seconds per mesh (default: 120)
#         SURVEY_JOINTS      1: also the joint test of issue 13 (`--joint-report --joint-poses`):
#                            each rig's 60-degree poses (every joint bent alone, x and y, each
#                            way) that fold an edge or stretch one beyond 2x, and their folds
set -uo pipefail

repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo_root" || exit 1
bin=${WIRERIG:-build/cli/wirerig}
assets=${WIRERIG_ASSET_DIR:-.cache/assets}
out=${SURVEY_OUT:-/tmp/survey}
limit=${SURVEY_TIMEOUT:-120}
joints=${SURVEY_JOINTS:-0}
joint_args=()
[ "$joints" = 1 ] && joint_args=(--joint-report --joint-poses)

# group|path under $assets
default_list=(
  # --- ASSETS.md: the paper's examples and the skinned models ---
  "assets|assimp/Collada/human.zae"
  "assets|man.off"
  "assets|assimp/BLEND/HUMAN.blend"
  "assets|cow.off"
  "assets|elephant.off"
  "assets|assimp/glTF/CesiumMilkTruck/CesiumMilkTruck.gltf"
  "assets|assimp/X/Testwuson.X"
  "assets|assimp/X/anim_test.x"
  "assets|camel.off"
  "assets|hand.off"
  "assets|cactus.off"
  "assets|assimp/BVH/01_01.bvh"
  "assets|assimp/SMD/WusonSMD.smd"
  "assets|assimp/MS3D/Wuson.ms3d"
  "assets|assimp/B3D/WusonBlitz.b3d"
  "assets|assimp/MD5/SimpleCube.md5mesh"
  "assets|assimp/glTF2/simple_skin/simple_skin.gltf"
  "assets|assimp/FBX/animation_with_skeleton.fbx"
  "assets|assimp/FBX/huesitos.fbx"
  # --- Assimp test models: Wuson (the cartoon pig) in every other format ---
  "wuson|assimp/AC/Wuson.ac"
  "wuson|assimp/AC/Wuson.acc"
  "wuson|assimp/DXF/wuson.dxf"
  "wuson|assimp/M3D/WusonBlitz0.m3d"
  "wuson|assimp/M3D/WusonBlitz1.m3d"
  "wuson|assimp/M3D/WusonBlitz2.m3d"
  "wuson|assimp/OBJ/WusonOBJ.obj"
  "wuson|assimp/OFF/Wuson.off"
  "wuson|assimp/PLY/Wuson.ply"
  "wuson|assimp/Q3D/WusonOrange.q3o"
  "wuson|assimp/Q3D/WusonOrange.q3s"
  "wuson|assimp/RAW/Wuson.raw"
  "wuson|assimp/STL/Wuson.stl"
  "wuson|assimp/WRL/Wuson.wrl"
  "wuson|assimp/XGL/Wuson.zgl"
  "wuson|assimp/XGL/wuson_dxf.zgl"
  # --- Assimp test models: the spider ---
  "spider|assimp/OBJ/spider.obj"
  "spider|assimp/COB/spider_4_3.cob"
  "spider|assimp/COB/spider_4_3_ascii.cob"
  "spider|assimp/COB/spider_6_6.cob"
  "spider|assimp/COB/spider_6_6_ascii.cob"
  "spider|assimp/FBX/spider.fbx"
  "spider|assimp/IRRMesh/spider.irrmesh"
  "spider|assimp/MDC/spider.mdc"
  "spider|assimp/STL/Spider_ascii.stl"
  "spider|assimp/STL/Spider_binary.stl"
  "spider|assimp/XGL/Spider_ascii.zgl"
  # --- Assimp test models: other characters, animals and figures ---
  "figure|assimp/MD2/sydney.md2"
  "figure|assimp/MD2/faerie.md2"
  "figure|assimp/IQM/mrfixit.iqm"
  "figure|assimp/X/BCN_Epileptic.X"
  "figure|assimp/XGL/BCN_Epileptic.zgl"
  "figure|assimp/MDL/MDL (HL1)/man.mdl"
  "figure|assimp/COB/dwarf.cob"
  "figure|assimp/COB/dwarf_ascii.cob"
  "figure|assimp/ASE/MotionCaptureROM.ase"
  "figure|assimp/WRL/MotionCaptureROM.WRL"
  "figure|assimp/CSM/ThomasFechten.csm"
  "figure|assimp/Collada/duck.dae"
  "figure|assimp/Collada/duck.zae"
  "figure|assimp/Collada/duck_nomanifest.zae"
  "figure|assimp/Collada/duck_triangulate.dae"
  "figure|assimp/SIB/heffalump.sib"
  "figure|assimp/X/fromtruespace_bin32.x"
  "figure|assimp/Q3D/E-AT-AT.q3o"
  "figure|assimp/Ogre/TheThing/Mesh.mesh.xml"
  "figure|assimp/BLEND/Suzanne_248.blend"
  "figure|assimp/BLEND/SuzanneSubdiv_252.blend"
  "figure|assimp/M3D/suzanne.m3d"
  # --- cannot be rigged: a single triangle, a flat sheet, points ---
  "flat|assimp/STL/triangle.stl"
  "flat|assimp/SMD/triangle.smd"
  "flat|assimp/BLEND/TexturedPlane_ImageUv_248.blend"
  "flat|assimp/OBJ/point_cloud.obj"
  # --- ASSETS.md: bad input, must fail cleanly ---
  "bad|assimp/invalid/malformed.obj"
  "bad|assimp/invalid/malformed2.obj"
  "bad|assimp/invalid/OutOfMemory.off"
  "bad|assimp/OFF/invalid.off"
  "bad|assimp/STL/sphereWithHole.stl"
  "bad|assimp/invalid/empty.3ds"
  "bad|assimp/invalid/empty.ase"
  "bad|assimp/invalid/empty.lwo"
  "bad|assimp/invalid/empty.md5mesh"
  "bad|assimp/invalid/empty.obj"
  "bad|assimp/invalid/empty.off"
  "bad|assimp/invalid/empty.ply"
  "bad|assimp/invalid/empty.raw"
  "bad|assimp/invalid/empty.smd"
  "bad|assimp/invalid/empty.x"
  "bad|assimp/invalid/emptyIrrMesh.xml"
)

if [ $# -gt 0 ]; then
  list=()
  for a in "$@"; do list+=("arg|$a"); done
else
  list=("${default_list[@]}")
fi

# The binary may be relinked while the survey runs: wait for it rather than fail the mesh.
wait_for_binary() {
  local i
  for i in $(seq 1 60); do
    [ -x "$bin" ] && return 0
    sleep 1
  done
  echo "survey: $bin is missing: build it first (scripts/build.sh)" >&2
  exit 2
}
wait_for_binary
if [ ! -d "$assets/assimp" ] || [ ! -s "$assets/cow.off" ]; then
  echo "survey: the test assets are missing from $assets: run scripts/setup.sh first" >&2
  exit 2
fi
mkdir -p "$out"

now() { date +%s.%N; }
bin_stamp() { stat -c '%s bytes, modified %y' "$bin" 2>/dev/null; }
stamp0=$(bin_stamp)
tsv=$out/survey.tsv
printf 'group\tasset\texit\trig\tquality\tverdict\tseconds\terror\tjoint60\n' >"$tsv"
n_ok=0; n_fail=0; n_good=0; n_usable=0; n_poor=0; n_other=0; n_pass60=0; n_jointed=0
echo "survey: $bin rig MESH -o $out/NAME.rig.json (timeout ${limit}s each), assets in $assets"
echo "survey: binary $stamp0"
for entry in "${list[@]}"; do
  group=${entry%%|*}
  rel=${entry#*|}
  mesh=$assets/$rel
  name=$(printf '%s' "$rel" | sed -e 's|^assimp/||' -e 's|[/ ()]|_|g')
  log=$out/$name.log
  rig=$out/$name.rig.json
  rm -f "$rig"
  if [ ! -e "$mesh" ]; then
    printf '%s | missing | the file is not in %s\n' "$rel" "$assets"
    printf '%s\t%s\tmissing\t\t\t\t\tthe file is not there\n' "$group" "$rel" >>"$tsv"
    n_fail=$((n_fail + 1))
    continue
  fi
  for attempt in 1 2; do
    wait_for_binary
    t0=$(now)
    timeout "$limit" "$bin" rig "$mesh" -o "$rig" "${joint_args[@]}" >"$log" 2>&1
    rc=$?
    t1=$(now)
    # 126/127: the binary vanished between the check and the exec (relink); run once more.
    if [ $rc -ne 126 ] && [ $rc -ne 127 ]; then break; fi
    sleep 5
  done
  secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }')
  rigline=$(grep -m1 '^rig: ' "$log" || true)
  quality=$(grep -m1 '^quality: ' "$log" || true)
  verdict=$(grep -m1 '^verdict: ' "$log" || true)
  error=""
  if [ $rc -eq 124 ]; then
    error="timed out after ${limit} s"
  elif [ $rc -gt 128 ]; then
    error="killed by signal $((rc - 128)): $(tail -n 1 "$log")"
  elif [ $rc -ne 0 ]; then
    error=$(grep -m1 '^wirerig' "$log" || tail -n 1 "$log")
    error=${error#"wirerig rig: $mesh: "}
  fi
  joint60=""
  if [ "$joints" = 1 ] && [ $rc -eq 0 ]; then
    # "poses where the wire rig misses a target": joint, pose, folds, stretch, volume, perimeter.
    # Rows of the joint table between its header and "all joints": the joints swept.
    swept=$(sed -n '/^joint skin/,/^  all joints/p' "$log" | grep -vc -e '^joint skin' \
      -e '^  joint  ' -e '^  all joints')
    if [ "$swept" -eq 0 ]; then
      joint60="no joints to test"
    else
      joint60=$(sed -n '/^poses where/,$p' "$log" |
        awk '$2 ~ /^[xy][+-]60$/ && ($3 > 0 || $4 > 2.0) { c++; f += $3 }
             END { printf "%d poses fail at 60 degrees (%d folded edges)", c, f }')
    fi
    case "$joint60" in
      "0 poses"*) n_pass60=$((n_pass60 + 1)); n_jointed=$((n_jointed + 1)) ;;
      *poses*) n_jointed=$((n_jointed + 1)) ;;
    esac
  fi
  if [ $rc -eq 0 ]; then
    n_ok=$((n_ok + 1))
    case "$verdict" in
      "verdict: good"*) n_good=$((n_good + 1)) ;;
      "verdict: usable"*) n_usable=$((n_usable + 1)) ;;
      "verdict: poor"*) n_poor=$((n_poor + 1)) ;;
      *) n_other=$((n_other + 1)) ;;
    esac
    printf '%s | exit 0 | %s | %s | %s | %s s%s\n' "$rel" "$rigline" "$quality" "$verdict" "$secs" \
      "${joint60:+ | $joint60}"
  else
    n_fail=$((n_fail + 1))
    printf '%s | exit %d | %s s | error: %s\n' "$rel" "$rc" "$secs" "$error"
  fi
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$group" "$rel" "$rc" "$rigline" "$quality" \
    "$verdict" "$secs" "$error" "$joint60" >>"$tsv"
done
echo "survey: ${#list[@]} meshes: $n_ok rigged ($n_good good, $n_usable usable, $n_poor poor," \
  "$n_other other), $n_fail refused; logs, rigs and $tsv in $out"
if [ "$joints" = 1 ]; then
  echo "survey: $n_pass60 of the $n_jointed rigs with joints pass the 60-degree joint test (no" \
    "folded edge, no edge stretched beyond 2x); $((n_ok - n_jointed)) rigs have no joint"
fi
# Another build may relink the binary mid-run: then the lines above mix two builds.
if [ "$(bin_stamp)" != "$stamp0" ]; then
  echo "survey: warning: $bin changed during the survey (now $(bin_stamp)); run it again" >&2
fi
