"""Light-only output and the wiring of the baked light into materials.

The scene: a 2 x 2 m floor with an image texture (a checker of two colours, made here and saved to
a temporary PNG) on its Diffuse BSDF's Color, a grey wall standing on one edge, and a point lamp
over the floor. The light-only attribute is the light arriving without the surface's colour, as
Cycles' Diffuse bake with Direct and Indirect and without Color gives it:
- times the albedo it is exactly the radiance the add-on writes, with and without the final
  gather: on the textured floor the albedo at each corner is the checker's texel there;
- it matches Cycles' Diffuse (Direct + Indirect, no Color) bake of the textured floor to corners,
  the hierarchical method's too.
Wire Baked Light makes each material emit the light times its diffuse colour as Cycles' Diffuse bake
has it (Cycles' Emit bake of the wired wall gives its radiance back, a Principled BSDF's too);
Unwire Baked Light restores the node trees exactly."""

import importlib
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)
textures = sys.modules[harness.MODULE + ".textures"]
cli = importlib.import_module(harness.MODULE + ".cli")

ROOM, CELLS, WALL_ALBEDO = 2.0, 8, 0.5
CHECKER = ((0.8, 0.5, 0.2), (0.3, 0.6, 0.7))  # the texture's two colours, in the PNG's sRGB
SETTINGS = dict(method="GAUSS_SEIDEL", hemicube_resolution=128, element_size=0.125)
SAMPLES_PER_HALF = 512
MAX_CYCLES_NOISE = 0.01
# Light-only against Cycles' Diffuse bake over the floor's corners (relative RMS), measured with Cycles'
# noise 0.16%: 0.25% with the final gather, 1.14% interpolated from the elements.
MAX_RELATIVE_RMS = {True: 0.01, False: 0.025}
# The hierarchical method (its light-only attribute too) against Cycles: blender_test_cycles' limit
# for its Cornell box (relative RMS).
HIERARCHICAL = dict(quality="CUSTOM", method="HIERARCHICAL", element_size=0.0625, refine_tolerance=0.02,
                    tolerance=1e-4)
HIERARCHY_ACCURACY = 0.035
PRINCIPLED_METALLIC = 0.25


def checker_image():
    """An 8 x 8 checker PNG in a temporary folder, loaded as an sRGB byte image."""
    size = 8
    i, j = np.meshgrid(np.arange(size), np.arange(size), indexing="ij")
    which = (i + j) % 2
    return bpy.data.images.load(scenes.save_png("checker", np.asarray(CHECKER, dtype=np.float32)[which]))


def scene(textured):
    """(floor, wall); the floor textured or of the texture's mean colour. Returns also that colour."""
    scenes.clear_scene()
    image = checker_image()
    mean = textures.Images().load(image).mean
    floor_material = (scenes.image_texture_material("Checker Floor", image, (1.0, 1.0, 1.0), "Closest") if textured
                      else scenes.diffuse("Mean Floor", tuple(mean)))
    floor = scenes.floor_with_uv_map(ROOM, CELLS, floor_material)
    wall = scenes.wall_and_point_lamp(ROOM, CELLS, WALL_ALBEDO)
    return floor, wall, np.float32(mean).astype(np.float64)


def checker_texel(floor):
    """(corners, 3) linear colour of the checker at each floor corner's UV, as Cycles' Closest lookup
    with Repeat reads it (corners lie on texel edges: the texel above and to the right), from the
    bytes the PNG stores."""
    image = next(n for n in floor.active_material.node_tree.nodes if n.bl_idname == "ShaderNodeTexImage").image
    size = image.size[0]
    stored = np.empty(size * size * 4, dtype=np.float32)
    image.pixels.foreach_get(stored)
    stored = stored.reshape(size, size, 4)[:, :, :3].astype(np.float64)
    uv = np.empty(len(floor.data.loops) * 2, dtype=np.float32)
    floor.data.uv_layers["UVMap"].data.foreach_get("uv", uv)
    texel = np.floor(uv.reshape(-1, 2).astype(np.float64) * size).astype(int) % size
    return textures.srgb_to_linear(stored[texel[:, 1], texel[:, 0]])


def select_only(obj):
    """`obj` selected and active, for Cycles' bake."""
    for other in bpy.context.view_layer.objects:
        if other is not None:  # Blender 5.2 lists objects just removed as None until it redraws
            other.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


def test_light_times_albedo_is_the_radiance():
    for final_gather in (True, False):
        floor, wall, _ = scene(textured=True)
        settings = bpy.context.scene.radiosity
        settings.quality = "CUSTOM"
        for key, value in SETTINGS.items():
            setattr(settings, key, value)
        settings.final_gather = final_gather
        settings.write_light_only = True
        assert bpy.ops.radiosity.bake() == {"FINISHED"}, settings.last_report
        light = harness.corner_colors(floor.data, "Radiosity Light")
        wall_light = harness.corner_colors(wall.data, "Radiosity Light")
        # The wall is untextured: its own radiance is its light times its albedo.
        np.testing.assert_allclose(wall_light * WALL_ALBEDO, harness.corner_colors(wall.data, "Radiosity"),
                                   rtol=1e-5, atol=1e-7)
        assert floor.data.color_attributes.active_color.name == "Radiosity"

        radiance = harness.corner_colors(floor.data, "Radiosity")
        albedo = checker_texel(floor)
        error = np.abs(light * albedo - radiance).max() / radiance.max()
        print("final gather %s: floor light %.4f..%.4f, max |light x albedo - radiance| %.2e of the brightest"
              % (final_gather, light.min(), light.max(), error), flush=True)
        assert light.min() > 0.0
        np.testing.assert_allclose(light * albedo, radiance, rtol=1e-5, atol=1e-6 * radiance.max())

        floor, wall, _ = scene(textured=False)
        addon.bake(bpy.context.scene, final_gather=final_gather, write_light_only=False, **SETTINGS)
        assert floor.data.color_attributes.get("Radiosity Light") is None  # not asked for


def test_light_matches_cycles_diffuse_bake():
    floor, wall, _ = scene(textured=True)
    bake = bpy.context.scene.render.bake
    bake.use_pass_direct = bake.use_pass_indirect = True
    bake.use_pass_color = False
    halves = []
    for seed in (1, 2):
        harness.use_unbiased_cycles(SAMPLES_PER_HALF, seed)
        bake.target = "VERTEX_COLORS"
        name = "Cycles Diffuse %d" % seed
        attributes = floor.data.color_attributes
        attributes.active_color = attributes.new(name, "FLOAT_COLOR", "CORNER")
        select_only(floor)
        assert bpy.ops.object.bake(type="DIFFUSE", pass_filter={"DIRECT", "INDIRECT"},
                                   target="VERTEX_COLORS") == {"FINISHED"}
        halves.append(harness.corner_colors(floor.data, name))
    reference = 0.5 * (halves[0] + halves[1])
    scale = np.sqrt(np.mean(reference ** 2))
    noise = np.sqrt(np.mean((halves[0] - halves[1]) ** 2)) / 2 / scale
    print("Cycles Diffuse (direct + indirect, no colour): noise %.2f%%, floor mean %.4f"
          % (100 * noise, reference.mean()), flush=True)
    assert noise < MAX_CYCLES_NOISE, "Cycles is too noisy to judge: %.2f%%" % (100 * noise)
    bakes = [("final gather %s" % final_gather, dict(final_gather=final_gather, **SETTINGS), limit)
             for final_gather, limit in MAX_RELATIVE_RMS.items()]
    bakes.append(("hierarchical", HIERARCHICAL, HIERARCHY_ACCURACY))
    for name, settings, max_relative_rms in bakes:
        addon.bake(bpy.context.scene, write_light_only=True, **settings)
        light = harness.corner_colors(floor.data, "Radiosity Light")
        relative_rms = np.sqrt(np.mean((light - reference) ** 2)) / scale
        mean_error = light.mean() / reference.mean() - 1
        print("%s: light only mean %.4f, relative RMS %.2f%%, mean %+.2f%%, limit %.2f%%"
              % (name, light.mean(), 100 * relative_rms, 100 * mean_error, 100 * max_relative_rms), flush=True)
        assert relative_rms < max_relative_rms, name


def tree_state(material):
    tree = material.node_tree
    return (sorted(n.name for n in tree.nodes),
            sorted((link.from_node.name, link.from_socket.identifier, link.to_node.name, link.to_socket.identifier)
                   for link in tree.links),
            sorted(material.keys()))


def emit_bake(obj):
    """Cycles' Emit bake of `obj` to corners: the emission the wired material renders."""
    return cycles_bake(obj, "EMIT")


def diffuse_colour_bake(obj):
    """Cycles' Diffuse bake of `obj` to corners with Color alone: the diffuse colour Cycles
    multiplies the light arriving on the surface by."""
    return cycles_bake(obj, "DIFFUSE", {"COLOR"})


def cycles_bake(obj, kind, passes=()):
    """Cycles' `kind` bake of `obj` to corners, one sample, `passes` its pass filter."""
    harness.use_unbiased_cycles(1, 0)
    attributes = obj.data.color_attributes
    attributes.active_color = attributes.new("Cycles " + kind, "FLOAT_COLOR", "CORNER")
    select_only(obj)
    assert bpy.ops.object.bake(type=kind, pass_filter=set(passes), target="VERTEX_COLORS") == {"FINISHED"}
    values = harness.corner_colors(obj.data, "Cycles " + kind)
    attributes.remove(attributes["Cycles " + kind])
    return values


def test_wire_and_unwire():
    floor, wall, _ = scene(textured=True)
    addon.bake(bpy.context.scene, write_light_only=True, **SETTINGS)
    originals = {m.name: tree_state(m) for m in bpy.data.materials}
    # While the preview shows, the slots hold its material: nothing is wired.
    assert bpy.ops.radiosity.preview() == {"FINISHED"}
    assert bpy.ops.radiosity.wire() == {"CANCELLED"}
    assert bpy.ops.radiosity.preview() == {"FINISHED"}
    assert {m.name: tree_state(m) for m in bpy.data.materials} == originals
    assert bpy.ops.radiosity.wire() == {"FINISHED"}
    for obj in (floor, wall):
        tree = obj.active_material.node_tree
        added = [n for n in tree.nodes if n.name.startswith("Radiosity Wire ")]
        assert {n.bl_idname for n in added} == {"ShaderNodeVertexColor", "ShaderNodeEmission",
                                                "ShaderNodeVectorMath"}, [n.bl_idname for n in added]
        attribute = next(n for n in added if n.bl_idname == "ShaderNodeVertexColor")
        assert attribute.layer_name == "Radiosity Light"
        output = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial")
        assert output.inputs["Surface"].links[0].from_node.bl_idname == "ShaderNodeEmission"
    # The floor's light is multiplied by its texture.
    product = next(n for n in floor.active_material.node_tree.nodes if n.bl_idname == "ShaderNodeVectorMath")
    assert product.inputs[1].links[0].from_node.bl_idname == "ShaderNodeTexImage"
    # What Cycles renders: the wall emits its light times its albedo, its baked radiance.
    np.testing.assert_allclose(emit_bake(wall), harness.corner_colors(wall.data, "Radiosity"), rtol=1e-3, atol=1e-5)
    # The floor emits its light times one of the checker's colours at each corner.
    ratio = emit_bake(floor) / harness.corner_colors(floor.data, "Radiosity Light")
    linear = textures.srgb_to_linear(np.asarray(CHECKER))
    assert np.all(ratio >= linear.min(axis=0) - 0.01) and np.all(ratio <= linear.max(axis=0) + 0.01), ratio
    assert bpy.ops.radiosity.wire() == {"CANCELLED"}  # wired already: nothing added twice

    assert bpy.ops.radiosity.unwire() == {"FINISHED"}
    assert {m.name: tree_state(m) for m in bpy.data.materials} == originals


def test_full_radiance_wiring():
    """Without the light-only attribute the emission is the baked radiance: Cycles' Emit bake of the
    wired floor gives the attribute back at every corner. Cycles reads a corner 1e-4 m (times its
    largest coordinate, when above 1 m) inside one of its triangles (bake_offset_towards_center), and
    averages the corners around a vertex, so at a corner of a single face the read differs from the
    corner's value by that step times the colour's slope across the face. A textured face's corners
    show the checker's texels, a steep slope: the floor here has the texture's mean colour."""
    floor, wall, _ = scene(textured=False)
    addon.bake(bpy.context.scene, method="HIERARCHICAL", element_size=0.25, write_light_only=False)
    assert floor.data.color_attributes.get("Radiosity Light") is None
    assert bpy.ops.radiosity.wire() == {"FINISHED"}
    np.testing.assert_allclose(emit_bake(floor), harness.corner_colors(floor.data, "Radiosity"), rtol=1e-3,
                               atol=1e-5)
    assert bpy.ops.radiosity.unwire() == {"FINISHED"}


def test_wiring_a_principled_bsdf():
    """A wired Principled BSDF emits the light times the diffuse colour Cycles gives it (its Diffuse
    bake with Color alone): the Base Color (a value here) less its Metallic part and, from
    Blender 4.0 on, less the albedo of the specular layer over the diffuse one. That is the wall's
    baked radiance too."""
    floor, wall, _ = scene(textured=True)
    material = bpy.data.materials.new("Principled Wall")
    if bpy.app.version < (5, 0, 0):  # 5.0 deprecated use_nodes: materials always use nodes
        material.use_nodes = True
    bsdf = next(n for n in material.node_tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled")
    bsdf.inputs["Base Color"].default_value = (WALL_ALBEDO, 0.4, 0.3, 1.0)
    bsdf.inputs["Metallic"].default_value = PRINCIPLED_METALLIC
    wall.data.materials[0] = material
    original = tree_state(material)
    diffuse_colour = diffuse_colour_bake(wall)
    addon.bake(bpy.context.scene, write_light_only=True, **SETTINGS)
    assert bpy.ops.radiosity.wire() == {"FINISHED"}
    wired = emit_bake(wall)
    expected = harness.corner_colors(wall.data, "Radiosity Light") * diffuse_colour
    print("wired Principled BSDF (Metallic %.2f): Cycles' diffuse colour %s, emission / (light x diffuse colour) "
          "%.5f..%.5f" % (PRINCIPLED_METALLIC, np.round(diffuse_colour.mean(axis=0), 5),
                          (wired / expected).min(), (wired / expected).max()), flush=True)
    np.testing.assert_allclose(wired, expected, rtol=1e-3, atol=1e-5)
    np.testing.assert_allclose(wired, harness.corner_colors(wall.data, "Radiosity"), rtol=1e-3, atol=1e-5)
    assert bpy.ops.radiosity.unwire() == {"FINISHED"}
    assert tree_state(material) == original


def test_copies_hold_the_light_too():
    scene(textured=True)
    addon.bake(bpy.context.scene, target="COPIES", write_light_only=True, **SETTINGS)
    copy = next(o for o in bpy.data.objects if o.get("radiosity_bake_copy") == "Wall")
    assert copy.data.color_attributes.active_color.name == "Radiosity"
    light = harness.corner_colors(copy.data, "Radiosity Light")
    np.testing.assert_allclose(light * WALL_ALBEDO, harness.corner_colors(copy.data, "Radiosity"), rtol=1e-5,
                               atol=1e-7)
    assert light.min() > 0.0


def test_batch_option():
    assert cli.overrides_of(cli.parse(["--write-light-only"])) == {"write_light_only": True}
    assert "write_light_only" not in cli.overrides_of(cli.parse([]))


harness.run(test_light_times_albedo_is_the_radiance, test_light_matches_cycles_diffuse_bake, test_wire_and_unwire,
            test_full_radiance_wiring, test_wiring_a_principled_bsdf,
            test_copies_hold_the_light_too, test_batch_option)
