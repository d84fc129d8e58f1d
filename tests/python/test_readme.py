"""The README's Python example runs as printed, on the shared BEAT2 recording under the example's
file names (links in a temporary folder)."""
import os
import re
import subprocess
import sys
from pathlib import Path

README = Path(__file__).resolve().parents[2] / "README.md"


def python_example():
    text = README.read_text()
    section = text[text.index("## From Python"):]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_the_example_is_at_most_ten_lines_of_code():
    lines = [line for line in python_example().splitlines() if line.strip()]
    assert len(lines) <= 10, lines


def test_the_readme_example_runs(beat2, tmp_path):
    names = {"ref.npz": "2_scott_0_1_1.npz", "ref.bvh": "2_scott_0_1_1.bvh", "ref.wav": "2_scott_0_1_1.wav",
             "ref.TextGrid": "2_scott_0_1_1.TextGrid", "new.wav": "2_scott_0_2_2.wav",
             "new.TextGrid": "2_scott_0_2_2.TextGrid"}
    for link, target in names.items():
        os.symlink(beat2 / target, tmp_path / link)
    r = subprocess.run([sys.executable, "-c", python_example()], cwd=tmp_path, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "(1860, 55, 4) (1860, 55, 3) (1860, 3)" in r.stdout, r.stdout
    assert (tmp_path / "out.npz").stat().st_size > 0
