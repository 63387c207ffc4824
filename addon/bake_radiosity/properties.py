"""Bake settings stored on the scene (``scene.radiosity``) and saved with the .blend file."""

import math

import bpy
from bpy.props import (BoolProperty, CollectionProperty, EnumProperty, FloatProperty, FloatVectorProperty,
                       IntProperty, StringProperty)


def _switch_to_custom(settings, _context):
    # Setting one of the individual settings (from Python; the panel shows them only in Custom)
    # means the artist wants that value, which a preset would override.
    if settings.quality != "CUSTOM":
        settings.quality = "CUSTOM"


def _update_light_mix(_layer, context):
    from . import light_mix  # light_mix imports this module
    light_mix.update_mix(context.scene)


class RadiosityLightLayer(bpy.types.PropertyGroup):
    """One light group's baked layer and how the live mix weighs it."""
    group: StringProperty(name="Light Group", description="The light group ('' for lights without one)")
    attribute: StringProperty(name="Attribute", description="The colour attribute holding the layer")
    strength: FloatProperty(
        name="Strength", description="The layer's light times this in the mix that Wire Baked Light shows",
        default=1.0, min=0.0, soft_max=10.0, update=_update_light_mix)
    tint: FloatVectorProperty(
        name="Tint", description="The layer's light times this colour in the mix", subtype="COLOR", size=3,
        default=(1.0, 1.0, 1.0), min=0.0, soft_max=1.0, update=_update_light_mix)


class RadiositySettings(bpy.types.PropertyGroup):
    quality: EnumProperty(
        name="Quality",
        description="How fine and how exact the bake is. The presets choose element size (relative to "
                    "the scene's size), hemi-cube resolution (so that the smallest elements and lamps cover "
                    "enough cells), tolerance and method; Custom shows each",
        items=(
            ("DRAFT", "Draft", "Quick look: elements 1/16 of the scene's size, resolution for 4 cells, "
             "tolerance 1e-3, refinement 0.05"),
            ("MEDIUM", "Medium", "Most bakes: elements 1/32 of the scene's size, resolution for 6 cells, "
             "near-field correction, tolerance 1e-4, refinement 0.02"),
            ("HIGH", "High", "Final bakes: elements 1/48 of the scene's size, resolution for 8 cells, "
             "near-field correction, tolerance 1e-5, refinement 0.01"),
            ("CUSTOM", "Custom", "Set element size, resolution, tolerance and method yourself"),
        ),
        default="MEDIUM",
    )
    memory_budget: IntProperty(
        name="Memory Budget",
        description="Megabytes the table of form factors may take. Automatic method stores the table "
                    "(Gauss-Seidel) when its worst case fits, otherwise it bakes hierarchically, whose "
                    "elements and links stay within it too (refinement stops there)",
        default=2048, min=1, soft_max=65536, subtype="UNSIGNED",
    )
    method: EnumProperty(
        name="Method",
        description="How the radiosity equations are solved",
        items=(
            ("AUTO", "Automatic",
             "Gauss-Seidel when the form factors fit the memory budget, otherwise hierarchical (scenes "
             "with fog or smoke: progressive refinement)"),
            ("GAUSS_SEIDEL", "Gauss-Seidel",
             "Store every form factor once, then gather until converged. Fastest for small and medium scenes"),
            ("PROGRESSIVE", "Progressive Refinement",
             "Shoot light from the brightest patch, one hemi-cube at a time. Memory grows only linearly "
             "with the scene, and the viewport shows the solution brightening"),
            ("JACOBI", "Jacobi",
             "Like Gauss-Seidel but every element is updated from the previous sweep. Slower; for comparison"),
            ("HIERARCHICAL", "Hierarchical",
             "Split faces only where the light changes (shadow edges, corners), down to the element size, "
             "and let far groups of faces exchange light as one. Memory grows more slowly with the scene "
             "than the stored table's: for large scenes. Not for scenes with fog or smoke"),
        ),
        default="AUTO",
        update=_switch_to_custom,
    )
    hemicube_resolution: IntProperty(
        name="Hemi-cube Resolution",
        description="Cells along the edge of the hemi-cube's top face. Higher finds smaller and more "
                    "distant surfaces at the cost of time (64 quick look, 128 normal, 256 final)",
        # The core's largest hemi-cube (the presets average turned ones beyond it).
        default=128, min=16, max=1024, soft_max=512,
        update=_switch_to_custom,
    )
    element_size: FloatProperty(
        name="Element Size",
        description="Largest edge of the elements that faces are split into, in scene units. "
                    "0 keeps one element per face. Smaller gives sharper shadows and slower bakes",
        default=0.1, min=0.0, soft_max=2.0, subtype="DISTANCE", unit="LENGTH", precision=3,
        update=_switch_to_custom,
    )
    tolerance: FloatProperty(
        name="Tolerance",
        description="Stop when the remaining error of the solution, relative to the emitted light, "
                    "falls below this (1e-3 preview, 1e-4 final)",
        default=1e-4, min=1e-8, max=0.5, precision=6,
        update=_switch_to_custom,
    )
    refine_tolerance: FloatProperty(
        name="Refinement",
        description="Hierarchical method: how much error each exchange of light may carry, as a share "
                    "of the scene's mean brightness, before its faces are split further (0.05 quick look, "
                    "0.02 normal, 0.01 final). Smaller: finer shadows and more elements",
        default=0.02, min=1e-4, max=1.0, precision=4,
        update=_switch_to_custom,
    )
    max_iterations: IntProperty(
        name="Max Iterations",
        description="Give up after this many sweeps (Gauss-Seidel, Jacobi) or shots (progressive) "
                    "even if the tolerance is not reached",
        default=1000, min=1, soft_max=100000,
    )
    hard_edge_angle: FloatProperty(
        name="Hard Edge Angle",
        description="Faces meeting at a sharper angle than this keep their own colours at the shared "
                    "corner instead of blending (30 degrees suits most architecture)",
        default=math.radians(30.0), min=0.0, max=math.pi, subtype="ANGLE",
    )
    attribute_name: StringProperty(
        name="Attribute",
        description="Name of the face-corner colour attribute that receives the baked light",
        default="Radiosity",
    )
    write_light_only: BoolProperty(
        name="Also Write Light Only",
        description="Also write the light arriving without the surface's colour (irradiance / pi, as Cycles' Diffuse "
                    "bake with Direct and Indirect and without Color) into the attribute '<Attribute> Light': "
                    "multiplied by a texture in the shader, it lights the texture at full resolution",
        default=False,
    )
    light_group_layers: BoolProperty(
        name="Light Group Layers",
        description="Also write one colour attribute per light group that lights the scene ('<Attribute> <group>', "
                    "'<Attribute> (no group)' for lamps, emitters and the World without one), each the light of "
                    "that group alone with every bounce; they sum to the usual attribute. Wire Baked Light then "
                    "mixes them with the strengths and tints below, live (within the Memory Budget; not with fog or "
                    "smoke; hierarchically with the Final Gather)",
        default=False,
    )
    light_layers: CollectionProperty(type=RadiosityLightLayer, name="Light Layers",
                                     description="The light group layers of the last bake and their mix")
    light_layers_attribute: StringProperty(
        name="Layered Attribute", description="The attribute of the last bake with light group layers, which "
                                              "Apply Light Mix writes", default="")
    final_gather: BoolProperty(
        name="Final Gather",
        description="Light each corner of the meshes where it is: direct light from every lamp and emitter at the "
                    "corner itself, indirect light by rays into the solution. Several times more accurate at "
                    "contacts and corners for a few percent more time (Target: Original Meshes; the hierarchical "
                    "method gathers at its corners itself)",
        default=True,
    )
    separate_linked_duplicates: BoolProperty(
        name="Separate Linked Duplicates",
        description="Objects that share one mesh (linked duplicates, Alt+D) each get a mesh of their own when the "
                    "light is written, so each keeps its own lighting (Target: Original Meshes; one undo step "
                    "with the bake). Off: they light the scene but are not written",
        default=False,
    )
    make_linked_local: BoolProperty(
        name="Make Linked Meshes Local",
        description="Meshes linked from another .blend file (File > Link, or under a library override) are not "
                    "saved with this file, so light written into them would be lost. On: each baked object showing "
                    "one gets a local mesh to hold its light, as Object > Relations > Make Local does (Target: "
                    "Original Meshes; one undo step with the bake). Off: such a bake is refused, naming the objects",
        default=False,
    )
    target: EnumProperty(
        name="Target",
        description="Where the baked light is written",
        items=(
            ("ORIGINAL", "Original Meshes",
             "Write a colour attribute onto each baked mesh at its own resolution"),
            ("COPIES", "Subdivided Copies",
             "Write onto new meshes made of the bake's elements, in a \"Radiosity Bake\" collection, "
             "keeping every detail of the solution"),
        ),
        default="ORIGINAL",
    )
    zone_size: FloatProperty(
        name="Zone Size",
        description="Edge of the cubic zones fog, smoke and fire are split into, in scene units. "
                    "0 chooses it from the media's size for about 4096 zones; time grows with the "
                    "square of the zone count",
        default=0.0, min=0.0, soft_max=2.0, subtype="DISTANCE", unit="LENGTH", precision=3,
    )
    media_folder: StringProperty(
        name="Media Folder",
        description="Folder for the baked media's OpenVDB files ('//' = beside the .blend; a temporary "
                    "folder while the file is unsaved)",
        default="//", subtype="DIR_PATH",
    )
    last_report: StringProperty(
        name="Last Bake",
        description="Summary of the most recent bake of this scene",
        default="",
    )
    last_accuracy: StringProperty(
        name="Last Bake Accuracy",
        description="Residual, energy balance and error estimate of the most recent bake",
        default="",
    )
    last_cost: StringProperty(
        name="Last Bake Cost",
        description="What the most recent bake cost: elements, output points gathered and interpolated, rays, "
                    "and the seconds of each phase",
        default="",
    )


CLASSES = (RadiosityLightLayer, RadiositySettings)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.radiosity = bpy.props.PointerProperty(type=RadiositySettings)


def unregister():
    del bpy.types.Scene.radiosity
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
