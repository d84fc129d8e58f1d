"""gmg for Blender: reenact a speaker's gestures for new speech on an armature.

Import a motion (BVH, BEAT2 .npz), build a gmg graph from an armature's action and its speech,
reenact new speech as a new action, regenerate a range of frames. Needs the gmg Python module
(built with gmg; `cmake --install` puts it in site-packages).
"""
import bpy
from bpy.props import FloatProperty, PointerProperty, StringProperty

from . import operators, panel

bl_info = {
    "name": "gmg: gestures from speech",
    "author": "gmg",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D View > Sidebar > gmg",
    "description": "Reenact a speaker's gestures for new speech on an armature (gesture motion graph)",
    "category": "Animation",
}


class GmgPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    module_dir: StringProperty(name="gmg module folder", subtype="DIR_PATH",
                               description="the folder holding gmg.*.so, when Blender's Python does not find it "
                                           "(e.g. <prefix>/lib/python3.11/site-packages)")

    def draw(self, context):
        self.layout.prop(self, "module_dir")


def _progress(self):
    return operators.State.progress


_classes = (GmgPreferences,) + operators.classes + panel.classes


def register():
    for c in _classes:
        bpy.utils.register_class(c)
    bpy.types.Scene.gmg = PointerProperty(type=panel.GmgSettings)
    bpy.types.WindowManager.gmg_progress = FloatProperty(name="Progress", subtype="FACTOR", min=0.0, max=1.0,
                                                         get=_progress)


def unregister():
    del bpy.types.WindowManager.gmg_progress
    del bpy.types.Scene.gmg
    for c in reversed(_classes):
        bpy.utils.unregister_class(c)
