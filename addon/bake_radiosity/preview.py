"""One-click preview of the baked light, and one click back to exactly what the artist had.

Showing sets every 3D view to solid shading, flat lighting, colour by attribute, and gives each
baked object an object-level material that emits the attribute (so Material Preview and
Rendered show it too). The previous state is kept on the scene, so it survives save and reload."""

import json

import bpy

STATE_KEY = "radiosity_preview_state"
MATERIAL_NAME = "Radiosity Preview"


def is_active(scene):
    return STATE_KEY in scene


def materials_behind(scene):
    """{(object name, slot index): material} that the preview's emission material covers on `scene`
    (empty when the preview is off): the materials a bake must read, whatever the viewport shows.
    A slot the preview added to an object that had none covers no material (None)."""
    if not is_active(scene):
        return {}
    state = json.loads(scene[STATE_KEY])
    behind = {}
    for obj_name, index, link, material_name in state["slots"]:
        obj = bpy.data.objects.get(obj_name)
        if obj is None:
            continue
        if link == "OBJECT":
            behind[(obj_name, index)] = bpy.data.materials.get(material_name) if material_name else None
        else:
            data_materials = obj.data.materials
            behind[(obj_name, index)] = data_materials[index] if index < len(data_materials) else None
    for obj_name in state["appended"]:
        obj = bpy.data.objects.get(obj_name)
        if obj is not None and len(obj.material_slots):
            behind[(obj_name, len(obj.material_slots) - 1)] = None
    return behind


def show(context):
    """Switches to the preview; returns a message if there is nothing baked to show."""
    scene = context.scene
    name = scene.radiosity.attribute_name
    baked = [o for o in scene.objects if o.type == "MESH" and o.data.color_attributes.get(name) is not None]
    if not baked:
        return "Nothing baked yet: no mesh in this scene has a colour attribute '%s'" % name
    state = {"views": [], "slots": [], "appended": []}
    for screen, index, shading in _view_shadings():
        state["views"].append([screen.name, index, shading.type, shading.color_type, shading.light])
        shading.type = "SOLID"
        shading.light = "FLAT"
        shading.color_type = "VERTEX"
    material = _emission_material(name)
    for obj in baked:
        if not obj.material_slots:
            obj.data.materials.append(material)
            state["appended"].append(obj.name)
            continue
        for index, slot in enumerate(obj.material_slots):
            state["slots"].append([obj.name, index, slot.link, _object_material_name(obj, index)])
            slot.link = "OBJECT"
            slot.material = material
    scene[STATE_KEY] = json.dumps(state)
    return None


def restore(context):
    scene = context.scene
    state = json.loads(scene[STATE_KEY])
    views = {(s.name, i): shading for s, i, shading in _view_shadings()}
    for screen_name, index, shading_type, color_type, light in state["views"]:
        shading = views.get((screen_name, index))
        if shading is not None:
            shading.type, shading.color_type, shading.light = shading_type, color_type, light
    for obj_name, index, link, material_name in state["slots"]:
        obj = bpy.data.objects.get(obj_name)
        if obj is None or index >= len(obj.material_slots):
            continue
        slot = obj.material_slots[index]
        slot.link = "OBJECT"
        slot.material = bpy.data.materials.get(material_name) if material_name else None
        slot.link = link
    for obj_name in state["appended"]:
        obj = bpy.data.objects.get(obj_name)
        if obj is not None and len(obj.data.materials) and obj.data.materials[-1] is not None \
                and obj.data.materials[-1].name.startswith(MATERIAL_NAME):
            obj.data.materials.pop()
    del scene[STATE_KEY]
    material = bpy.data.materials.get(MATERIAL_NAME)
    if material is not None and material.users == 0:
        bpy.data.materials.remove(material)


def _object_material_name(obj, index):
    """The material linked to the object (not its mesh) in slot `index`, if any."""
    slot = obj.material_slots[index]
    previous = slot.link
    slot.link = "OBJECT"
    material = slot.material
    slot.link = previous
    return material.name if material is not None else None


def _view_shadings():
    for screen in bpy.data.screens:
        for index, area in enumerate(screen.areas):
            if area.type == "VIEW_3D":
                yield screen, index, area.spaces.active.shading


def _emission_material(attribute_name):
    material = bpy.data.materials.get(MATERIAL_NAME) or bpy.data.materials.new(MATERIAL_NAME)
    if bpy.app.version < (5, 0, 0):  # 5.0 deprecated use_nodes: materials always use nodes
        material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    attribute = nodes.new("ShaderNodeAttribute")
    attribute.attribute_type = "GEOMETRY"
    attribute.attribute_name = attribute_name
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    output = nodes.new("ShaderNodeOutputMaterial")
    links = material.node_tree.links
    links.new(attribute.outputs["Color"], emission.inputs["Color"])
    links.new(emission.outputs["Emission"], output.inputs["Surface"])
    attribute.location, emission.location, output.location = (-400, 0), (-150, 0), (100, 0)
    return material
