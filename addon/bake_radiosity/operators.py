"""The "Bake Radiosity" operator. Interactively the core runs in a worker thread while a timer
keeps the status bar (and, for progressive refinement, the viewport) up to date; Esc cancels.
Nothing is written until the solve has succeeded, so a cancelled or failed bake changes nothing,
and a finished bake is one undo step."""

import threading

import bpy

from . import light_mix, overlay, pipeline, preview, wiring
from .engine import native
from .engine.progress_view import ProgressView

_running = None  # the operator instance baking now; one bake at a time


class _Worker:
    """Runs the solve off the main thread. The core reports into a ProgressMonitor, which the
    modal timer polls: a Python callback would need the GIL, which Blender's main thread holds
    most of the time, and would stall the core at every report."""

    def __init__(self, job, want_layout):
        self.job = job
        self.want_layout = want_layout
        self.layout = None
        self.monitor = native.core().ProgressMonitor()
        self.cancelled = False
        self.error = None
        self.done = False
        self.thread = threading.Thread(target=self._run, name="Bake Radiosity", daemon=True)

    def cancel(self):
        self.monitor.cancel()

    def _run(self):
        core = native.core()
        try:
            if self.want_layout:
                self.layout = self.job.element_layout()
            if not self.monitor.cancelled:
                self.job.solve(progress=self.monitor)
            self.cancelled = self.monitor.cancelled
        except core.Cancelled:
            self.cancelled = True
        except Exception as error:  # reported to the artist in the main thread
            self.error = error
        finally:
            self.done = True


class RADIOSITY_OT_bake(bpy.types.Operator):
    bl_idname = "radiosity.bake"
    bl_label = "Bake Radiosity"
    bl_description = ("Bake diffuse light (radiosity) of what Cycles renders into a colour attribute. "
                      "Esc cancels")
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return context.scene is not None and _running is None

    def execute(self, context):
        try:
            summary = pipeline.bake(context.scene)
        except (pipeline.BakeError, native.CoreMissingError) as error:
            self.report({"ERROR"}, "Bake Radiosity failed: %s" % error)
            return {"CANCELLED"}
        for warning in summary["warnings"]:
            self.report({"WARNING"}, warning)
        self.report({"INFO"}, "Bake Radiosity: " + context.scene.radiosity.last_report)
        self.report({"INFO"}, "Bake Radiosity: " + context.scene.radiosity.last_accuracy)
        return {"FINISHED"}

    def invoke(self, context, event):
        global _running
        if bpy.app.background:
            return self.execute(context)
        try:
            native.core()
            view_layer, depsgraph = pipeline.view_layer_and_depsgraph(context.scene)
            job = pipeline.BakeJob(context.scene, depsgraph, view_layer)
        except (pipeline.BakeError, native.CoreMissingError) as error:
            self.report({"ERROR"}, "Bake Radiosity failed: %s" % error)
            return {"CANCELLED"}
        self._scene_name = context.scene.name
        self._worker = _Worker(job, want_layout=job.method == "progressive")
        self._overlay = None
        self._progress = ProgressView(job.choice.tolerance)
        self._worker.thread.start()
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.2, window=context.window)
        wm.modal_handler_add(self)
        _running = self
        self._set_status(context, "Bake Radiosity: preparing %d faces - Esc to cancel" % job.exported.polygon_count)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        worker = self._worker
        if event.type == "ESC" and event.value == "PRESS":
            worker.cancel()
            self._set_status(context, "Bake Radiosity: cancelling...")
            return {"RUNNING_MODAL"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        if worker.done:
            return self._finish(context)
        self._show_progress(context)
        return {"PASS_THROUGH"}

    def cancel(self, context):
        # Blender ends the operator (e.g. a file is loaded): stop the core and drop its result.
        self._worker.cancel()
        self._worker.thread.join()
        self._cleanup(context)

    def _show_progress(self, context):
        if self._worker.monitor.cancelled:
            return  # keep saying "cancelling..." until the core stops
        if self._worker.layout is not None and self._overlay is None:
            self._overlay = overlay.ProgressOverlay(*self._worker.layout)
        text, radiance = self._progress.tick(self._worker.monitor, preview=self._overlay is not None)
        if text is not None:
            self._set_status(context, text + " - Esc to cancel")
        if radiance is not None:
            self._overlay.show(radiance)

    def _finish(self, context):
        worker = self._worker
        self._cleanup(context)
        if worker.cancelled:
            self.report({"INFO"}, "Bake Radiosity cancelled; nothing was changed")
            return {"CANCELLED"}
        if worker.error is not None:
            self.report({"ERROR"}, "Bake Radiosity failed: %s" % worker.error)
            return {"CANCELLED"}
        scene = bpy.data.scenes.get(self._scene_name)
        if scene is None:
            self.report({"ERROR"}, "Bake Radiosity: the baked scene was removed")
            return {"CANCELLED"}
        try:
            summary = worker.job.write(scene)
        except pipeline.BakeError as error:
            self.report({"ERROR"}, "Bake Radiosity failed: %s" % error)
            return {"CANCELLED"}
        for warning in summary["warnings"]:
            self.report({"WARNING"}, warning)
        self.report({"INFO"}, "Bake Radiosity: " + scene.radiosity.last_report)
        self.report({"INFO"}, "Bake Radiosity: " + scene.radiosity.last_accuracy)
        return {"FINISHED"}

    def _cleanup(self, context):
        global _running
        context.window_manager.event_timer_remove(self._timer)
        if self._overlay is not None:
            self._overlay.remove()
            self._overlay = None
        self._set_status(context, None)
        _running = None

    @staticmethod
    def _set_status(context, text):
        if context.workspace is not None:
            context.workspace.status_text_set(text)


class RADIOSITY_OT_preview(bpy.types.Operator):
    bl_idname = "radiosity.preview"
    bl_label = "Preview Radiosity"
    bl_description = ("Show the baked light in the viewport (solid shading by colour attribute, and a "
                      "material preview that emits it); click again to restore your shading and materials")
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        if preview.is_active(context.scene):
            preview.restore(context)
        else:
            message = preview.show(context)
            if message:
                self.report({"WARNING"}, message)
        return {"FINISHED"}


class RADIOSITY_OT_wire(bpy.types.Operator):
    bl_idname = "radiosity.wire"
    bl_label = "Wire Baked Light"
    bl_description = ("Put the baked light into the baked objects' materials, for Material Preview and renders: "
                      "an emission of the light-only attribute times the material's colour (or texture), or of the "
                      "baked attribute itself")
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        if preview.is_active(context.scene):
            self.report({"WARNING"}, "Restore Shading first: the preview has replaced the materials to wire")
            return {"CANCELLED"}
        wired, messages = wiring.wire(context.scene)
        for message in messages:
            self.report({"WARNING"}, message)
        if wired:
            self.report({"INFO"}, "Wired the baked light into %d material(s)" % wired)
        return {"FINISHED"} if wired else {"CANCELLED"}


class RADIOSITY_OT_unwire(bpy.types.Operator):
    bl_idname = "radiosity.unwire"
    bl_label = "Unwire Baked Light"
    bl_description = "Remove exactly the nodes and links Wire Baked Light added, restoring the materials"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        count = wiring.unwire(context.scene)
        self.report({"INFO"}, "Unwired %d material(s)" % count)
        return {"FINISHED"}


class RADIOSITY_OT_apply_light_mix(bpy.types.Operator):
    bl_idname = "radiosity.apply_light_mix"
    bl_label = "Apply Light Mix"
    bl_description = ("Write the light group layers' current mix (their strengths and tints) into the baked "
                      "attribute, as if baked so; one undo step")
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return len(context.scene.radiosity.light_layers) > 0

    def execute(self, context):
        count = light_mix.apply_mix(context.scene)
        if not count:
            self.report({"WARNING"}, "No mesh in this scene holds the light group layers of the last bake")
            return {"CANCELLED"}
        self.report({"INFO"}, "Wrote the light mix into %d mesh(es)" % count)
        return {"FINISHED"}


CLASSES = (RADIOSITY_OT_bake, RADIOSITY_OT_preview, RADIOSITY_OT_wire, RADIOSITY_OT_unwire,
           RADIOSITY_OT_apply_light_mix)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)


def unregister():
    global _running
    if _running is not None:
        _running._worker.cancel()
        _running._worker.thread.join()
        _running = None
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
