#!/usr/bin/env bash
# Installs the Debian packages wirerig needs and caches the real test meshes.
# Idempotent: prints nothing and installs nothing when everything is present.
# Usage: scripts/setup.sh            (as root, or with sudo available)
# Env:   WIRERIG_ASSET_DIR  where meshes go (default: <repo>/.cache/assets, git-ignored)
set -euo pipefail

repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
asset_dir=${WIRERIG_ASSET_DIR:-$repo_root/.cache/assets}

# Build toolchain, libraries the targets link, test and benchmark frameworks.
packages=(
  cmake ninja-build g++ pkg-config git ca-certificates
  # Compiler cache: the build without CGAL reuses what the optimised build compiled.
  ccache
  # The sanitizer build and the fuzzers: clang 14, its runtimes (ASan, UBSan and libFuzzer are in
  # libclang-rt-14-dev, only recommended by clang) and llvm-symbolizer (llvm) for the reports.
  clang libclang-rt-14-dev llvm
  libeigen3-dev libglm-dev nlohmann-json3-dev libcli11-dev libassimp-dev libminizip-dev libcgal-dev
  libtinygltf-dev libstb-dev libmeshoptimizer-dev
  libglfw3-dev libimgui-dev libegl-dev libgl-dev xvfb xauth
  libegl-mesa0 libglx-mesa0 libgl1-mesa-dri
  libgtest-dev libgmock-dev libbenchmark-dev
  nodejs
  assimp-testmodels
)

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

apt_updated=0
apt_update_once() {
  [ $apt_updated -eq 1 ] && return 0
  "${sudo_cmd[@]}" apt-get -qq -o DPkg::Lock::Timeout=600 update >/dev/null
  apt_updated=1
}

apt_install() {
  export DEBIAN_FRONTEND=noninteractive
  apt_update_once
  "${sudo_cmd[@]}" apt-get -qq install -y --no-install-recommends \
    -o DPkg::Lock::Timeout=600 "$@" >/dev/null
}

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
# Debian's npm, unless npm came with nodejs (NodeSource's nodejs bundles it and conflicts).
command -v npm >/dev/null 2>&1 || missing+=(npm)
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  apt_install "${missing[@]}"
fi

# Real meshes (docs/assets.md): Assimp's test models are used in place; the
# CGAL demo meshes are extracted from the libcgal-demo .deb without installing it.
mkdir -p "$asset_dir"
cgal_meshes=(cow.off elephant.off man.off camel.off hand.off cactus.off)
need_cgal=0
for m in "${cgal_meshes[@]}"; do [ -s "$asset_dir/$m" ] || need_cgal=1; done
if [ $need_cgal -eq 1 ]; then
  echo "setup: fetching CGAL demo meshes into $asset_dir"
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  download() {
    (cd "$work" && apt-get -qq -o APT::Sandbox::User=root download libcgal-demo >/dev/null 2>&1)
  }
  download || { apt_update_once && download; } ||
    { echo "setup: cannot download libcgal-demo from the Debian archive" >&2; exit 1; }
  dpkg -x "$work"/libcgal-demo_*.deb "$work/x"
  tar -xzf "$work/x/usr/share/doc/libcgal-dev/data.tar.gz" -C "$work"
  for m in "${cgal_meshes[@]}"; do
    src=$(find "$work/data/meshes" -name "$m" | head -n 1)
    [ -n "$src" ] || { echo "setup: $m is missing from libcgal-demo" >&2; exit 1; }
    cp "$src" "$asset_dir/$m.tmp" && mv "$asset_dir/$m.tmp" "$asset_dir/$m"
  done
fi
ln -sfn /usr/share/assimp/models "$asset_dir/assimp"

# The Khronos glTF validator and three.js (npm), pinned by scripts/gltf_validator/package-lock.json;
# the tests run them through scripts/validate_gltf.mjs and scripts/three_skinned_positions.mjs.
validator_dir=$repo_root/.cache/gltf-validator
if ! cmp -s "$repo_root/scripts/gltf_validator/package-lock.json" "$validator_dir/package-lock.json" ||
   [ ! -f "$validator_dir/node_modules/gltf-validator/package.json" ] ||
   [ ! -f "$validator_dir/node_modules/three/package.json" ]; then
  echo "setup: installing the glTF validator and three.js into $validator_dir"
  mkdir -p "$validator_dir"
  cp "$repo_root"/scripts/gltf_validator/package.json "$repo_root"/scripts/gltf_validator/package-lock.json "$validator_dir/"
  (cd "$validator_dir" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi
