"""Benchmark: twenty reenactments in one Python process (the graph loaded once) against twenty
`gmg reenact --graph` commands (each starts, loads the graph, reenacts and writes its BVH).

Usage: PYTHONPATH=build/python /usr/bin/python3 tests/python/bench_batch.py build/gmg [--runs 5]

Uses the shared BEAT2 recording (2_scott_0_1_1's graph; 2_scott_0_2_2 and 0_3_3 in turn, seeds 1
to 20) when ../shared/data holds it, else a synthetic speaker. Prints, for each way, the median
and the spread (min, max) of the wall seconds over the runs, and the median ratio."""
import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import gmg

ROOT = Path(__file__).resolve().parents[2]


def inputs(binary, work):
    data = ROOT.parent / "shared" / "data" / "beat2_scott"
    if (data / "2_scott_0_1_1.bvh").exists():
        subprocess.run([binary, "build", "--motion", data / "2_scott_0_1_1.bvh", "--audio", data / "2_scott_0_1_1.wav",
                        "--transcript", data / "2_scott_0_1_1.TextGrid", "-o", work / "ref.gmg"], check=True,
                       capture_output=True)
        speech = [(data / f"2_scott_0_{k}_{k}.wav", data / f"2_scott_0_{k}_{k}.TextGrid") for k in (2, 3)]
        return "BEAT2 2_scott_0_1_1", work / "ref.gmg", speech
    for stem, args in (("ref", []), ("new", ["--no-motion"]), ("other", ["--no-motion"])):
        subprocess.run([binary, "synth", "-o", work, "--stem", stem, "--duration", "60" if stem == "ref" else "30",
                        "--seed", str(len(stem)), *args], check=True, capture_output=True)
    subprocess.run([binary, "build", "--motion", work / "ref.bvh", "--audio", work / "ref.wav", "--transcript",
                    work / "ref.tsv", "-o", work / "ref.gmg"], check=True, capture_output=True)
    return "synthetic speaker", work / "ref.gmg", [(work / f"{s}.wav", work / f"{s}.tsv") for s in ("new", "other")]


def in_python(graph_file, speech, out):
    graph = gmg.load(graph_file)
    for seed in range(1, 21):
        audio, words = speech[seed % 2]
        gmg.reenact(graph, audio, words, seed=seed).write(out / f"py_{seed}.bvh")


def by_commands(binary, graph_file, speech, out):
    for seed in range(1, 21):
        audio, words = speech[seed % 2]
        subprocess.run([binary, "reenact", "--graph", graph_file, "--audio", audio, "--transcript", words,
                        "--seed", str(seed), "-o", out / f"cli_{seed}.bvh"], check=True, capture_output=True)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("gmg")
    parser.add_argument("--runs", type=int, default=5)
    a = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        name, graph_file, speech = inputs(a.gmg, work)
        py, cli, ratio = [], [], []
        for _ in range(a.runs):  # in turn, so a drift of the machine's speed hits both alike
            t = time.perf_counter()
            in_python(graph_file, speech, work)
            py.append(time.perf_counter() - t)
            t = time.perf_counter()
            by_commands(a.gmg, graph_file, speech, work)
            cli.append(time.perf_counter() - t)
            ratio.append(py[-1] / cli[-1])
        same = all((work / f"py_{s}.bvh").read_bytes() == (work / f"cli_{s}.bvh").read_bytes() for s in range(1, 21))
    print(f"20 reenactments of {name}, {a.runs} runs, wall seconds median (min-max):")
    print(f"  one Python process: {statistics.median(py):.2f} ({min(py):.2f}-{max(py):.2f})")
    print(f"  20 gmg commands:    {statistics.median(cli):.2f} ({min(cli):.2f}-{max(cli):.2f})")
    print(f"  ratio Python/commands: {statistics.median(ratio):.3f} ({min(ratio):.3f}-{max(ratio):.3f})")
    print(f"  outputs byte-identical: {same}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
