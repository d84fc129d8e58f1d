"""The Python module at its edges: objects that were never built, paths with a NUL byte, speech
arrays that cannot be speech or are not samples, arguments of the wrong type or range, outputs of
the wrong kind, and gmg.Motion built from arrays."""
import subprocess
import sys
import wave

import numpy as np
import pytest

import gmg
from conftest import read_wav, run_gmg


def write_wav(path, samples, rate=16000):
    """float samples in [-1, 1] as a 16-bit PCM mono WAV."""
    with wave.open(str(path), "wb") as w:
        w.setnchannels(1)
        w.setsampwidth(2)
        w.setframerate(rate)
        w.writeframes((np.asarray(samples) * 32767).astype("<i2").tobytes())


def test_objects_that_were_never_built_raise_gmg_error_instead_of_crashing(synth):
    # In a child interpreter: before the fix, the first of these ended it with SIGSEGV.
    script = r"""
import gmg, sys
calls = {"with_frames": (), "slice": (0, 1), "write": ("x.bvh",), "save": ("x.gmg",), "write_report": ("x.json",),
         "stats": ()}
checked = []
for cls in (gmg.Graph, gmg.Reenactment, gmg.Motion):
    obj = cls.__new__(cls)
    for name in sorted(n for n in dir(cls) if not n.startswith("_")) + ["__len__", "__repr__"]:
        member = getattr(cls, name)
        try:
            if isinstance(member, property):
                getattr(obj, name)
            else:
                member(obj, *calls.get(name, ()))
        except gmg.Error as e:
            assert "was never built" in str(e), (cls, name, e)
            checked.append(cls.__name__ + "." + name)
            continue
        sys.exit("no gmg.Error from %s.%s" % (cls.__name__, name))
for call in (lambda: gmg.reenact(gmg.Graph.__new__(gmg.Graph), sys.argv[1]),
             lambda: gmg.evaluate(gmg.Motion.__new__(gmg.Motion)),
             lambda: gmg.evaluate(gmg.Reenactment.__new__(gmg.Reenactment)),
             lambda: gmg.build(gmg.Motion.__new__(gmg.Motion), sys.argv[1])):
    try:
        call()
        sys.exit("no gmg.Error")
    except gmg.Error as e:
        assert "was never built" in str(e), e
print(len(checked))
"""
    r = subprocess.run([sys.executable, "-c", script, str(synth / "new.wav")], capture_output=True, text=True)
    assert r.returncode == 0, (r.returncode, r.stdout, r.stderr)
    assert int(r.stdout) >= 35  # every property and method of the three classes


def test_a_path_with_a_nul_byte_is_refused_not_cut_short(synth, tmp_path):
    nul = "\x00junk"
    for call in (lambda: gmg.load(str(synth / "ref.gmg") + nul),
                 lambda: gmg.read_motion(str(synth / "ref.bvh") + nul),
                 lambda: gmg.reenact(synth / "ref.gmg", str(synth / "new.wav") + nul),
                 lambda: gmg.reenact(synth / "ref.gmg", synth / "new.wav", str(synth / "new.tsv") + nul),
                 lambda: gmg.convert(synth / "ref.bvh", str(tmp_path / "o.bvh") + nul),
                 lambda: gmg.read_motion(synth / "ref.bvh").write(str(tmp_path / "m.bvh") + nul)):
        with pytest.raises(gmg.Error, match=r"\\x00junk: a path cannot hold a NUL byte"):
            call()
    assert list(tmp_path.iterdir()) == []


def test_speech_as_samples_is_refused_as_a_file_of_it_is(synth, tmp_path):
    g = gmg.load(synth / "ref.gmg")
    rate = 16000
    tone = 0.3 * np.sin(2 * np.pi * 220 * np.arange(12 * rate) / rate)  # steady: no onset in 12 s
    for samples, problem in ((np.zeros(2 * rate), "is silent: every sample is zero"),
                             (np.zeros(rate // 5), "holds 0.2 s of audio, too short to be speech"),
                             (np.zeros((rate, 2)), "is silent: every sample is zero"),
                             (tone, "has no onset in 12.0 s of audio")):
        with pytest.raises(gmg.Error) as e:
            gmg.reenact(g, samples.astype(np.float32), sample_rate=rate, name="speech")
        assert problem in str(e.value) and "allow_silence=True uses it anyway" in str(e.value)
        # The same text as the command line's for a WAV of those samples, the flag named as Python names it.
        mono = samples if samples.ndim == 1 else samples.mean(axis=1)
        write_wav(tmp_path / "speech", mono)
        code, _, err = run_gmg("reenact", "--graph", synth / "ref.gmg", "--audio", tmp_path / "speech",
                               "-o", tmp_path / "o.bvh", check=False)
        assert code == 1
        assert err.replace(str(tmp_path / "speech"), "speech").replace("--allow-silence", "allow_silence=True") == \
            "gmg: error: " + str(e.value) + "\n"
    assert gmg.reenact(g, np.zeros(2 * rate, np.float32), sample_rate=rate, allow_silence=True).frame_count == 60
    # Building from samples and evaluating against them check them too.
    motion = gmg.read_motion(synth / "ref.bvh")
    with pytest.raises(gmg.Error, match="ref.bvh: is silent"):  # the clip is named after its motion
        gmg.build(clips=[{"motion": motion, "audio": np.zeros(40 * rate, np.float32), "sample_rate": rate}])
    with pytest.raises(gmg.Error, match="audio: is silent"):
        gmg.evaluate(motion, audio=np.zeros(40 * rate, np.float32), sample_rate=rate)
    assert gmg.evaluate(motion, audio=np.zeros(40 * rate, np.float32), sample_rate=rate,
                        allow_silence=True)["frames"] == 1200


def test_samples_that_are_not_real_mono_or_stereo_say_what_to_pass(synth):
    g = gmg.load(synth / "ref.gmg")
    new, rate = read_wav(synth / "new.wav")
    with pytest.raises(gmg.Error, match="audio: expected real numbers, got complex ones"):
        gmg.reenact(g, new.astype(np.complex64), sample_rate=rate)
    with pytest.raises(gmg.Error, match=r"a \(2, 192000\) array looks like \(channels, samples\); pass "
                                        r"\(samples, channels\), e.g. x.T, or mono samples"):
        gmg.reenact(g, np.stack([new, new]), sample_rate=rate)
    with pytest.raises(gmg.Error, match="audio: expected an array of numbers, got dtype <U1"):
        gmg.reenact(g, np.array(["a", "b"]), sample_rate=rate)
    # Views of any layout are copied: a strided slice and a broadcast stereo pair give the plain array's result.
    plain = gmg.reenact(g, new, sample_rate=rate, seed=4).rotations
    doubled = np.repeat(new, 2)[::2]
    assert not doubled.flags.c_contiguous
    np.testing.assert_array_equal(gmg.reenact(g, doubled, sample_rate=rate, seed=4).rotations, plain)
    stereo = np.broadcast_to(new[:, None], (len(new), 2))
    np.testing.assert_array_equal(gmg.reenact(g, stereo, sample_rate=rate, seed=4).rotations, plain)


def test_a_transcript_file_and_words_together_are_refused(synth):
    words = [(0.1, 0.5, "hello")]
    with pytest.raises(gmg.Error, match="reenact: give either a transcript file or words=, not both"):
        gmg.reenact(synth / "ref.gmg", synth / "new.wav", synth / "new.tsv", words=words)
    with pytest.raises(gmg.Error, match="build: give either a transcript file or words=, not both"):
        gmg.build(synth / "ref.bvh", synth / "ref.wav", synth / "ref.tsv", words=words)
    with pytest.raises(gmg.Error, match="clips: give either a transcript file or words=, not both"):
        gmg.build(clips=[{"motion": synth / "ref.bvh", "audio": synth / "ref.wav", "transcript": synth / "ref.tsv",
                          "words": words}])


def test_outputs_of_the_wrong_kind_are_refused_as_the_command_line_refuses_them(synth, tmp_path):
    r = gmg.reenact(synth / "ref.gmg", synth / "new.wav", seed=1)
    with pytest.raises(gmg.Error, match=r"r\.bvh: must be a \.json file \(its extension chooses the format\)"):
        r.write_report(tmp_path / "r.bvh")
    with pytest.raises(gmg.Error, match=r"m\.txt: must be a \.bvh or \.npz file"):
        r.write(tmp_path / "m.txt")
    with pytest.raises(gmg.Error, match=r"g\.bvh: must be a \.gmg file"):
        gmg.load(synth / "ref.gmg").save(tmp_path / "g.bvh")
    assert list(tmp_path.iterdir()) == []


def test_arguments_of_the_wrong_type_or_range_name_the_argument(synth):
    g = gmg.load(synth / "ref.gmg")
    new, rate = read_wav(synth / "new.wav")
    cases = [
        (dict(seed=-1), r"seed: -1 is out of range \(0 to 18446744073709551615\)"),
        (dict(seed=2 ** 70), r"seed: 1180591620717411303424 is out of range"),
        (dict(seed=1.5), r"seed: expected a whole number, got float 1.5"),
        (dict(sample_rate=float("nan")), r"sample_rate: nan is not a whole number of Hz \(4000 to 192000 Hz"),
        (dict(sample_rate=1e12), r"sample_rate: 1e\+12 Hz is outside the 4000 to 192000 Hz gmg reads"),
        (dict(sample_rate="16000"), r"sample_rate: expected a whole number of Hz, got str"),
        (dict(words=[(0.1, 0.5, 3)]), r"words: word 1: its text: expected a str, got int 3"),
        (dict(words=[(0.1, "x", "a")]), r"words: word 1: its end must be a number of seconds, got str 'x'"),
        (dict(words=["abc"]), r"words: word 1: expected \(start_seconds, end_seconds, text\), got 'abc'"),
        (dict(name=5), r"name: expected a str, got int 5"),
    ]
    for kwargs, message in cases:
        args = dict(sample_rate=rate)
        args.update(kwargs)
        with pytest.raises(gmg.Error, match=message):
            gmg.reenact(g, new, **args)
    with pytest.raises(gmg.Error, match=r"tier: expected a str, got int 5"):
        gmg.reenact(g, synth / "new.wav", synth / "new.tsv", tier=5)
    # Whole numbers of other types are taken: NumPy's integers, a float sample rate that is whole.
    a = gmg.reenact(g, new, sample_rate=float(rate), seed=np.uint64(7))
    b = gmg.reenact(g, new, sample_rate=rate, seed=7)
    np.testing.assert_array_equal(a.rotations, b.rotations)


def chain(frames=5):
    """A three-joint chain with turning joints, moving root and quaternions of length 2."""
    t = np.linspace(0, 1, frames)
    angles = np.stack([0.3 * t, -0.7 * t, 1.1 * t], axis=1)  # per frame and joint, about a tilted axis
    axis = np.array([0.6, 0.0, 0.8])
    rot = np.concatenate([np.cos(angles / 2)[..., None], np.sin(angles / 2)[..., None] * axis], axis=2)
    root = np.stack([t, 1 + 0 * t, -t], axis=1)
    return dict(joint_names=["root", "upper", "lower"], parents=[-1, 0, 1],
                offsets=np.array([[0.0, 90, 0], [0, 20, 0], [0, 15.5, 0]]), rotations=2 * rot, root=root, fps=25)


def test_a_motion_built_from_arrays_is_a_motion_everywhere(synth, tmp_path):
    c = chain()
    m = gmg.Motion(**c)
    assert (m.frame_count, m.joint_count, m.fps, m.joint_names) == (5, 3, 25, ["root", "upper", "lower"])
    np.testing.assert_array_equal(m.parents, [-1, 0, 1])
    np.testing.assert_array_equal(m.offsets, c["offsets"])
    np.testing.assert_allclose(m.rotations, c["rotations"] / 2, atol=1e-15)  # normalised, (w, x, y, z) kept
    np.testing.assert_array_equal(m.root, c["root"])
    # The last joint's world position by hand: root + R0 (offset1 + R1 offset2), all about one axis.
    a0, a1 = 0.3, 0.3 - 0.7
    axis = np.array([0.6, 0.0, 0.8])

    def turn(v, angle):
        return v * np.cos(angle) + np.cross(axis, v) * np.sin(angle) + axis * axis.dot(v) * (1 - np.cos(angle))
    end = c["root"][4] + turn(np.array([0, 20, 0.0]), a0) + turn(np.array([0, 15.5, 0.0]), a1)
    np.testing.assert_allclose(m.positions[4, 2], end, atol=1e-12)
    # Written as BVH and read back: the same motion, to the file's six decimals.
    m.write(tmp_path / "m.bvh")
    back = gmg.read_motion(tmp_path / "m.bvh")
    assert back.joint_names == m.joint_names and back.fps == 25 and back.frame_count == 5
    np.testing.assert_array_equal(back.parents, m.parents)
    np.testing.assert_allclose(back.positions, m.positions, atol=1e-5)
    q, p = back.rotations, m.rotations
    assert np.minimum(np.abs(q - p).max(axis=2), np.abs(q + p).max(axis=2)).max() < 1e-7
    # A reference's arrays make the motion its file makes: the same graph, and the same metrics.
    ref = gmg.read_motion(synth / "ref.bvh")
    same = gmg.Motion(ref.joint_names, ref.parents, ref.offsets, ref.rotations, ref.root, ref.fps, name="ref")
    np.testing.assert_array_equal(same.positions, ref.positions)
    assert gmg.build(same, synth / "ref.wav", synth / "ref.tsv").stats() == gmg.load(synth / "ref.gmg").stats()
    assert gmg.evaluate(same, truth=ref)["frames"] == 1200


def test_a_motion_from_arrays_is_checked_as_a_file_is():
    def refused(message, **change):
        c = chain()
        c.update(change)
        with pytest.raises(gmg.Error, match=message):
            gmg.Motion(**c)
    nan = chain()["rotations"].copy()
    nan[2, 1, 0] = np.nan
    zero = chain()["rotations"].copy()
    zero[3, 2] = 0
    refused("joint_names: joint 2: duplicate joint name 'upper'", joint_names=["root", "upper", "upper"])
    refused("joint_names: joint 1: 'up per' holds a space", joint_names=["root", "up per", "lower"])
    refused("joint_names: joint 1: expected a str, got int 7", joint_names=["root", 7, "lower"])
    refused("joint_names: 0 joints; gmg reads skeletons of 1 to 1024 joints", joint_names=[])
    refused(r"parents: joint 2 \('lower'\) has parent 2; a parent comes before its child \(0 to 1\)", parents=[-1, 0, 2])
    refused("parents: joint 0 .* has parent 0; the root's must be -1", parents=[0, 0, 1])
    refused(r"parents: expected shape \(3,\)", parents=[-1, 0])
    refused("parents: expected whole numbers", parents=np.array([-1.0, 0, 1]))
    refused(r"offsets: expected shape \(frames, 3\), found \(3, 2\)", offsets=np.zeros((3, 2)))
    refused(r"rotations: expected shape \(frames, 3, 4\), found \(5, 2, 4\)", rotations=np.ones((5, 2, 4)))
    refused("rotations: value 28 is not finite", rotations=nan)  # [2, 1, 0] of (5, 3, 4)
    refused("rotations: the quaternion of frame 3, joint 2 has length 0", rotations=zero)
    refused("rotations: expected real numbers, got complex ones", rotations=chain()["rotations"].astype(complex))
    refused("root: 4 frames, but rotations has 5", root=np.zeros((4, 3)))
    refused("fps: 0 is outside the 1 to 1000 fps gmg reads", fps=0)
    refused("fps: expected a number of frames per second", fps="30")
