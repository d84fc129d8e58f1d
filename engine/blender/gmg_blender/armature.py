"""An armature and its action as gmg's arrays, and gmg's arrays as keys on an armature.

gmg's motion is a BVH-like skeleton: joints with rest offsets from their parents, per frame a
local rotation of every joint and the root's position, Y-up, every joint's rest rotation the
identity. A Blender armature is Z-up and each bone has its own rest orientation (its head-to-tail
direction and roll). The two meet through the world: joint j's gmg frame is the bone's posed frame
turned back by its rest rotation Rm_j and from Z-up to Y-up (K). For a pose-space basis rotation
Rb_j that gives the local rotation q_j = S_j Rb_j S_j^-1 with S_j = K Rm_j, for any rest
orientation, so an armature made elsewhere converts as one this add-on made. Positions are in
armature space (the object's own transform is not part of the motion). Bones keep Blender's
default inheritance (rotation and scale from the parent, not connected); scale keys are ignored.
"""
import bpy
import numpy as np

from . import rotations as rot


class AddonError(Exception):
    """A refusal the add-on makes itself (the gmg module raises gmg.Error): shown as the report."""


class Rest:
    """An armature's bones in an order where parents come first, with their rest (armature space)."""

    def __init__(self, obj):
        bones = obj.data.bones
        roots = [b for b in bones if b.parent is None]
        if len(roots) != 1:
            raise AddonError(f"armature '{obj.name}': {len(roots)} root bones; gmg needs a skeleton with one root")
        order = []
        stack = [roots[0]]
        while stack:  # depth first, children in Blender's order: the order a BVH lists them
            b = stack.pop()
            order.append(b)
            stack.extend(reversed(b.children))
        self.names = [b.name for b in order]
        index = {n: i for i, n in enumerate(self.names)}
        self.parents = np.array([-1 if b.parent is None else index[b.parent.name] for b in order], dtype=np.int64)
        self.heads = np.array([tuple(b.head_local) for b in order], dtype=np.float64)
        self.rest = np.array([tuple(b.matrix_local.to_quaternion()) for b in order], dtype=np.float64)
        self.turn = rot.multiply(rot.Z_UP_TO_Y_UP, self.rest)  # S_j = K Rm_j

    def offsets(self):
        """gmg's rest offsets, Y-up: the root's from the origin, the others' from their parents."""
        d = self.heads.copy()
        d[1:] -= self.heads[self.parents[1:]]
        return rot.rotate(rot.Z_UP_TO_Y_UP, d)


def bone_path(name, channel):
    return f'pose.bones["{bpy.utils.escape_identifier(name)}"].{channel}'


def channel_values(action, path, size, frames, default):
    """(frames, size) values of an action's channel at whole frames: the keys themselves where
    every frame has one, else the curves evaluated; `default` where a curve is missing."""
    out = np.tile(np.asarray(default, dtype=np.float64), (len(frames), 1))
    for i in range(size):
        fc = action.fcurves.find(path, index=i)
        if fc is None:
            continue
        n = len(fc.keyframe_points)
        co = np.empty(2 * n, dtype=np.float64)
        fc.keyframe_points.foreach_get("co", co)
        x = co[0::2]
        at = np.minimum(np.searchsorted(x, frames), max(n - 1, 0))
        if n and not fc.modifiers and np.array_equal(x[at], frames):
            out[:, i] = co[1::2][at]
        else:
            out[:, i] = [fc.evaluate(float(f)) for f in frames]
    return out


def action_frames(action):
    """The whole frames an action covers."""
    first, last = action.frame_range
    return np.arange(int(round(first)), int(round(last)) + 1)


def motion_arrays(obj, action, frames):
    """The armature's motion over `frames` as gmg.Motion's arrays, Y-up:
    (joint_names, parents, offsets, rotations, root)."""
    rest = Rest(obj)
    count = len(frames)
    basis = np.empty((count, len(rest.names), 4))
    for j, name in enumerate(rest.names):
        mode = obj.pose.bones[name].rotation_mode
        if mode == "QUATERNION":
            q = channel_values(action, bone_path(name, "rotation_quaternion"), 4, frames, (1, 0, 0, 0))
        elif mode == "AXIS_ANGLE":
            q = rot.from_axis_angle(channel_values(action, bone_path(name, "rotation_axis_angle"), 4, frames,
                                                   (0, 0, 1, 0)))
        else:
            q = rot.from_euler(channel_values(action, bone_path(name, "rotation_euler"), 3, frames, (0, 0, 0)), mode)
        basis[:, j] = rot.normalized(q)
    rotations = rot.multiply(rot.multiply(rest.turn, basis), rot.conjugate(rest.turn))
    location = channel_values(action, bone_path(rest.names[0], "location"), 3, frames, (0, 0, 0))
    root = rot.rotate(rot.Z_UP_TO_Y_UP, rest.heads[0] + rot.rotate(rest.rest[0], location))
    return rest.names, rest.parents, rest.offsets(), rotations, root


def pose_values(obj, names, rotations, root):
    """gmg's local rotations (frames, joints, 4) and root positions (frames, 3), Y-up, of joints
    `names` as the armature's pose channels: {bone: (quaternions, root location or None)}."""
    rest = Rest(obj)
    index = {n: i for i, n in enumerate(rest.names)}
    missing = [n for n in names if n not in index]
    if missing:
        shown = ", ".join(missing[:5]) + (" ..." if len(missing) > 5 else "")
        raise AddonError(f"armature '{obj.name}' lacks {len(missing)} of the motion's joints ({shown})")
    if index[names[0]] != 0:
        raise AddonError(f"armature '{obj.name}': its root bone is '{rest.names[0]}', the motion's '{names[0]}'")
    turn = rest.turn[[index[n] for n in names]]
    basis = rot.multiply(rot.multiply(rot.conjugate(turn), np.asarray(rotations)), turn)
    world = rot.rotate(rot.Y_UP_TO_Z_UP, np.asarray(root)) - rest.heads[0]
    location = rot.rotate(rot.conjugate(rest.rest[0]), world)
    return {n: (rot.continuous(basis[:, k]), location if k == 0 else None) for k, n in enumerate(names)}


def _keys(fc, frames, values):
    co = np.empty((len(frames), 2), dtype=np.float64)
    co[:, 0] = frames
    co[:, 1] = values
    fc.keyframe_points.add(len(frames))
    fc.keyframe_points.foreach_set("co", co.ravel())
    fc.update()


def key_new_action(obj, name, frames, values):
    """A new action on nothing yet: every bone of `values` (pose_values) keyed at `frames`."""
    action = bpy.data.actions.new(name)
    for bone, (quaternions, location) in values.items():
        for i in range(4):
            _keys(action.fcurves.new(bone_path(bone, "rotation_quaternion"), index=i, action_group=bone), frames,
                  quaternions[:, i])
        if location is not None:
            for i in range(3):
                _keys(action.fcurves.new(bone_path(bone, "location"), index=i, action_group=bone), frames,
                      location[:, i])
    return action


def use_action(obj, action, bones):
    """Plays `action` on the armature; `bones` turn to quaternion rotation (what it keys). The
    action it replaces keeps a fake user, so saving the file does not drop it."""
    if obj.animation_data is None:
        obj.animation_data_create()
    previous = obj.animation_data.action
    if previous is not None and previous != action:
        previous.use_fake_user = True
    for bone in bones:
        obj.pose.bones[bone].rotation_mode = "QUATERNION"
    obj.animation_data.action = action


def replace_keys(action, frames, values):
    """Keys of `action` at `frames` set to `values` (pose_values); every other key kept as it is."""
    for bone, (quaternions, location) in values.items():
        before = [action.fcurves.find(bone_path(bone, "rotation_quaternion"), index=i) for i in range(4)]
        if all(before):  # the sign the frame before has, so the curves do not swing the long way into the range
            q = np.array([fc.evaluate(float(frames[0] - 1)) for fc in before])
            if np.dot(q, quaternions[0]) < 0:
                quaternions = -quaternions
        channels = [("rotation_quaternion", quaternions)]
        if location is not None:
            channels.append(("location", location))
        for channel, v in channels:
            for i in range(v.shape[1]):
                path = bone_path(bone, channel)
                fc = action.fcurves.find(path, index=i) or action.fcurves.new(path, index=i, action_group=bone)
                n = len(fc.keyframe_points)
                co = np.empty(2 * n, dtype=np.float64)
                fc.keyframe_points.foreach_get("co", co)
                x = co[0::2]
                at = np.minimum(np.searchsorted(x, frames), max(n - 1, 0))
                found = (x[at] == frames) if n else np.zeros(len(frames), dtype=bool)
                y = co[1::2]
                y[at[found]] = v[found, i]
                fc.keyframe_points.foreach_set("co", co)
                for f, value in zip(frames[~found], v[~found, i]):
                    fc.keyframe_points.insert(float(f), float(value), options={"FAST"})
                fc.update()


def create_armature(context, name, joint_names, parents, offsets):
    """A new armature object of gmg's skeleton (Y-up offsets), Z-up, each bone from its joint
    towards its children (a leaf continues its parent's direction)."""
    parents = np.asarray(parents)
    position = np.zeros((len(joint_names), 3))
    for j, p in enumerate(parents):
        position[j] = (position[p] if p >= 0 else 0) + offsets[j]
    heads = rot.rotate(rot.Y_UP_TO_Z_UP, position)
    extent = float(np.max(np.ptp(heads, axis=0))) if len(heads) > 1 else 1.0
    shortest = max(extent, 1e-3) * 0.02
    tails = heads + np.array([0.0, 0.0, shortest * 4])
    children = [[] for _ in joint_names]
    for j, p in enumerate(parents):
        if p >= 0:
            children[p].append(j)
    for j in range(len(joint_names)):
        if children[j]:
            toward = heads[children[j]].mean(axis=0)
        elif parents[j] >= 0:
            toward = heads[j] + (heads[j] - heads[parents[j]]) * 0.5
        else:
            continue
        if np.linalg.norm(toward - heads[j]) > shortest:
            tails[j] = toward
    if context.object is not None and context.object.mode != "OBJECT":
        bpy.ops.object.mode_set(mode="OBJECT")
    data = bpy.data.armatures.new(name)
    obj = bpy.data.objects.new(name, data)
    try:
        context.scene.collection.objects.link(obj)
        for other in context.view_layer.objects.selected:
            other.select_set(False)
        context.view_layer.objects.active = obj
        obj.select_set(True)
        bpy.ops.object.mode_set(mode="EDIT")
        bones = []
        for j, joint in enumerate(joint_names):
            b = data.edit_bones.new(joint)
            b.head = heads[j]
            b.tail = tails[j]
            b.use_connect = False
            if parents[j] >= 0:
                b.parent = bones[parents[j]]
            bones.append(b)
        bpy.ops.object.mode_set(mode="OBJECT")
    except Exception:
        bpy.data.objects.remove(obj)
        bpy.data.armatures.remove(data)
        raise
    return obj
