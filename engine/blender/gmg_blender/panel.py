"""The sidebar panel (3D view › sidebar › gmg) and the settings it keeps on the scene."""
import bpy
from bpy.props import BoolProperty, FloatProperty, IntProperty, StringProperty

from .operators import State, gmg_module


def _engine_speech_weight(settings, context):
    # Ticking the box starts from gmg's own default, which lives in the engine's config.
    if settings.set_speech_weight:
        try:
            settings.speech_weight = gmg_module().config()["speech_weight"]
        except Exception:  # no module: the panel's error comes when an operator runs
            pass


class GmgSettings(bpy.types.PropertyGroup):
    graph: StringProperty(name="Graph", subtype="FILE_PATH", default="//speaker.gmg",
                          description="the graph file Build writes and Reenact reads")
    audio: StringProperty(name="Audio", subtype="FILE_PATH", description="speech: the reference's for Build, "
                          "the new one for Reenact")
    transcript: StringProperty(name="Transcript", subtype="FILE_PATH", description="its words; optional")
    seed: IntProperty(name="Seed", min=0, default=1)
    set_speech_weight: BoolProperty(name="Speech weight", update=_engine_speech_weight,
                                    description="set gmg's speech_weight (else its default)")
    speech_weight: FloatProperty(name="", min=0.0, max=1000.0, description="sync against smoothness")
    regen_start: IntProperty(name="From", default=1)
    regen_end: IntProperty(name="To", default=30)


def _speech(op, settings):
    op.audio, op.transcript = settings.audio, settings.transcript
    if settings.set_speech_weight:
        op.speech_weight = settings.speech_weight


class GMG_PT_panel(bpy.types.Panel):
    bl_label = "gmg"
    bl_idname = "GMG_PT_panel"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "gmg"

    def draw(self, context):
        layout = self.layout
        s = context.scene.gmg
        layout.operator("gmg.import_motion", icon="IMPORT")
        col = layout.column(align=True)
        col.prop(s, "audio")
        col.prop(s, "transcript")
        col.prop(s, "graph")
        op = layout.operator("gmg.build", icon="OUTLINER_DATA_ARMATURE")
        _speech(op, s)
        op.filepath = s.graph
        row = layout.row(align=True)
        row.prop(s, "seed")
        row = layout.row(align=True)
        row.prop(s, "set_speech_weight")
        sub = row.row()
        sub.enabled = s.set_speech_weight
        sub.prop(s, "speech_weight")
        op = layout.operator("gmg.reenact", icon="PLAY_SOUND")
        _speech(op, s)
        op.graph, op.seed = s.graph, s.seed
        row = layout.row(align=True)
        row.prop(s, "regen_start")
        row.prop(s, "regen_end")
        op = layout.operator("gmg.regenerate", icon="FILE_REFRESH")
        op.frame_start, op.frame_end, op.seed = s.regen_start, s.regen_end, s.seed
        if s.set_speech_weight:
            op.speech_weight = s.speech_weight
        job = State.job
        if job is not None:
            box = layout.box()
            box.label(text=f"{job.label}: {job.elapsed():.0f} s (Esc cancels)", icon="TIME")
            box.prop(context.window_manager, "gmg_progress", text="", slider=True)


classes = (GmgSettings, GMG_PT_panel)
