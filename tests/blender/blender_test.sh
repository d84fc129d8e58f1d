#!/usr/bin/env bash
# The Blender add-on in background Blender (tests/blender/addon_test.py): installed from its zip into
# a user folder of the test's own, as Blender's preferences install it. Skips (exit 77) with a
# message when Blender or the BEAT2 data is absent.
# Usage: blender_test.sh BUILD_DIR SOURCE_DIR GMG_BINARY
set -euo pipefail
build=$1
source=$2
gmg=$3
if ! command -v blender >/dev/null; then
  echo "SKIP: blender is not installed (scripts/setup.sh --blender installs Debian's)"
  exit 77
fi
data="$source/../shared/data/beat2_scott"
if [ ! -f "$data/2_scott_0_1_1.bvh" ]; then
  echo "SKIP: the BEAT2 clips are not in $data"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export BLENDER_USER_SCRIPTS="$work/scripts" BLENDER_USER_CONFIG="$work/config"
PYTHONPATH="$build/python" PYTHONDONTWRITEBYTECODE=1 blender -b --factory-startup --python-use-system-env \
  --python-exit-code 1 --python "$source/tests/blender/addon_test.py" -- "$build/gmg_blender.zip" "$data" "$gmg" "$work"
