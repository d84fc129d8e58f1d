#!/usr/bin/env bash
# `cmake --install` gives a gmg that needs no source tree: a copy of the install folder, moved
# away from the build, builds a graph and reenacts (the default lexicon and config are compiled
# in), and the binary holds no path into the source tree. It still links the system's shared
# libraries (the Debian packages of scripts/setup.sh); this test runs where they are installed.
# Usage: install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/inst" >/dev/null
cp -r "$work/inst" "$work/moved"
rm -rf "$work/inst"
gmg="$work/moved/bin/gmg"
test -x "$gmg"
if [ ! -f "$work/moved/share/gmg/gmg_blender.zip" ]; then  # the Blender add-on, for Preferences > Add-ons > Install
  echo "FAIL: the install has no share/gmg/gmg_blender.zip"
  exit 1
fi
if grep -aF "$source" "$gmg" >/dev/null; then
  echo "FAIL: the installed binary contains the source path $source"
  exit 1
fi
cd "$work"  # nowhere near the source tree
"$gmg" synth -o data --stem ref --duration 30 --seed 3 >/dev/null
"$gmg" synth -o data --stem new --duration 8 --seed 4 --no-motion >/dev/null
built=$("$gmg" build --motion data/ref.bvh --audio data/ref.wav --transcript data/ref.tsv -o data/ref.gmg)
echo "$built"
keyword_nodes=$("$gmg" inspect data/ref.gmg | sed -n 's/^keyword nodes: //p')
if [ "${keyword_nodes:-0}" -lt 1 ]; then
  echo "FAIL: no keyword nodes: the built-in lexicon did not reach the installed binary"
  exit 1
fi
"$gmg" reenact --graph data/ref.gmg --audio data/new.wav --transcript data/new.tsv -o data/out.bvh >/dev/null
frames=$(sed -n 's/^Frames: //p' data/out.bvh)
if [ "$frames" != "240" ]; then
  echo "FAIL: expected 240 frames, got '$frames'"
  exit 1
fi
echo "PASS: installed copy built a graph with $keyword_nodes keyword nodes and reenacted $frames frames"
