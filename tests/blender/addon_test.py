"""The gmg add-on inside background Blender (run by tests/blender/blender_test.sh).

Installed from its zip as Blender's preferences install it, it imports BEAT2 2_scott_0_1_1.bvh,
builds a graph from the armature with the clip's WAV and TextGrid, and reenacts 2_scott_0_2_2
with seed 7: the armature's world joint positions must equal the forward kinematics of
`gmg reenact --graph` (the graph the add-on saved, the same seed) within 1 mm. A wrong file, silence
and a cancelled reenact must give their errors and leave the armature's action as it was.
Usage: blender -b --factory-startup --python-use-system-env --python-exit-code 1 --python addon_test.py --
       ZIP DATA_DIR GMG_BINARY WORK_DIR
"""
import os
import subprocess
import sys
import time
import wave

import bpy
import mathutils
import numpy as np

zip_path, data, gmg_binary, work = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.preferences.addon_install(filepath=zip_path)
bpy.ops.preferences.addon_enable(module="gmg_blender")
import gmg  # noqa: E402  (the module Blender's Python finds: the one just built)
import gmg_blender.operators as ops  # noqa: E402

assert os.path.realpath(ops.__file__).startswith(os.path.realpath(work)), ops.__file__
ref = os.path.join(data, "2_scott_0_1_1")
new = os.path.join(data, "2_scott_0_2_2")
graph = os.path.join(work, "G.gmg")
MM = 1e-3


def z_up(p):
    """gmg's Y-up positions (..., 3) in Blender's Z-up."""
    return np.stack([p[..., 0], -p[..., 2], p[..., 1]], axis=-1)


def world_heads(obj, names, frame):
    bpy.context.scene.frame_set(frame)
    return np.array([tuple(obj.matrix_world @ obj.pose.bones[n].head) for n in names])


def keys_of(action):
    """Every key of an action, for comparing before and after."""
    out = {}
    for fc in action.fcurves:
        co = np.empty(2 * len(fc.keyframe_points))
        fc.keyframe_points.foreach_get("co", co)
        out[(fc.data_path, fc.array_index)] = co.reshape(-1, 2)
    return out


def same_keys(a, b):
    return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)


def refused(call, *words):
    """The operator call fails with a report holding every word."""
    try:
        call()
    except RuntimeError as e:
        for w in words:
            assert w in str(e), f"'{w}' not in the report: {e}"
        return str(e)
    raise AssertionError("the operator did not refuse")


# ---- The round trip, timed -----------------------------------------------------------------
wall, cpu = time.perf_counter(), time.process_time()
bpy.ops.gmg.import_motion(filepath=ref + ".bvh")
obj = bpy.context.active_object
imported = obj.animation_data.action
bpy.ops.gmg.build(audio=ref + ".wav", transcript=ref + ".TextGrid", filepath=graph)
bpy.ops.gmg.reenact(graph=graph, audio=new + ".wav", transcript=new + ".TextGrid", seed=7)
wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
print(f"import + build + reenact: {wall:.2f} s, {cpu:.2f} s of CPU")
assert cpu <= 3.0, f"import, build and reenact took {cpu:.2f} s of CPU (target 3 s)"

scene = bpy.context.scene
action = obj.animation_data.action
assert action.name == "gmg 2_scott_0_2_2 seed 7", action.name
assert scene.render.fps == 30 and scene.frame_start == 1 and scene.frame_end == 1860, scene.frame_end
strip = scene.sequence_editor.sequences["gmg speech"]
assert os.path.samefile(bpy.path.abspath(strip.sound.filepath), new + ".wav") and strip.frame_start == 1

cli = os.path.join(work, "cli.bvh")
subprocess.run([gmg_binary, "reenact", "--graph", graph, "--audio", new + ".wav", "--transcript",
                new + ".TextGrid", "--seed", "7", "-o", cli], check=True, capture_output=True)
expected = gmg.read_motion(cli)
assert expected.frame_count == 1860
for frame in (1, 600, 1500):
    error = np.abs(world_heads(obj, expected.joint_names, frame) - z_up(expected.positions[frame - 1])).max()
    print(f"frame {frame}: largest joint distance from `gmg reenact` {error * 1000:.4f} mm")
    assert error <= MM, f"frame {frame}: {error} m"

# The imported action is the BVH's motion, Z-up.
source = gmg.read_motion(ref + ".bvh")
obj.animation_data.action = imported
for frame in (1, 1906):
    error = np.abs(world_heads(obj, source.joint_names, frame) - z_up(source.positions[frame - 1])).max()
    assert error <= MM, f"imported frame {frame}: {error} m"
obj.animation_data.action = action

# A BEAT2 .npz with the BVH as its skeleton: the same joints, root-relative positions as the BVH's.
bpy.ops.gmg.import_motion(filepath=ref + ".npz", skeleton=ref + ".bvh")
npz = bpy.context.active_object
assert npz != obj and npz.type == "ARMATURE" and len(npz.data.bones) == 55
smplx = gmg.read_motion(ref + ".npz", skeleton=ref + ".bvh")
for frame in (1, 1906):
    error = np.abs(world_heads(npz, smplx.joint_names, frame) - z_up(smplx.positions[frame - 1])).max()
    assert error <= MM, f"imported npz frame {frame}: {error} m"
npz_data = npz.data
bpy.data.objects.remove(npz)
bpy.data.armatures.remove(npz_data)
bpy.context.view_layer.objects.active = obj

# ---- An armature of other rest orientations, keyed in Euler angles ---------------------------
# Bones rolled and pointing elsewhere than the add-on makes them: reenact onto it gives the same
# world positions, and its Euler-keyed action reads back as the same gmg motion.
import gmg_blender.armature as arm  # noqa: E402

other = arm.create_armature(bpy.context, "rolled", source.joint_names, source.parents, source.offsets)
bpy.ops.object.mode_set(mode="EDIT")
for j, b in enumerate(other.data.edit_bones):
    b.tail = b.head + mathutils.Vector((0.03, -0.02, 0.05)) * (1 + j % 3)
    b.roll = 0.4 + 0.1 * j
bpy.ops.object.mode_set(mode="OBJECT")
bpy.ops.gmg.reenact(graph=graph, audio=new + ".wav", transcript=new + ".TextGrid", seed=7)
for frame in (1, 600, 1500):
    error = np.abs(world_heads(other, expected.joint_names, frame) - z_up(expected.positions[frame - 1])).max()
    assert error <= MM, f"rolled armature, frame {frame}: {error} m"
quaternions = other.animation_data.action
euler = bpy.data.actions.new("euler")
for j, name in enumerate(source.joint_names):
    channels = {"rotation_euler": []}
    for f in range(1, 6):
        q = [quaternions.fcurves.find(arm.bone_path(name, "rotation_quaternion"), index=i).evaluate(f)
             for i in range(4)]
        channels["rotation_euler"].append(tuple(mathutils.Quaternion(q).to_euler("ZXY")))
    if j == 0:
        channels["location"] = [[quaternions.fcurves.find(arm.bone_path(name, "location"), index=i).evaluate(f)
                                 for i in range(3)] for f in range(1, 6)]
    for channel, values in channels.items():
        for i in range(3):
            fc = euler.fcurves.new(arm.bone_path(name, channel), index=i)
            for f, v in zip(range(1, 6), values):
                fc.keyframe_points.insert(f, v[i])
    other.pose.bones[name].rotation_mode = "ZXY"
read = gmg.Motion(*arm.motion_arrays(other, euler, np.arange(1, 6)), 30)
error = np.abs(read.positions - expected.positions[:5]).max()
assert error <= MM, f"the Euler-keyed action read as gmg's motion: {error} m"
print(f"a rolled armature: reenacted and read back from Euler keys within {error * 1000:.4f} mm")
rolled = other.data
bpy.data.objects.remove(other)
bpy.data.armatures.remove(rolled)
bpy.context.view_layer.objects.active = obj

# ---- Refusals leave everything as it was ---------------------------------------------------
before = keys_of(action)
actions = len(bpy.data.actions)
objects = len(bpy.data.objects)
wrong = os.path.join(work, "wrong.bvh")
with open(wrong, "w") as f:
    f.write("not a motion\n")
silence = os.path.join(work, "silence.wav")
with wave.open(silence, "wb") as w:
    w.setnchannels(1)
    w.setsampwidth(2)
    w.setframerate(16000)
    w.writeframes(bytes(2 * 16000 * 3))

refused(lambda: bpy.ops.gmg.import_motion(filepath=wrong), wrong)
refused(lambda: bpy.ops.gmg.import_motion(filepath=os.path.join(work, "absent.bvh")), "absent.bvh", "no such file")
assert len(bpy.data.objects) == objects and len(bpy.data.armatures) == 1
refused(lambda: bpy.ops.gmg.build(audio=silence, filepath=os.path.join(work, "S.gmg")), silence, "silent")
assert not os.path.exists(os.path.join(work, "S.gmg"))
refused(lambda: bpy.ops.gmg.reenact(graph=graph, audio=silence, seed=1), silence, "silent")
refused(lambda: bpy.ops.gmg.reenact(graph=wrong, audio=new + ".wav", seed=1), wrong)
assert obj.animation_data.action == action and len(bpy.data.actions) == actions
assert same_keys(keys_of(action), before)

# Cancelled: the work ends in its thread and nothing is applied.
job = ops.reenact_job(bpy.context, graph, new + ".wav", new + ".TextGrid", 8)
job.start()
job.cancel()
job.thread.join()
assert job.error is None and job.result is not None and job.finish() is None
assert obj.animation_data.action == action and len(bpy.data.actions) == actions
assert same_keys(keys_of(action), before)
print("refusals and a cancelled reenact left the action as it was")

# ---- Regenerate frames 600 to 900 ----------------------------------------------------------
class KeepingGmg:
    """Stands in for a gmg module whose reenact takes keep= and ranges= where the module built here
    has none: it records what the add-on passes and reenacts the whole speech with the seed asked,
    so the add-on's side (the kept motion it writes, the range in seconds, the keys it replaces)
    is checked either way."""
    Error, Motion, load = gmg.Error, gmg.Motion, gmg.load

    def __init__(self):
        self.kept = self.ranges = None

    def reenact(self, graph, audio, transcript=None, *, keep, ranges, seed, set=None):
        """reenact(graph, audio, transcript, keep=, ranges=, seed=, set=)"""
        self.kept, self.ranges = gmg.read_motion(keep), ranges
        return gmg.reenact(graph, audio, transcript, seed=seed, set=set)


def check_regenerated(before, after):
    assert after.keys() == before.keys()
    changed = False
    for k, co in before.items():
        outside = (co[:, 0] < 600) | (co[:, 0] > 900)
        assert np.array_equal(after[k][outside], co[outside]), f"{k}: a key outside 600-900 changed"
        assert np.array_equal(after[k][:, 0], co[:, 0]), f"{k}: keys moved"
        changed = changed or not np.array_equal(after[k][~outside], co[~outside])
    assert changed, "regenerate changed no key within 600-900"


if "keep" in (gmg.reenact.__doc__ or ""):
    bpy.ops.gmg.regenerate(frame_start=600, frame_end=900, seed=3)
    check_regenerated(before, keys_of(action))
    # As `gmg reenact --keep` of the seed-7 output over frames 600 to 900 (gmg's 599 to 899) with seed 3.
    kept = os.path.join(work, "kept.bvh")
    subprocess.run([gmg_binary, "reenact", "--graph", graph, "--audio", new + ".wav", "--transcript",
                    new + ".TextGrid", "--seed", "3", "--keep", cli, "--range", f"{599 / 30}:{900 / 30}", "-o", kept],
                   check=True, capture_output=True)
    regenerated = gmg.read_motion(kept)
    for frame in (600, 750, 900):
        error = np.abs(world_heads(obj, regenerated.joint_names, frame) - z_up(regenerated.positions[frame - 1])).max()
        assert error <= MM, f"regenerated frame {frame}: {error} m from gmg reenact --keep"
    print("regenerate 600-900 kept every other frame's keys and equals gmg reenact --keep --range")
else:
    refused(lambda: bpy.ops.gmg.regenerate(frame_start=600, frame_end=900, seed=3), "keep")
    assert same_keys(keys_of(action), before)
    stand_in, module = KeepingGmg(), ops.gmg_module
    ops.gmg_module = lambda: stand_in
    try:
        refused(lambda: bpy.ops.gmg.regenerate(frame_start=600, frame_end=1900, seed=3), "1900", "1 to 1860")
        bpy.ops.gmg.regenerate(frame_start=600, frame_end=900, seed=3)
    finally:
        ops.gmg_module = module
    # Blender frames 600 to 900 from start frame 1 are gmg frames 599 to 899: [599/30, 900/30) s.
    assert stand_in.kept.frame_count == 1860 and stand_in.ranges == [(599 / 30, 900 / 30)], stand_in.ranges
    for frame in (1, 599):  # the kept motion the add-on wrote is the action's (to the BVH's 6 decimals)
        bpy.context.scene.frame_set(frame)
        error = np.abs(world_heads(obj, expected.joint_names, frame) - z_up(stand_in.kept.positions[frame - 1])).max()
        assert error <= MM, f"kept frame {frame}: {error} m"
    check_regenerated(before, keys_of(action))
    print("SKIP: regenerate with gmg's keep=: this gmg module has none; its refusal checked, and with a stand-in "
          "reenact the range 600-900 was replaced and every other frame's keys kept")
print("PASS: the add-on imported, built and reenacted within 1 mm of `gmg reenact`")
