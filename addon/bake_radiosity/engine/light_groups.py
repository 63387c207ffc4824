"""Light groups as baked layers: which layer each source lights (Blender's Light Groups, from 3.2:
each lamp, emitting object and the World names its group), the layers' colour attributes, and
whether their memory fits the budget. No bpy: names and arrays from the export.

One layer per group that lights the scene: a group lights it when one of its lamps, emitting
polygons or the World is exported. A source with no group, or naming a group the view layer does
not have (Cycles renders no pass for it), lights the layer "no group"."""

from dataclasses import dataclass
from typing import List, Optional, Sequence

import numpy as np

from . import native

MEBIBYTE = 1 << 20
NO_GROUP = ""
# The layer of the sources without a group: "<attribute> (no group)". A light group named "(no group)"
# would share it (refusal says so).
NO_GROUP_SUFFIX = " (no group)"
# The add-on's own copies of each layer's colours (float32: half the core's doubles).
PYTHON_COPY_SHARE = 0.5


@dataclass(frozen=True)
class Layers:
    """The layers a bake writes: names[k] is layer k's group (NO_GROUP: sources without one)."""
    names: List[str]
    polygon: np.ndarray  # (F,) int32: the layer of each polygon's emission (0 where it emits nothing)
    lamp: np.ndarray     # (lamps,) int32, in the order of the exported lamps
    world: int           # the World's layer (0 when the World gives no light)

    def keyword(self) -> dict:
        """The `layers` keyword of `_core.bake`."""
        return {"count": len(self.names), "polygon": self.polygon, "lamp": self.lamp, "world": self.world}


def group_of(name: str, view_layer_groups: Sequence[str]) -> str:
    """The group a source's light group name puts it in: NO_GROUP unless the view layer has it."""
    return name if name and name in view_layer_groups else NO_GROUP


def layers_of(group_names: Sequence[str], polygon_group: np.ndarray, emission: np.ndarray,
              lamp_groups: Sequence[str], world_group: Optional[str], view_layer_groups: Sequence[str]) -> Layers:
    """The Layers of a scene: polygon f's light group is group_names[polygon_group[f]], lamp l's
    lamp_groups[l] ("" for none), `emission` (F, 3) the polygons' emission, and `world_group` the
    World's (None when the World gives no light). Groups in the order of the view layer's list, the
    sources without a group first."""
    polygon_group = np.asarray(polygon_group, dtype=np.int64)
    groups = np.array([group_of(g, view_layer_groups) for g in group_names] or [NO_GROUP], dtype=object)
    lamp_names = [group_of(g, view_layer_groups) for g in lamp_groups]
    emitting = np.asarray(emission).max(axis=1) > 0.0 if len(polygon_group) else np.zeros(0, bool)
    lighting = set(groups[np.unique(polygon_group[emitting])]) | set(lamp_names)
    if world_group is not None:
        lighting.add(group_of(world_group, view_layer_groups))
    names = [n for n in [NO_GROUP] + list(view_layer_groups) if n in lighting]
    index = {n: k for k, n in enumerate(names)}
    group_layer = np.array([index.get(g, 0) for g in groups], dtype=np.int32)
    polygon = group_layer[polygon_group] if len(polygon_group) else np.zeros(0, np.int32)
    lamp = np.array([index[n] for n in lamp_names], dtype=np.int32)
    world = index[group_of(world_group, view_layer_groups)] if world_group is not None else 0
    return Layers(names, polygon, lamp, world)


def attribute_name(attribute: str, group: str) -> str:
    """The colour attribute of `group`'s layer beside the bake's `attribute`: "<attribute> <group>",
    "<attribute> (no group)" for the sources without one."""
    return attribute + (NO_GROUP_SUFFIX if group == NO_GROUP else " " + group)


def layer_bytes(layers: int, elements: int, corners: int) -> int:
    """The memory `layers` layers add to a bake: the core's bound and the add-on's copies."""
    core = int(native.core().layer_bytes_bound(layers, elements, corners))
    return int(core * (1.0 + PYTHON_COPY_SHARE))


def refusal(layers: Layers, method: str, media: bool, gathered: bool, matrix_bytes: int, elements: int, corners: int,
            budget_bytes: int) -> Optional[str]:
    """Why the bake cannot add the layers (it then bakes without them), or None: not with fog or
    smoke, hierarchically only with the final gather (`gathered`: every layer lights the same leaves),
    and the layers with the stored form factors (`matrix_bytes`, 0 when not stored: the hierarchy's
    nodes and links take what the layers leave of the budget) within the memory budget."""
    if NO_GROUP in layers.names and NO_GROUP_SUFFIX.strip() in layers.names:
        return ("A light group is named '%s', the name of the layer of lights without a group: rename it to bake "
                "light group layers; baked without them" % NO_GROUP_SUFFIX.strip())
    if media:
        return "Light group layers are not baked with fog or smoke yet: baked without them"
    if method == "hierarchical" and not gathered:
        return "Hierarchical light group layers need the Final Gather (Target: Original Meshes): baked without them"
    needed = layer_bytes(len(layers.names), elements, corners)
    if matrix_bytes + needed > budget_bytes or needed >= budget_bytes:
        return ("Light group layers need %.1f MB, which with the form factors' %.1f MB is more than the memory "
                "budget (%.0f MB): baked without them; raise the Memory Budget to bake them"
                % (needed / MEBIBYTE, matrix_bytes / MEBIBYTE, budget_bytes / MEBIBYTE))
    return None
