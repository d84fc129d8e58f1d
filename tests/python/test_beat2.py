"""BEAT2 from Python: the shared clip 2_scott_0_1_1 built and reenacted from Python equals the
command line byte for byte, and the .npz it writes keeps the speaker (BEAT2's keys, shapes and
dtypes; trans in BEAT2's convention; the reference's betas; a face that speaks the new speech)."""
import numpy as np

import gmg
from conftest import run_gmg


def test_build_and_reenact_of_the_shared_beat2_clip_equal_the_command_line(beat2, tmp_path):
    ref = dict(motion=beat2 / "2_scott_0_1_1.npz", skeleton=beat2 / "2_scott_0_1_1.bvh",
               audio=beat2 / "2_scott_0_1_1.wav", transcript=beat2 / "2_scott_0_1_1.TextGrid")
    new_audio, new_words = beat2 / "2_scott_0_2_2.wav", beat2 / "2_scott_0_2_2.TextGrid"
    run_gmg("build", "--motion", ref["motion"], "--skeleton", ref["skeleton"], "--audio", ref["audio"],
            "--transcript", ref["transcript"], "-o", tmp_path / "cli.gmg")
    run_gmg("reenact", "--graph", tmp_path / "cli.gmg", "--audio", new_audio, "--transcript", new_words,
            "--seed", "7", "-o", tmp_path / "cli.npz")
    run_gmg("reenact", "--graph", tmp_path / "cli.gmg", "--audio", new_audio, "--transcript", new_words,
            "--seed", "7", "-o", tmp_path / "cli.bvh")
    g = gmg.build(**ref)
    g.save(tmp_path / "py.gmg")
    assert (tmp_path / "py.gmg").read_bytes() == (tmp_path / "cli.gmg").read_bytes()
    assert g.has_face
    r = gmg.reenact(gmg.load(tmp_path / "py.gmg"), new_audio, new_words, seed=7)
    r.write(tmp_path / "py.npz")
    r.write(tmp_path / "py.bvh")
    assert (tmp_path / "py.npz").read_bytes() == (tmp_path / "cli.npz").read_bytes()
    assert (tmp_path / "py.bvh").read_bytes() == (tmp_path / "cli.bvh").read_bytes()

    # The output read with NumPy: BEAT2's keys, shapes and dtypes.
    with np.load(beat2 / "2_scott_0_1_1.npz") as orig, np.load(tmp_path / "py.npz") as out:
        assert out.files == orig.files
        for key in orig.files:
            assert out[key].dtype == orig[key].dtype, key
            assert out[key].shape[1:] == orig[key].shape[1:], key
        assert out["poses"].shape[0] == r.frame_count == round(62.0 * 30)
        assert str(out["model"]) == "smplx2020" and str(out["gender"]) == "neutral"
        assert abs(np.median(out["trans"][:, 1]) - np.median(orig["trans"][:, 1])) < 0.01
        np.testing.assert_array_equal(out["betas"], orig["betas"])
        np.testing.assert_array_equal(out["expressions"], r.expressions)
        # The face track: it changes from frame to frame, every coefficient within the speaker's own
        # range (+-0.05), and the jaw Python returns is the opening of SMPL-X joint 22 in `poses`.
        e = out["expressions"]
        assert np.abs(np.diff(e, axis=0)).mean() > 0.1 * np.abs(np.diff(orig["expressions"], axis=0)).mean()
        lo, hi = orig["expressions"].min(axis=0), orig["expressions"].max(axis=0)
        assert ((e >= lo - 0.05) & (e <= hi + 0.05)).all()
        np.testing.assert_allclose(r.jaw, np.linalg.norm(out["poses"][:, 66:69], axis=1), atol=1e-6)
    assert r.report["face_track"]["follows"] == "speech" and r.report["face_track"]["units"] == "phones"
    assert r.report["body"] == {"face": "reference", "betas": "reference"}


def test_a_graph_built_from_the_bvh_writes_beat2s_trans_and_says_it_has_no_face(beat2, tmp_path):
    g = gmg.build(beat2 / "2_scott_0_1_1.bvh", beat2 / "2_scott_0_1_1.wav", beat2 / "2_scott_0_1_1.TextGrid")
    r = gmg.reenact(g, beat2 / "2_scott_0_2_2.wav", beat2 / "2_scott_0_2_2.TextGrid", seed=7,
                    betas=beat2 / "2_scott_0_1_1.npz")
    r.write(tmp_path / "out.npz")
    with np.load(beat2 / "2_scott_0_1_1.npz") as orig, np.load(tmp_path / "out.npz") as out:
        assert abs(np.median(out["trans"][:, 1]) - np.median(orig["trans"][:, 1])) < 0.01
        np.testing.assert_array_equal(out["betas"], orig["betas"])
        assert not out["expressions"].any()
    assert r.report["body"]["face"] == "none"
    assert "the reference has no face" in r.report["body"]["note"]
    assert r.report["body"]["betas"] == str(beat2 / "2_scott_0_1_1.npz")
