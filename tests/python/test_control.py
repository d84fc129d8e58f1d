"""gmg.reenact's keep=, ranges= and pins= (`gmg reenact --keep --range --pin`): kept frames exactly
the earlier output's, pins honoured, the same as the command line, and the targets on BEAT2."""
import json

import numpy as np
import pytest

import gmg
from conftest import run_gmg


def frame_lines(path):
    lines = open(path).read().split("\n")
    return lines[lines.index("MOTION") + 3:]


def heading_relative(motion, first, count):
    """Joint positions relative to the root, turned into the root's heading (Y-up): (count, joints, 3)."""
    p = motion.positions[first:first + count]
    q = motion.rotations[first:first + count, 0]
    w, x, y, z = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    yaw = -np.arctan2(2 * (w * y + x * z), 1 - 2 * (x * x + y * y))
    r = p - p[:, :1]
    c, s = np.cos(yaw)[:, None], np.sin(yaw)[:, None]
    out = r.copy()
    out[..., 0] = c * r[..., 0] + s * r[..., 2]
    out[..., 2] = -s * r[..., 0] + c * r[..., 2]
    return out


def test_kept_frames_are_the_earlier_outputs_and_match_the_command_line(synth, tmp_path):
    g = gmg.load(synth / "ref.gmg")
    prev = gmg.reenact(g, synth / "new.wav", seed=1)
    r = gmg.reenact(g, synth / "new.wav", keep=prev, ranges=[(3.0, 6.0)], seed=2)
    inside = np.zeros(prev.frame_count, bool)
    inside[90:180] = True
    assert np.array_equal(r.rotations[~inside], prev.rotations[~inside])
    assert np.array_equal(r.translations[~inside], prev.translations[~inside])
    assert not np.allclose(r.rotations[inside], prev.rotations[inside], atol=1e-3)
    assert r.report["control"]["planned"] == [[90, 180]]
    # From files, byte for byte the command line's.
    prev.write(tmp_path / "a.bvh")
    run_gmg("reenact", "--graph", synth / "ref.gmg", "--audio", synth / "new.wav", "--keep", tmp_path / "a.bvh",
            "--range", "3:6", "--seed", "2", "-o", tmp_path / "cli.bvh")
    gmg.reenact(g, synth / "new.wav", keep=tmp_path / "a.bvh", ranges=[(3.0, 6.0)], seed=2).write(tmp_path / "py.bvh")
    assert (tmp_path / "py.bvh").read_bytes() == (tmp_path / "cli.bvh").read_bytes()
    assert frame_lines(tmp_path / "a.bvh")[:90] == frame_lines(tmp_path / "py.bvh")[:90]


def test_a_pin_plays_the_reference_and_bad_pins_are_refused(synth):
    g = gmg.load(synth / "ref.gmg")
    r = gmg.reenact(g, synth / "new.wav", pins=[(4.0, 10.0, 11.5)], seed=3)
    assert r.report["control"]["pinned"] == [{"start_frame": 120, "frames": 45, "graph_frame": 300}]
    gap = heading_relative(r.motion, 126, 33) - heading_relative(g.motion, 306, 33)
    assert np.linalg.norm(gap, axis=2).max() < 1.0  # centimetres
    with pytest.raises(gmg.Error, match="overlap"):
        gmg.reenact(g, synth / "new.wav", pins=[(4.0, 10.0, 11.5), (5.0, 20.0, 21.0)])
    with pytest.raises(gmg.Error, match="ends after the audio"):
        gmg.reenact(g, synth / "new.wav", pins=[(11.5, 10.0, 11.5)])
    with pytest.raises(gmg.Error, match="keep= and ranges= go together"):
        gmg.reenact(g, synth / "new.wav", ranges=[(1.0, 2.0)])


# The targets on BEAT2: 2_scott_0_2_2 from 2_scott_0_1_1's graph.
def test_beat2_range_and_pin_targets(beat2, tmp_path):
    run_gmg("build", "--motion", beat2 / "2_scott_0_1_1.bvh", "--audio", beat2 / "2_scott_0_1_1.wav",
            "--transcript", beat2 / "2_scott_0_1_1.TextGrid", "-o", tmp_path / "g.gmg")
    new = ["--graph", tmp_path / "g.gmg", "--audio", beat2 / "2_scott_0_2_2.wav",
           "--transcript", beat2 / "2_scott_0_2_2.TextGrid"]
    run_gmg("reenact", *new, "--seed", "1", "-o", tmp_path / "A.bvh")
    run_gmg("reenact", *new, "--keep", tmp_path / "A.bvh", "--range", "20:30", "--seed", "2", "-o", tmp_path / "B.bvh",
            "--report", tmp_path / "B.json")
    a, b = frame_lines(tmp_path / "A.bvh"), frame_lines(tmp_path / "B.bvh")
    assert len(a) == len(b)
    assert a[:600] == b[:600] and a[900:] == b[900:]
    ref = gmg.load(tmp_path / "g.gmg").motion
    pa, pb = gmg.read_motion(tmp_path / "A.bvh").positions, gmg.read_motion(tmp_path / "B.bvh").positions
    variation = np.linalg.norm(np.diff(ref.positions, axis=0), axis=2).mean()
    assert np.linalg.norm(pb[600:900] - pa[600:900], axis=2).mean() >= 0.3 * variation
    steps = np.linalg.norm(np.diff(pb, axis=0), axis=2).max(axis=1)
    p999 = np.percentile(np.linalg.norm(np.diff(ref.positions, axis=0), axis=2).max(axis=1), 99.9)
    assert steps.max() <= 1.5 * p999
    assert steps[596:604].max() <= 1.5 * p999 and steps[896:904].max() <= 1.5 * p999
    assert json.loads((tmp_path / "B.json").read_text())["control"]["kept"] == [[0, 600], [900, len(a) - 1]]

    # An .npz earlier output of a graph with a face: the same values outside the range, the face included.
    run_gmg("build", "--motion", beat2 / "2_scott_0_1_1.npz", "--skeleton", beat2 / "2_scott_0_1_1.bvh",
            "--audio", beat2 / "2_scott_0_1_1.wav", "--transcript", beat2 / "2_scott_0_1_1.TextGrid",
            "-o", tmp_path / "face.gmg")
    face = ["--graph", tmp_path / "face.gmg"] + new[2:]
    # The face along the body's path is kept, and regenerated in the range, with the body.
    body_face = face + ["--set", "face_mode=body"]
    run_gmg("reenact", *body_face, "--seed", "1", "-o", tmp_path / "A.npz")
    run_gmg("reenact", *body_face, "--keep", tmp_path / "A.npz", "--range", "20:30", "--seed", "2",
            "-o", tmp_path / "B.npz")
    with np.load(tmp_path / "A.npz") as na, np.load(tmp_path / "B.npz") as nb:
        for key in ("poses", "trans", "expressions"):
            assert np.array_equal(na[key][:600], nb[key][:600]) and np.array_equal(na[key][900:], nb[key][900:]), key
        assert not np.array_equal(na["poses"][600:900], nb["poses"][600:900])
        assert not np.array_equal(na["expressions"][600:900], nb["expressions"][600:900])
    # The face track (the default) follows the speech, not the seed: the range gets the same face.
    run_gmg("reenact", *face, "--seed", "1", "-o", tmp_path / "C.npz")
    run_gmg("reenact", *face, "--keep", tmp_path / "C.npz", "--range", "20:30", "--seed", "2", "-o", tmp_path / "D.npz")
    with np.load(tmp_path / "C.npz") as nc, np.load(tmp_path / "D.npz") as nd:
        assert np.array_equal(nc["trans"][:600], nd["trans"][:600])
        assert not np.array_equal(nc["poses"][600:900], nd["poses"][600:900])
        assert np.array_equal(nc["expressions"], nd["expressions"])

    run_gmg("reenact", *new, "--pin", "40=27:28.6", "--seed", "1", "-o", tmp_path / "P.bvh")
    p = gmg.read_motion(tmp_path / "P.bvh")
    gap = heading_relative(p, 1206, 36) - heading_relative(ref, 816, 36)
    assert np.linalg.norm(gap, axis=2).max() < 0.01  # metres
