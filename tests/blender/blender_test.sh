#!/usr/bin/env bash
# The Blender add-on, installed from its zip into a user folder of the test's own, as Blender's
# preferences install it: in background Blender (tests/blender/addon_test.py), or with `panel`,
# from the interface on a virtual X display (tests/blender/panel_test.py; needs xvfb-run).
# Skips (exit 77) with a message when Blender, xvfb-run or the BEAT2 data is absent.
# Usage: blender_test.sh BUILD_DIR SOURCE_DIR GMG_BINARY [panel]
set -euo pipefail
build=$1
source=$2
gmg=$3
mode=${4:-headless}
if ! command -v blender >/dev/null; then
  echo "SKIP: blender is not installed (scripts/setup.sh --blender installs Debian's)"
  exit 77
fi
data="$source/../shared/data/beat2_scott"
if [ ! -f "$data/2_scott_0_1_1.bvh" ]; then
  echo "SKIP: the BEAT2 clips are not in $data"
  exit 77
fi
if [ "$mode" = panel ] && ! command -v xvfb-run >/dev/null; then
  echo "SKIP: xvfb-run is not installed (Debian's xvfb): the interface needs a display"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export BLENDER_USER_SCRIPTS="$work/scripts" BLENDER_USER_CONFIG="$work/config"
export PYTHONPATH="$build/python" PYTHONDONTWRITEBYTECODE=1
if [ "$mode" = panel ]; then
  timeout 300 xvfb-run -a -s "-screen 0 1280x800x24" blender --factory-startup --enable-event-simulate \
    --python-use-system-env --python "$source/tests/blender/panel_test.py" -- "$build/gmg_blender.zip" "$data" "$work"
  exit
fi
blender -b --factory-startup --python-use-system-env \
  --python-exit-code 1 --python "$source/tests/blender/addon_test.py" -- "$build/gmg_blender.zip" "$data" "$gmg" "$work"
