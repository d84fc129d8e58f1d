#!/usr/bin/env bash
# The demo: sets up and builds, generates a procedural speaker (motion + speech + words),
# builds its motion graph, and reenacts its gestures for a second, new utterance.
# Output: demo_output/reenacted.bvh (open in Blender: File > Import > Motion Capture (.bvh)),
# demo_output/report.json (how every subsequence was matched), demo_output/reenacted.mp4 (a video
# of the result with its speech, captions and onset/junction markers).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
out=demo_output
mkdir -p "$out"
gmg=build/gmg
echo "demo: generating the reference speaker (60 s) and a new utterance (20 s)"
$gmg synth -o "$out" --stem reference --duration 60 --seed 1
$gmg synth -o "$out" --stem new_speech --duration 20 --seed 2 --no-motion
echo "demo: building the motion graph"
$gmg build --motion "$out/reference.bvh" --audio "$out/reference.wav" --transcript "$out/reference.tsv" -o "$out/reference.gmg"
$gmg inspect "$out/reference.gmg"
echo "demo: reenacting"
$gmg reenact --graph "$out/reference.gmg" --audio "$out/new_speech.wav" --transcript "$out/new_speech.tsv" \
  -o "$out/reenacted.bvh" --report "$out/report.json" --seed 7
$gmg evaluate --generated "$out/reenacted.bvh" --audio "$out/new_speech.wav" --report "$out/report.json" \
  --reference "$out/reference.gmg"
echo "demo: rendering the result with its speech"
$gmg render "$out/reenacted.bvh" --audio "$out/new_speech.wav" --transcript "$out/new_speech.tsv" \
  --report "$out/report.json" -o "$out/reenacted.mp4"
echo
echo "demo: done. Reenacted motion: $out/reenacted.bvh (Blender: File > Import > Motion Capture (.bvh))"
echo "      Video with its speech: $out/reenacted.mp4"
echo "      Report: $out/report.json"
