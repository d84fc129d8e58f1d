"""Fixtures of the Python module's tests: the module under test (PYTHONPATH, set by ctest to the
build's python/ folder), the gmg binary (GMG_BINARY) for the comparisons with the command line,
synthetic clips made by `gmg synth`, and the shared recordings (GMG_SHARED_DATA_DIR), whose tests
skip with a message when they are absent."""
import json
import os
import subprocess
import wave
from pathlib import Path

import numpy as np
import pytest


def gmg_binary():
    path = os.environ.get("GMG_BINARY", "")
    if not path or not os.access(path, os.X_OK):
        pytest.fail("GMG_BINARY must name the gmg binary (ctest sets it)")
    return path


def run_gmg(*args, check=True):
    """`gmg args...`: (exit code, stdout, stderr)."""
    r = subprocess.run([gmg_binary(), *map(str, args)], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError(f"gmg {' '.join(map(str, args))} failed ({r.returncode}): {r.stderr}")
    return r.returncode, r.stdout, r.stderr


def read_wav(path):
    """A 16-bit PCM mono WAV as float32 samples scaled as gmg scales them (1/32768), and its rate."""
    with wave.open(str(path)) as w:
        assert w.getsampwidth() == 2 and w.getnchannels() == 1
        data = np.frombuffer(w.readframes(w.getnframes()), dtype="<i2")
        return data.astype(np.float32) / np.float32(32768.0), w.getframerate()


def read_tsv(path):
    """A TSV transcript (start, end, word) as (start, end, text) tuples."""
    words = []
    for line in Path(path).read_text().splitlines():
        start, end, text = line.split("\t", 2)
        words.append((float(start), float(end), text))
    return words


@pytest.fixture(scope="session")
def synth(tmp_path_factory):
    """A synthetic speaker: ref (40 s, with motion) and new (12 s of speech), and ref's graph."""
    d = tmp_path_factory.mktemp("synth")
    run_gmg("synth", "-o", d, "--stem", "ref", "--duration", "40", "--seed", "11")
    run_gmg("synth", "-o", d, "--stem", "new", "--duration", "12", "--seed", "12", "--no-motion")
    run_gmg("build", "--motion", d / "ref.bvh", "--audio", d / "ref.wav", "--transcript", d / "ref.tsv",
            "-o", d / "ref.gmg")
    return d


@pytest.fixture(scope="session")
def beat2():
    root = os.environ.get("GMG_SHARED_DATA_DIR", "")
    d = Path(root) / "beat2_scott"
    if not root or not (d / "2_scott_0_1_1.npz").exists():
        pytest.skip("../shared/data is absent: skipping the real-data test")
    return d


def cli_json(*args):
    return json.loads(run_gmg(*args)[1])
