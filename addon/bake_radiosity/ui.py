"""The Radiosity panel, in Properties > Render and in the 3D View's sidebar (N)."""

import bpy

from . import auto_settings, preview


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
    if settings.last_report:
        box = layout.box()
        box.label(text=settings.last_report, icon="INFO")
        # Residual, energy balance and error estimate, one line each.
        for part in settings.last_accuracy.split("; ") if settings.last_accuracy else ():
            box.label(text=part)

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
    else:
        column.label(text="Elements 1/%d of the scene, resolution from the scene (%g cells)%s, tolerance %g, "
                          "refinement %g" % (preset.divisions, preset.cells, ", near field" if preset.near_field else "",
                                             preset.tolerance, preset.refine_tolerance))
    column.prop(settings, "memory_budget", text="Memory Budget (MB)")
    column.prop(settings, "hard_edge_angle")
    column.separator()
    column.prop(settings, "target")
    column.prop(settings, "attribute_name")
    column.separator()
    column.prop(settings, "zone_size")
    column.prop(settings, "media_folder")


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
