#!/usr/bin/env bash
# The demo: sets up and builds the gmg command (only it: scripts/test.sh builds the rest with the
# same options, so nothing is compiled twice), generates a procedural speaker (motion + speech +
# transcript), builds its motion graph, and reenacts its gestures for a second, new utterance.
# Output in demo_output/:
#   reference.mp4   the first 20 s of the speaker gmg learnt from, with its own speech
#   reenacted.mp4   the result: that speaker's gestures for the new speech, with it; captions,
#                   and markers on the speech's onsets and the junctions of the graph's path
#   reenacted.bvh   the result's motion (Blender: File > Import > Motion Capture (.bvh))
#   report.json     how every subsequence was matched
#   evaluation.json the result's metrics; evaluation.png the same over time (joint speed, onset
#                   strength, onsets, junctions)
# Two videos rather than one side by side: each plays its own speech, so what a figure does can
# be checked against what is heard (beside the result, the reference would gesture to words that
# are not playing).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh gmg
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
  --reference "$out/reference.gmg" -o "$out/evaluation.json" --plot "$out/evaluation.png" >/dev/null
echo "demo: rendering the reference and the result, each with its speech"
$gmg render "$out/reference.bvh" --audio "$out/reference.wav" --transcript "$out/reference.tsv" --to 20 \
  -o "$out/reference.mp4"
$gmg render "$out/reenacted.bvh" --audio "$out/new_speech.wav" --transcript "$out/new_speech.tsv" \
  --report "$out/report.json" -o "$out/reenacted.mp4"
echo
echo "demo: done. The speaker gmg learnt from: $out/reference.mp4"
echo "      Its gestures reenacted for new speech: $out/reenacted.mp4"
echo "      Motion: $out/reenacted.bvh (Blender: File > Import > Motion Capture (.bvh))"
echo "      How it was matched: $out/report.json; metrics: $out/evaluation.json, over time: $out/evaluation.png"
