"""The Python module `gmg`: arrays in and out, errors as exceptions with the command line's
messages, the same bytes as the command line, the GIL released during the long calls."""
import json
import threading

import numpy as np
import pytest

import gmg
from conftest import cli_json, read_tsv, read_wav, run_gmg


def test_the_module_is_the_one_built_here_and_has_its_api():
    assert gmg.__version__ == "0.1.0"
    for name in ("build", "load", "reenact", "evaluate", "convert", "read_motion", "config", "config_keys",
                 "Motion", "Graph", "Reenactment", "Error"):
        assert hasattr(gmg, name), name
    assert issubclass(gmg.Error, Exception)


def test_a_motion_comes_out_as_arrays_that_agree_with_each_other(synth):
    m = gmg.read_motion(synth / "ref.bvh")
    n, j = m.frame_count, m.joint_count
    assert (n, j) == (1200, 22) and m.fps == 30 and len(m) == n
    assert m.rotations.shape == (n, j, 4) and m.rotations.dtype == np.float64
    np.testing.assert_allclose(np.linalg.norm(m.rotations, axis=2), 1.0, atol=1e-12)
    assert m.axis_angle.shape == (n, j, 3)
    assert m.translations.shape == (n, j, 3) and m.root.shape == (n, 3)
    np.testing.assert_array_equal(m.root, m.translations[:, 0])
    p = m.positions
    assert p.shape == (n, j, 3)
    np.testing.assert_array_equal(p[:, 0], m.root)  # the root's world position is its translation
    # A child sits at its bone length from its parent in every frame.
    parents = m.parents
    for k in range(1, j):
        bone = np.linalg.norm(m.offsets[k])
        np.testing.assert_allclose(np.linalg.norm(p[:, k] - p[:, parents[k]], axis=1), bone, rtol=1e-9, atol=1e-9)
    assert m.joint_names[0] == "Hips" and parents[0] == -1
    assert m.expressions is None and m.betas is None


def test_arrays_go_back_in_as_a_motion_of_the_same_skeleton(synth, tmp_path):
    m = gmg.read_motion(synth / "ref.bvh")
    again = m.with_frames(axis_angle=m.axis_angle)
    q, p = again.rotations, m.rotations  # q and -q are one rotation
    assert np.minimum(np.abs(q - p).max(axis=2), np.abs(q + p).max(axis=2)).max() < 1e-12
    # A new length: 10 frames at rest, the root where asked.
    root = np.tile([1.0, 2.0, 3.0], (10, 1))
    rest = m.with_frames(rotations=np.tile([1.0, 0, 0, 0], (10, m.joint_count, 1)), root=root, fps=25)
    assert (rest.frame_count, rest.fps) == (10, 25)
    np.testing.assert_array_equal(rest.root, root)
    rest.write(tmp_path / "rest.bvh")
    back = gmg.read_motion(tmp_path / "rest.bvh")
    np.testing.assert_allclose(back.positions, rest.positions, atol=1e-5)
    # Shapes that do not fit are gmg.Error naming the array.
    with pytest.raises(gmg.Error, match=r"rotations: expected shape \(frames, 22, 4\), found \(10, 3\)"):
        m.with_frames(rotations=np.zeros((10, 3)))
    with pytest.raises(gmg.Error, match="not finite"):
        m.with_frames(root=np.full((m.frame_count, 3), np.nan))


def test_errors_are_gmg_errors_with_the_command_lines_messages(synth, tmp_path):
    # (call, command line, its exit code: 1 a bad input, 2 a usage error such as a bad --set)
    cases = [
        (lambda: gmg.load(tmp_path / "missing.gmg"), ["inspect", tmp_path / "missing.gmg"], 1),
        (lambda: gmg.reenact(synth / "ref.gmg", tmp_path / "missing.wav"),
         ["reenact", "--graph", synth / "ref.gmg", "--audio", tmp_path / "missing.wav", "-o", tmp_path / "o.bvh"], 1),
        (lambda: gmg.read_motion(synth / "ref.tsv"),
         ["convert", synth / "ref.tsv", tmp_path / "o.npz"], 1),
        (lambda: gmg.reenact(synth / "ref.gmg", synth / "new.wav", set={"l_pn": "0"}),
         ["reenact", "--graph", synth / "ref.gmg", "--audio", synth / "new.wav", "--set", "l_pn=0",
          "-o", tmp_path / "o.bvh"], 2),
    ]
    for call, args, expected_code in cases:
        code, _, err = run_gmg(*args, check=False)
        assert code == expected_code, err
        with pytest.raises(gmg.Error) as e:
            call()
        assert "gmg: error: " + str(e.value) + "\n" == err
    with pytest.raises(gmg.Error, match="audio given as samples needs sample_rate="):
        gmg.reenact(synth / "ref.gmg", np.zeros(16000, dtype=np.float32))
    with pytest.raises(gmg.Error, match="sample_rate: 100 Hz is outside the 4000 to 192000 Hz gmg reads"):
        gmg.reenact(synth / "ref.gmg", np.zeros(1000, dtype=np.float32), sample_rate=100)


def test_reenact_from_files_is_the_command_line_byte_for_byte(synth, tmp_path):
    run_gmg("reenact", "--graph", synth / "ref.gmg", "--audio", synth / "new.wav", "--transcript", synth / "new.tsv",
            "--seed", "7", "-o", tmp_path / "cli.bvh", "--report", tmp_path / "cli.json")
    r = gmg.reenact(str(synth / "ref.gmg"), synth / "new.wav", synth / "new.tsv", seed=7)
    r.write(tmp_path / "py.bvh")
    r.write_report(tmp_path / "py.json")
    assert (tmp_path / "py.bvh").read_bytes() == (tmp_path / "cli.bvh").read_bytes()
    assert (tmp_path / "py.json").read_bytes() == (tmp_path / "cli.json").read_bytes()
    assert r.report == json.loads((tmp_path / "cli.json").read_text())
    assert r.frame_count == 12 * 30


def test_build_from_files_is_gmg_build_and_reenact_in_memory_matches_the_cli(synth, tmp_path):
    g = gmg.build(synth / "ref.bvh", synth / "ref.wav", synth / "ref.tsv")
    g.save(tmp_path / "py.gmg")
    assert (tmp_path / "py.gmg").read_bytes() == (synth / "ref.gmg").read_bytes()
    assert g.frame_count == 1200 and g.name == str(synth / "ref.bvh") and not g.has_face
    assert g.stats()["keyword_nodes"] == cli_json("inspect", synth / "ref.gmg", "--json")["keyword_nodes"]
    run_gmg("reenact", "--reference-motion", synth / "ref.bvh", "--reference-audio", synth / "ref.wav",
            "--reference-transcript", synth / "ref.tsv", "--audio", synth / "new.wav", "--seed", "3",
            "-o", tmp_path / "cli.npz", "--report", tmp_path / "cli.json")
    r = gmg.reenact(g, synth / "new.wav", seed=3)
    r.write(tmp_path / "py.npz")
    r.write_report(tmp_path / "py.json")
    assert (tmp_path / "py.npz").read_bytes() == (tmp_path / "cli.npz").read_bytes()
    assert (tmp_path / "py.json").read_bytes() == (tmp_path / "cli.json").read_bytes()


def test_arrays_in_give_what_the_files_give(synth):
    samples, rate = read_wav(synth / "ref.wav")
    words = read_tsv(synth / "ref.tsv")
    motion = gmg.read_motion(synth / "ref.bvh")
    from_arrays = gmg.build(motion, samples, words=words, sample_rate=rate)
    from_files = gmg.load(synth / "ref.gmg")
    assert from_arrays.frame_count == from_files.frame_count
    assert from_arrays.stats() == from_files.stats()
    new, new_rate = read_wav(synth / "new.wav")
    a = gmg.reenact(from_arrays, new, sample_rate=new_rate, words=read_tsv(synth / "new.tsv"), seed=5)
    b = gmg.reenact(from_files, synth / "new.wav", synth / "new.tsv", seed=5)
    np.testing.assert_array_equal(a.rotations, b.rotations)
    np.testing.assert_array_equal(a.root, b.root)
    assert a.report["subsequences"] == b.report["subsequences"]
    # Stereo samples are mixed to mono as the readers mix them.
    c = gmg.reenact(from_files, np.stack([new, new], axis=1), sample_rate=new_rate,
                    words=read_tsv(synth / "new.tsv"), seed=5)
    np.testing.assert_array_equal(c.rotations, b.rotations)


def test_evaluate_gives_the_command_lines_metrics(synth, tmp_path):
    r = gmg.reenact(synth / "ref.gmg", synth / "new.wav", synth / "new.tsv", seed=2)
    r.write(tmp_path / "out.bvh")
    r.write_report(tmp_path / "out.json")
    args = dict(audio=synth / "new.wav", report=tmp_path / "out.json", reference=synth / "ref.gmg")
    cli = cli_json("evaluate", "--generated", tmp_path / "out.bvh", "--audio", args["audio"], "--report",
                   args["report"], "--reference", args["reference"], "--json")
    assert gmg.evaluate(str(tmp_path / "out.bvh"), **args) == cli
    # From the objects in memory: the same metrics (the motion in memory is the file's before
    # the BVH's six decimals, so to rounding).
    mem = gmg.evaluate(r, audio=synth / "new.wav", reference=gmg.load(synth / "ref.gmg"))
    assert mem["frames"] == cli["frames"] and mem["failures"] == cli["failures"]
    assert mem["bc"] == pytest.approx(cli["bc"], rel=1e-4, abs=1e-6)
    assert mem["generated"]["jerk_cm_s3"] == pytest.approx(cli["generated"]["jerk_cm_s3"], rel=1e-3)
    # Bytes that are not UTF-8 in a message (a binary file read as text) do not hide the error.
    with pytest.raises(gmg.Error, match="not a BVH file"):
        gmg.read_motion(synth / "ref.wav")


def test_config_is_the_command_lines(synth):
    assert gmg.config() == cli_json("config")
    assert gmg.config(set={"l_pn": 7}, seed=9)["l_pn"] == 7
    assert gmg.config(set=["l_pn=8"])["l_pn"] == 8
    assert gmg.config(config={"l_pn": 9})["l_pn"] == 9
    assert "l_pn" in gmg.config_keys()
    with pytest.raises(gmg.Error, match="no_such_key"):
        gmg.config(set={"no_such_key": 1})


def test_convert_is_exact_from_bvh_to_npz_and_back(synth, tmp_path):
    run_gmg("convert", synth / "ref.bvh", tmp_path / "cli.bvh")
    summary = gmg.convert(tmp_path / "cli.bvh", tmp_path / "a.npz", npz_dtype="float64")
    assert summary["frames"] == 1200 and summary["joints"] == 22
    gmg.convert(tmp_path / "a.npz", tmp_path / "back.bvh", skeleton=synth / "ref.bvh")
    assert (tmp_path / "back.bvh").read_bytes() == (tmp_path / "cli.bvh").read_bytes()
    with np.load(tmp_path / "a.npz") as z:
        assert z["poses"].shape == (1200, 66) and z["trans"].shape == (1200, 3)
        assert int(z["mocap_frame_rate"]) == 30


def test_long_calls_release_the_gil(synth):
    g = gmg.load(synth / "ref.gmg")
    done = threading.Event()
    result = {}

    def work():
        result["r"] = gmg.reenact(g, synth / "new.wav", synth / "new.tsv", seed=1)
        done.set()

    t = threading.Thread(target=work)
    ticks = 0
    t.start()
    while not done.is_set():  # this loop runs only while the reenactment does not hold the GIL
        ticks += 1
    t.join()
    assert result["r"].frame_count == 360
    assert ticks > 10000, ticks
    # Reenactments of one graph from several threads give each its own result.
    out = [None] * 4

    def one(k):
        out[k] = gmg.reenact(g, synth / "new.wav", synth / "new.tsv", seed=k).rotations

    threads = [threading.Thread(target=one, args=(k,)) for k in range(4)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    for k in range(4):
        np.testing.assert_array_equal(out[k], gmg.reenact(g, synth / "new.wav", synth / "new.tsv", seed=k).rotations)
