"""The gmg add-on from Blender's interface (run by tests/blender/blender_test.sh ... panel, under a
virtual X display): the panel draws, Build and Reenact invoked as the panel's buttons invoke them
run in a thread while Blender's event loop goes on, and a reenact cancelled with Esc changes
nothing. Prints PASS: or FAIL: (an interface session has no exit code of its own).
Usage: blender --factory-startup --enable-event-simulate --python-use-system-env --python panel_test.py --
       ZIP DATA_DIR WORK_DIR
"""
import os
import sys
import traceback

import bpy

zip_path, data, work = sys.argv[sys.argv.index("--") + 1:]
bpy.context.preferences.filepaths.temporary_directory = work  # where quitting leaves its recovery file
bpy.ops.preferences.addon_install(filepath=zip_path)
bpy.ops.preferences.addon_enable(module="gmg_blender")
import gmg_blender.operators as ops  # noqa: E402
import gmg_blender.panel as panel  # noqa: E402

# The panel shown in the sidebar's first tab, so that it draws without a click; its draws counted.
bpy.utils.unregister_class(panel.GMG_PT_panel)
panel.GMG_PT_panel.bl_category = "Item"
drawn = {"times": 0}
draw = panel.GMG_PT_panel.draw


def counted_draw(self, context):
    draw(self, context)
    drawn["times"] += 1


panel.GMG_PT_panel.draw = counted_draw
bpy.utils.register_class(panel.GMG_PT_panel)

ref = os.path.join(data, "2_scott_0_1_1")
new = os.path.join(data, "2_scott_0_2_2")
graph = os.path.join(work, "G.gmg")
step = {"n": 0, "ticks": 0}


def view3d():
    win = bpy.context.window_manager.windows[0]
    area = next(a for a in win.screen.areas if a.type == "VIEW_3D")
    area.spaces[0].show_region_ui = True
    return win, dict(window=win, screen=win.screen, area=area,
                     region=next(r for r in area.regions if r.type == "WINDOW"))


def finish(message):
    print(message, flush=True)
    bpy.ops.wm.quit_blender()


def tick():
    try:
        step["ticks"] += 1
        if step["ticks"] > 600:
            return finish(f"FAIL: still at step {step['n']} after 120 s")
        if ops.State.job is not None:
            return 0.2
        win, override = view3d()
        s = bpy.context.scene.gmg
        with bpy.context.temp_override(**override):
            n = step["n"]
            if n == 0:
                bpy.ops.gmg.import_motion("EXEC_DEFAULT", filepath=ref + ".bvh")
                s.audio, s.transcript, s.graph = ref + ".wav", ref + ".TextGrid", graph
                assert bpy.ops.gmg.build("INVOKE_DEFAULT", audio=s.audio, transcript=s.transcript,
                                         filepath=s.graph) == {"RUNNING_MODAL"}
                assert ops.State.job is not None and not bpy.ops.gmg.reenact.poll()  # one job at a time
            elif n == 1:
                assert os.path.isfile(graph) and s.graph == graph
                assert bpy.ops.gmg.reenact("INVOKE_DEFAULT", graph=graph, audio=new + ".wav",
                                           transcript=new + ".TextGrid", seed=7) == {"RUNNING_MODAL"}
            elif n == 2:
                obj = bpy.context.active_object
                assert obj.animation_data.action.name == "gmg 2_scott_0_2_2 seed 7", obj.animation_data.action.name
                step["actions"] = sorted(a.name for a in bpy.data.actions)
                started = bpy.ops.gmg.reenact("INVOKE_DEFAULT", graph=graph, audio=new + ".wav", seed=9)
                assert started == {"RUNNING_MODAL"}
                win.event_simulate(type="ESC", value="PRESS")
                win.event_simulate(type="ESC", value="RELEASE")
            elif n == 3:
                obj = bpy.context.active_object
                assert obj.animation_data.action.name == "gmg 2_scott_0_2_2 seed 7"
                assert sorted(a.name for a in bpy.data.actions) == step["actions"], "the cancelled reenact applied"
                assert drawn["times"] > 0, "the panel never drew"
                return finish(f"PASS: the panel drew ({drawn['times']} times), build and reenact ran in a thread, "
                              "Esc cancelled a reenact without change")
        step["n"] += 1
        return 0.5
    except Exception:
        traceback.print_exc()
        return finish("FAIL: see the traceback above")


bpy.app.timers.register(tick, first_interval=1.0)
