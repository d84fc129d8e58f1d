#!/usr/bin/env bash
# `cmake --install build --prefix ~/.local` gives a Python module that the interpreter finds in
# the user's own site-packages, without PYTHONPATH and without the source or build tree: a copy
# of the install folder, moved away, used as the user base (PYTHONUSERBASE), imports gmg from
# there and builds a graph and reenacts with it.
# Usage: python_install_test.sh BUILD_DIR PYTHON SITE_DIR (SITE_DIR relative to the prefix)
set -euo pipefail
build=$1
python=$2
site=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/inst" >/dev/null
cp -r "$work/inst" "$work/moved"
rm -rf "$work/inst"
cd "$work"
"$work/moved/bin/gmg" synth -o data --stem ref --duration 20 --seed 3 >/dev/null
"$work/moved/bin/gmg" synth -o data --stem new --duration 6 --seed 4 --no-motion >/dev/null
where=$(env -u PYTHONPATH PYTHONUSERBASE="$work/moved" "$python" -c '
import gmg, sys
g = gmg.build("data/ref.bvh", "data/ref.wav", "data/ref.tsv")
r = gmg.reenact(g, "data/new.wav", "data/new.tsv", seed=1)
assert r.rotations.shape == (180, 22, 4), r.rotations.shape
print(gmg.__file__)')
case "$where" in
  "$work/moved/$site/"*) ;;
  *) echo "FAIL: gmg was imported from '$where', not from the installed $work/moved/$site"; exit 1 ;;
esac
echo "PASS: the installed module imports from the user's site-packages ($site) and reenacts"
