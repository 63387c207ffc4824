"""The Radiosity panel, in Properties > Render and in the 3D View's sidebar (N)."""

import textwrap

import bpy

from . import preview
from .engine import auto_settings

# Average width of a label character at UI scale 1, in pixels (Blender's default interface font).
CHARACTER_PIXELS = 7.0


def wrapped_lines(text, context):
    """`text` cut into lines that fit the panel's width (labels do not wrap by themselves); one
    line where there is no region to measure, as in the background."""
    region = getattr(context, "region", None)
    if region is None or region.width <= 0:
        return [text]
    preferences = context.preferences
    scale = preferences.system.ui_scale or preferences.view.ui_scale  # the first is 0 without a window
    characters = int(region.width / (CHARACTER_PIXELS * scale))
    return textwrap.wrap(text, max(characters - 4, 16)) or [text]


def draw_panel(layout, context):
    settings = context.scene.radiosity
    layout.use_property_split = True
    layout.use_property_decorate = False
    row = layout.row()
    row.scale_y = 1.5
    row.operator("radiosity.bake", icon="RENDER_STILL")
    showing = preview.is_active(context.scene)
    layout.operator("radiosity.preview", text="Restore Shading" if showing else "Preview Bake",
                    icon="HIDE_OFF" if showing else "SHADING_SOLID", depress=showing)
    row = layout.row(align=True)
    row.operator("radiosity.wire", icon="NODETREE")
    row.operator("radiosity.unwire", icon="X")
    if settings.last_report:
        box = layout.box().column(align=True)
        for number, line in enumerate(wrapped_lines(settings.last_report, context)):
            box.label(text=line, icon="INFO" if number == 0 else "BLANK1")
        # Residual, energy balance and error estimate, each on lines of its own.
        for part in settings.last_accuracy.split("; ") if settings.last_accuracy else ():
            for line in wrapped_lines(part, context):
                box.label(text=line)
        for line in wrapped_lines(settings.last_cost, context) if settings.last_cost else ():
            box.label(text=line)

    column = layout.column()
    column.prop(settings, "quality")
    preset = auto_settings.PRESETS.get(settings.quality)
    if preset is None:
        column.prop(settings, "method")
        column.prop(settings, "element_size")
        column.prop(settings, "hemicube_resolution", text="Resolution")
        column.prop(settings, "tolerance")
        if settings.method == "HIERARCHICAL":
            column.prop(settings, "refine_tolerance")
        column.prop(settings, "max_iterations")
    elif settings.final_gather and settings.target == "ORIGINAL":
        gathered = preset.gathered
        near_field = ", near field" if gathered.near_field else ""
        column.label(text="Elements 1/%d of the scene, resolution from the scene (%g cells)%s, final gather %d rays, "
                          "tolerance %g" % (gathered.divisions, gathered.cells, near_field, gathered.rays,
                                            preset.tolerance))
    else:
        near_field = ", near field" if preset.near_field else ""
        column.label(text="Elements 1/%d of the scene, resolution from the scene (%g cells)%s, tolerance %g, "
                          "refinement %g" % (preset.divisions, preset.cells, near_field,
                                             preset.tolerance, preset.refine_tolerance))
    column.prop(settings, "final_gather")
    column.prop(settings, "memory_budget", text="Memory Budget (MB)")
    column.prop(settings, "hard_edge_angle")
    column.separator()
    column.prop(settings, "target")
    if settings.target == "ORIGINAL":
        column.prop(settings, "separate_linked_duplicates")
        column.prop(settings, "make_linked_local")
    column.prop(settings, "attribute_name")
    column.prop(settings, "write_light_only")
    column.prop(settings, "light_group_layers")
    draw_light_mix(layout, settings)
    column.separator()
    column.prop(settings, "zone_size")
    column.prop(settings, "media_folder")


def draw_light_mix(layout, settings):
    """Each light group layer of the last bake with its strength and tint, and Apply Light Mix."""
    if not len(settings.light_layers):
        return
    box = layout.box().column(align=True)
    box.label(text="Light Mix (live where wired)")
    for layer in settings.light_layers:
        row = box.row(align=True)
        row.label(text=layer.group or "(no group)")
        row.prop(layer, "strength", text="")
        row.prop(layer, "tint", text="")
    box.operator("radiosity.apply_light_mix", icon="CHECKMARK")


class RADIOSITY_PT_render(bpy.types.Panel):
    bl_label = "Radiosity"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"

    def draw(self, context):
        draw_panel(self.layout, context)


class RADIOSITY_PT_view3d(bpy.types.Panel):
    bl_label = "Radiosity"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Radiosity"

    def draw(self, context):
        draw_panel(self.layout, context)


CLASSES = (RADIOSITY_PT_render, RADIOSITY_PT_view3d)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)


def unregister():
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
