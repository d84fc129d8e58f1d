"""The add-on's operators: import a motion, build a graph from an armature, reenact speech on it,
regenerate a range of frames. Each reads Blender's data in the main thread, lets the gmg module
work (in a thread when invoked from the interface, to the end when executed: scripts and
`blender -b`), then writes Blender's data in the main thread. A refusal or an error is the
operator's report and changes nothing: the armature keeps the action it had.
"""
import os
import sys
import tempfile

import bpy
import numpy as np
from bpy.props import FloatProperty, IntProperty, StringProperty

from . import armature
from .armature import AddonError
from .jobs import Job


def gmg_module():
    """The gmg Python module: from Blender's sys.path, else the folder the add-on's preferences name."""
    try:
        import gmg
        return gmg
    except ImportError:
        pass
    addon = bpy.context.preferences.addons.get(__package__)
    folder = bpy.path.abspath(addon.preferences.module_dir) if addon else ""
    if folder and folder not in sys.path:
        sys.path.append(folder)
    try:
        import gmg
        return gmg
    except ImportError as e:
        raise AddonError("the gmg Python module is not found (" + str(e) + "): install gmg with `cmake --install`, "
                         "then give the folder holding gmg.*.so in the add-on's preferences") from e


class State:
    """The job running from the interface (one at a time), for the panel and the operators' poll."""
    job = None
    progress = 0.0


def path_of(text, what, must_exist=True):
    if not text:
        raise AddonError(f"{what}: no file given")
    path = bpy.path.abspath(text)
    if must_exist and not os.path.isfile(path):
        raise AddonError(f"{what}: {path}: no such file")
    return path


def active_armature(context, need_action=True):
    obj = context.active_object
    if obj is None or obj.type != "ARMATURE":
        raise AddonError("select an armature (the active object is " +
                         ("none" if obj is None else f"'{obj.name}', a {obj.type.lower()}") + ")")
    if need_action and (obj.animation_data is None or obj.animation_data.action is None):
        raise AddonError(f"armature '{obj.name}' has no action")
    return obj


def scene_fps(scene):
    return scene.render.fps / scene.render.fps_base


def set_scene_fps(scene, fps):
    whole = max(1, int(round(fps)))
    scene.render.fps = whole
    scene.render.fps_base = whole / fps


def overrides(op):
    """The engine parameters the operator was given (`set=` of gmg.build and gmg.reenact)."""
    return {"speech_weight": op.speech_weight} if op.properties.is_property_set("speech_weight") else None


def armature_named(name):
    obj = bpy.data.objects.get(name)
    if obj is None or obj.type != "ARMATURE":
        raise AddonError(f"armature '{name}' is gone")
    return obj


class ThreadedOperator:
    """execute: runs the job to the end. invoke: in a thread, the interface responsive, Esc cancels."""

    def make_job(self, context):
        raise NotImplementedError

    @classmethod
    def poll(cls, context):
        return State.job is None

    def execute(self, context):
        try:
            message = self.make_job(context).run_here()
        except Exception as e:  # gmg.Error and the add-on's refusals: the report names the file
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, message)
        return {"FINISHED"}

    def invoke(self, context, event):
        if bpy.app.background:
            return self.execute(context)
        try:
            job = self.make_job(context)
        except Exception as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        State.job, State.progress = job, 0.1
        job.start()
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def _end(self, context):
        context.window_manager.event_timer_remove(self._timer)
        State.job, State.progress = None, 0.0
        for area in context.screen.areas if context.screen else []:
            area.tag_redraw()

    def modal(self, context, event):
        job = State.job
        if event.type == "ESC":
            job.cancel()
            self._end(context)
            self.report({"WARNING"}, f"{job.label} cancelled: nothing changed")
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        for area in context.screen.areas if context.screen else []:
            if area.type == "VIEW_3D":
                area.tag_redraw()
        if not job.done():
            return {"PASS_THROUGH"}
        State.progress = 0.9
        try:
            message = job.finish()
        except Exception as e:
            self._end(context)
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self._end(context)
        self.report({"INFO"}, message)
        return {"FINISHED"}


class GMG_OT_import_motion(bpy.types.Operator):
    """Import a BVH (or a BEAT2 .npz with a BVH skeleton) as a new armature with one action"""
    bl_idname = "gmg.import_motion"
    bl_label = "Import Motion (gmg)"
    bl_options = {"REGISTER", "UNDO"}

    filepath: StringProperty(name="File", subtype="FILE_PATH")
    filter_glob: StringProperty(default="*.bvh;*.npz", options={"HIDDEN"})
    skeleton: StringProperty(name="Skeleton", description="BVH whose hierarchy gives an .npz its skeleton",
                             subtype="FILE_PATH")

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        try:
            message = self.make_job(context).run_here()
        except Exception as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, message)
        return {"FINISHED"}

    def make_job(self, context):
        return import_job(context, self.filepath, self.skeleton)


def import_job(context, filepath, skeleton=""):
    """The work of gmg.import_motion (see the operator)."""
    gmg = gmg_module()
    path = path_of(filepath, "import")
    skeleton = path_of(skeleton, "skeleton") if skeleton else None
    scene = context.scene

    def work():
        m = gmg.read_motion(path, skeleton=skeleton)
        return m.joint_names, m.parents, m.offsets, m.rotations, m.root, m.fps

    def apply(result):
        names, parents, offsets, rotations, root, fps = result
        stem = os.path.splitext(os.path.basename(path))[0]
        obj = armature.create_armature(context, stem, names, parents, offsets)
        try:
            if [b.name for b in obj.data.bones] != list(names):
                raise AddonError(f"{path}: Blender cannot name every bone after its joint (a name over 63 bytes?)")
            values = armature.pose_values(obj, names, rotations, root)
            frames = np.arange(len(root)) + scene.frame_start
            action = armature.key_new_action(obj, stem, frames, values)
        except Exception:
            bpy.data.objects.remove(obj)
            raise
        armature.use_action(obj, action, names)
        set_scene_fps(scene, fps)
        scene.frame_end = int(frames[-1])
        return f"imported {path}: {len(names)} joints, {len(root)} frames at {fps:g} fps"

    return Job("import", work, apply)


class SpeechProperties:
    audio: StringProperty(name="Audio", subtype="FILE_PATH", description="the speech (WAV, FLAC, MP3, ...)")
    transcript: StringProperty(name="Transcript", subtype="FILE_PATH",
                               description="its words (.TextGrid, .tsv, .json); optional")
    speech_weight: FloatProperty(name="Speech weight", min=0.0, max=1000.0,
                                 description="sync against smoothness (gmg's speech_weight); gmg's default if unset")


class GMG_OT_build(ThreadedOperator, SpeechProperties, bpy.types.Operator):
    """Build a gmg graph from the active armature's action and its speech, and save it"""
    bl_idname = "gmg.build"
    bl_label = "Build Graph"

    filepath: StringProperty(name="Graph", subtype="FILE_PATH", description="the graph file to write (.gmg)")

    def make_job(self, context):
        return build_job(context, self.audio, self.transcript, self.filepath, overrides(self))


def build_job(context, audio, transcript, filepath, settings=None):
    """The work of gmg.build (see the operator); settings: gmg parameters, as gmg.build's set=."""
    gmg = gmg_module()
    obj = active_armature(context)
    audio = path_of(audio, "audio")
    transcript = path_of(transcript, "transcript") if transcript else None
    out = path_of(filepath, "graph", must_exist=False)
    action = obj.animation_data.action
    arrays = armature.motion_arrays(obj, action, armature.action_frames(action))
    fps, label = scene_fps(context.scene), action.name
    scene_name = context.scene.name

    def work():
        motion = gmg.Motion(*arrays, fps, name=label)
        try:
            graph = gmg.build(motion=motion, audio=audio, transcript=transcript, set=settings)
        except gmg.Error as e:  # gmg names the clip by its motion, here the action: name the files too
            inputs = ", ".join(p for p in (audio, transcript) if p)
            raise AddonError(f"{e} (building from action '{label}' with {inputs})") from e
        graph.save(out)
        return graph.stats()

    def apply(stats):
        scene = bpy.data.scenes.get(scene_name)
        if scene is not None:
            scene.gmg.graph = out
        return (f"wrote {out}: {stats['frames']} frames, {stats['onset_nodes']} onset, "
                f"{stats['keyword_nodes']} keyword nodes, {stats['unnatural_edges']} transitions")

    return Job("build", work, apply)


def add_speech_strip(scene, audio, start):
    if scene.sequence_editor is None:
        scene.sequence_editor_create()
    strips = scene.sequence_editor.sequences
    old = strips.get("gmg speech")
    if old is not None:
        strips.remove(old)
    channel = 1 + max((s.channel for s in strips), default=0)
    strips.new_sound("gmg speech", audio, channel, start)


class GMG_OT_reenact(ThreadedOperator, SpeechProperties, bpy.types.Operator):
    """Reenact gestures for new speech on the active armature: a new action from the scene's start frame"""
    bl_idname = "gmg.reenact"
    bl_label = "Reenact"
    bl_options = {"REGISTER", "UNDO"}

    graph: StringProperty(name="Graph", subtype="FILE_PATH", description="a graph file (.gmg)")
    seed: IntProperty(name="Seed", min=0, description="another seed, another motion for the same speech")

    def make_job(self, context):
        return reenact_job(context, self.graph, self.audio, self.transcript, self.seed, overrides(self))


def reenact_job(context, graph, audio, transcript, seed, settings=None):
    """The work of gmg.reenact (see the operator)."""
    gmg = gmg_module()
    obj = active_armature(context, need_action=False)
    graph = path_of(graph, "graph")
    audio = path_of(audio, "audio")
    transcript = path_of(transcript, "transcript") if transcript else None
    name = obj.name
    scene = context.scene
    bones = {b.name for b in obj.data.bones}

    def work():
        r = gmg.reenact(graph, audio, transcript, seed=seed, set=settings)
        names = r.motion.joint_names
        missing = [n for n in names if n not in bones]
        if missing:
            raise AddonError(f"{graph}: armature '{name}' lacks {len(missing)} of the graph's joints "
                             f"({', '.join(missing[:5])})")
        return names, r.rotations, r.root, r.fps

    def apply(result):
        names, rotations, root, fps = result
        obj = armature_named(name)
        values = armature.pose_values(obj, names, rotations, root)
        start = scene.frame_start
        frames = np.arange(len(root)) + start
        stem = os.path.splitext(os.path.basename(audio))[0]
        action = armature.key_new_action(obj, f"gmg {stem} seed {seed}", frames, values)
        action["gmg_graph"], action["gmg_audio"] = graph, audio
        action["gmg_transcript"] = transcript or ""
        action["gmg_seed"], action["gmg_start"], action["gmg_frames"] = seed, start, len(root)
        armature.use_action(obj, action, names)
        set_scene_fps(scene, fps)
        scene.frame_end = int(frames[-1])
        add_speech_strip(scene, audio, start)
        return f"reenacted {audio} with seed {seed}: action '{action.name}', frames {start} to {frames[-1]}"

    return Job("reenact", work, apply)


class GMG_OT_regenerate(ThreadedOperator, bpy.types.Operator):
    """Plan the frames from frame_start to frame_end of the active armature's gmg action afresh, keeping the rest"""
    bl_idname = "gmg.regenerate"
    bl_label = "Regenerate Range"
    bl_options = {"REGISTER", "UNDO"}

    frame_start: IntProperty(name="From frame")
    frame_end: IntProperty(name="To frame", description="the last frame planned afresh")
    seed: IntProperty(name="Seed", min=0)
    speech_weight: SpeechProperties.__annotations__["speech_weight"]

    def make_job(self, context):
        return regenerate_job(context, self.frame_start, self.frame_end, self.seed, overrides(self))


def regenerate_job(context, frame_start, frame_end, seed, settings=None):
    """The work of gmg.regenerate (see the operator)."""
    gmg = gmg_module()
    if "keep" not in (gmg.reenact.__doc__ or ""):
        raise AddonError("this gmg module cannot regenerate a range (gmg.reenact has no keep=, ranges=): "
                         "update gmg")
    obj = active_armature(context)
    action = obj.animation_data.action
    if "gmg_graph" not in action:
        raise AddonError(f"action '{action.name}' was not made by gmg's reenact: nothing to regenerate")
    start, count = int(action["gmg_start"]), int(action["gmg_frames"])
    if not start <= frame_start <= frame_end < start + count:
        raise AddonError(f"action '{action.name}': frames {frame_start} to {frame_end} are not within "
                         f"its frames {start} to {start + count - 1}")
    graph, audio = action["gmg_graph"], action["gmg_audio"]
    transcript = action["gmg_transcript"] or None
    fps = scene_fps(context.scene)
    arrays = armature.motion_arrays(obj, action, np.arange(start, start + count))
    first, last = frame_start - start, frame_end - start
    span = ((first / fps, (last + 1) / fps),)
    name, action_name = obj.name, action.name

    def work():
        # The kept motion in the graph's own skeleton (its joints, in its order, with its offsets),
        # as gmg reenact --keep wants it; the armature may have bones the graph has not.
        g = gmg.load(graph)
        skeleton = g.motion
        index = {n: j for j, n in enumerate(arrays[0])}
        missing = [n for n in skeleton.joint_names if n not in index]
        if missing:
            raise AddonError(f"{graph}: armature '{name}' lacks {len(missing)} of the graph's joints "
                             f"({', '.join(missing[:5])})")
        order = [index[n] for n in skeleton.joint_names]
        kept = skeleton.with_frames(rotations=arrays[3][:, order], root=arrays[4], fps=fps)
        with tempfile.TemporaryDirectory(prefix="gmg_blender_") as folder:
            prev = os.path.join(folder, "kept.bvh")
            kept.write(prev)
            r = gmg.reenact(g, audio, transcript, keep=prev, ranges=list(span), seed=seed, set=settings)
            return r.motion.joint_names, r.rotations[first:last + 1], r.root[first:last + 1]

    def apply(result):
        names, rotations, root = result
        obj = armature_named(name)
        act = bpy.data.actions.get(action_name)
        if act is None:
            raise AddonError(f"action '{action_name}' is gone")
        values = armature.pose_values(obj, names, rotations, root)
        armature.replace_keys(act, np.arange(first, last + 1) + start, values)
        return f"regenerated frames {first + start} to {last + start} of '{action_name}' with seed {seed}"

    return Job("regenerate", work, apply)


classes = (GMG_OT_import_motion, GMG_OT_build, GMG_OT_reenact, GMG_OT_regenerate)
