#!/usr/bin/env bash
# Installs the Debian packages the project needs that are missing, then configures and builds
# build/ (Release). Idempotent: a second run installs nothing and rebuilds only what changed.
# Usage: scripts/setup.sh [--blender] [TARGET...]: only those targets (scripts/demo.sh builds
# `gmg`), else everything. Every caller configures with the same options (warnings are errors
# unless GMG_WERROR=OFF), so what one script built another does not compile again. --blender also
# installs Debian's Blender (about 80 packages, 500 MB), which the add-on (engine/blender) and its
# test need; without it that test is skipped, and CI does not install it.
set -euo pipefail
cd "$(dirname "$0")/.."
with_blender=0
build_targets=()
for arg in "$@"; do
  case $arg in
    --blender) with_blender=1 ;;
    -*) echo "setup: unknown option '$arg' (usage: scripts/setup.sh [--blender] [TARGET...])" >&2; exit 2 ;;
    *) build_targets+=("$arg") ;;
  esac
done

packages=(
  build-essential cmake pkg-config git clang-format
  libboost-graph-dev libeigen3-dev libaubio-dev libfftw3-dev libglm-dev libcairo2-dev
  libcli11-dev nlohmann-json3-dev libzip-dev libfast-float-dev libxxhash-dev libgtest-dev libgmock-dev libbenchmark-dev ffmpeg
  libjemalloc-dev
  python3-dev pybind11-dev python3-numpy python3-pytest
)
if ((with_blender)); then packages+=(blender); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing missing packages: ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all ${#packages[@]} packages already installed"
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DGMG_WERROR="${GMG_WERROR:-ON}" >/dev/null
if ((${#build_targets[@]})); then
  targets=()
  for t in "${build_targets[@]}"; do targets+=(--target "$t"); done
  cmake --build build -j"$jobs" "${targets[@]}"
  echo "setup: built ${build_targets[*]}"
else
  cmake --build build -j"$jobs"
  echo "setup: built build/gmg, the tests and the Python module"
fi
