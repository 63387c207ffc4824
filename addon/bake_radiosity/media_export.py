"""Participating media of the rendered scene as the core's voxel grids: the insides of meshes whose
material has a volume shader, and Volume objects (OpenVDB files), all on one world lattice of
`zone_size` cells. Coefficients come from the core's principled_volume (media_materials.py)."""

import os
from dataclasses import dataclass, field

import bpy
import numpy as np

from . import media_materials, visibility
from .engine import native
from .export import GEOMETRY_TYPES, MEDIUM_TAG, _corner_order, _read, is_bake_output  # noqa: F401 (MEDIUM_TAG)

# Automatic zone size aims at this many cells over the media's boxes: the exchange factors grow
# with the square of the zone count (docs/volumes.md), 16^3 zones bake in seconds.
ZONE_BUDGET = 4096


@dataclass
class Medium:
    """One medium: the core's input dict and where it came from."""
    object_name: str
    material_name: str
    grid: dict              # origin, voxel_size, extinction, albedo, emission as `_core.bake` takes them (media=)
    input_file: str = ""    # the user's OpenVDB file (Volume objects), never written over


@dataclass
class ExportedMedia:
    media: list = field(default_factory=list)
    zone_size: float = 0.0
    warnings: list = field(default_factory=list)

    @property
    def input_files(self):
        return {os.path.realpath(m.input_file) for m in self.media if m.input_file}


def export_media(depsgraph, view_layer, zone_size):
    """Every medium Cycles renders (visibility.py), voxelised at `zone_size` (0: automatic, see
    ZONE_BUDGET)."""
    sources, warnings = [], []
    # export_scene already warned about objects that render but cannot be baked.
    for instance in visibility.rendered_instances(depsgraph, view_layer):
        obj = instance.object
        if is_bake_output(obj.original):
            continue
        material = _volume_material(obj, warnings) if obj.type in GEOMETRY_TYPES | {"VOLUME"} else None
        if material is None and obj.type == "VOLUME":
            warnings.append(_volume_without_material(obj))
        if material is not None:
            sources.append((obj, np.array(instance.matrix_world, dtype=np.float64), material))
    exported = ExportedMedia(warnings=warnings)
    if not sources:
        return exported
    exported.zone_size = zone_size if zone_size > 0.0 else automatic_zone_size(
        [_world_box(obj, matrix) for obj, matrix, _ in sources])
    for obj, matrix, material in sources:
        shader = media_materials.volume_shader(material)
        exported.warnings += ["Material '%s': %s" % (material.name, p) for p in shader.problems]
        medium = (_volume_object_medium if obj.type == "VOLUME" else _mesh_medium)(
            obj, matrix, material, shader, exported.zone_size, exported.warnings)
        if medium is not None:
            exported.media.append(medium)
    return exported


def automatic_zone_size(boxes):
    """Cell edge that puts about ZONE_BUDGET cells into the media's world boxes ((lo, hi) pairs)."""
    volume = sum(float(np.prod(np.maximum(hi - lo, 1e-6))) for lo, hi in boxes)
    return (volume / ZONE_BUDGET) ** (1.0 / 3.0)


def _volume_material(obj, warnings):
    with_volume = [s.material for s in obj.material_slots if media_materials.volume_output_node(s.material) is not None]
    names = sorted({m.name for m in with_volume})
    if len(names) > 1:
        warnings.append("Object '%s' has several volume materials; its medium uses '%s'"
                        % (obj.name, with_volume[0].name))
    return with_volume[0] if with_volume else None


def _volume_without_material(obj):
    """Cycles renders a Volume object without a volume material as a default Principled Volume; the
    bake needs the material to read its density and colour."""
    volume = obj.original.data
    path = bpy.path.abspath(volume.filepath, library=volume.library)
    if not os.path.isfile(path):
        return "Volume '%s': file '%s' not found and no volume material; not baked" % (obj.name, path)
    return ("Volume '%s' has no volume material (Cycles renders it as a default Principled Volume); not baked: "
            "give it a material with a Principled Volume" % obj.name)


def _world_box(obj, matrix):
    corners = np.array([c[:] for c in obj.bound_box], dtype=np.float64) @ matrix[:3, :3].T + matrix[:3, 3]
    return corners.min(axis=0), corners.max(axis=0)


def _mesh_medium(obj, matrix, material, shader, zone_size, warnings):
    """The mesh's inside: each cell's volume fraction scales density and emission."""
    mesh = obj.to_mesh()
    try:
        co = _read(mesh.vertices, "co", np.float32, 3).astype(np.float64)
        loop_total = _read(mesh.polygons, "loop_total", np.int32)
        loop_start = _read(mesh.polygons, "loop_start", np.int32)
        loop_vertex = _read(mesh.loops, "vertex_index", np.int32)
    finally:
        obj.to_mesh_clear()
    if len(loop_total) == 0:
        return None
    mirrored = np.linalg.det(matrix[:3, :3]) < 0.0
    corners = loop_vertex[_corner_order(loop_start, loop_total, mirrored)].astype(np.int32)
    positions = (co @ matrix[:3, :3].T + matrix[:3, 3]).astype(np.float32)
    offsets = np.concatenate([[0], np.cumsum(loop_total)]).astype(np.int32)
    inside = native.core().voxelize_mesh(positions, offsets, corners, zone_size)
    named = ({t.density_grid for t in shader.terms} | {t.emission_grid for t in shader.terms}) - {None, "density"}
    if named:
        warnings.append("Object '%s': a mesh has no grids %s; they count as 1 inside it"
                        % (obj.name, ", ".join(sorted(named))))
    # Inside a mesh every grid a shader names reads as the volume fraction (Cycles finds no grid
    # and keeps the socket's value), so density and emission both scale by it.
    fraction = inside["values"]
    return _medium(obj, material, shader, inside["origin"], zone_size, lambda name: fraction, fraction, warnings)


def _volume_object_medium(obj, matrix, material, shader, zone_size, warnings):
    volume = obj.original.data
    volume.grids.load()
    path = bpy.path.abspath(volume.grids.frame_filepath or volume.filepath, library=volume.library)
    if not os.path.isfile(path):
        warnings.append("Volume '%s': file '%s' not found; not baked" % (obj.name, path))
        return None
    available = {name for name, _ in native.core().vdb_grids(path)}
    wanted = ({t.density_grid for t in shader.terms} | {t.emission_grid for t in shader.terms}) - {None}
    missing = wanted - available
    if missing:
        warnings.append("Volume '%s': no grid %s in '%s'; those parts of '%s' are 0"
                        % (obj.name, ", ".join(sorted(missing)), os.path.basename(path), material.name))
    read = {name: native.core().read_vdb_grid(path, name, matrix, zone_size) for name in wanted & available}
    if not read:
        warnings.append("Volume '%s': no density grid; not baked" % obj.name)
        return None
    origin, values = _common_lattice(read, zone_size)
    occupied = np.zeros(next(iter(values.values())).shape[:3], dtype=np.float32)
    for name, grid in values.items():
        magnitude = np.abs(grid if grid.ndim == 3 else grid.mean(axis=-1))
        occupied = np.maximum(occupied, (magnitude > 0.0).astype(np.float32))
    zeros = np.zeros_like(occupied)
    medium = _medium(obj, material, shader, origin, zone_size, lambda name: values.get(name, zeros), occupied, warnings)
    if medium is not None:
        medium.input_file = path
    return medium


def _common_lattice(read, zone_size):
    """Grids read from one file onto their union box (all sit on the same world lattice)."""
    lo = np.min([np.rint(np.array(g["origin"]) / zone_size) for g in read.values()], axis=0).astype(int)
    hi = np.max([np.rint(np.array(g["origin"]) / zone_size).astype(int) + np.array(g["values"].shape[2::-1])
                 for g in read.values()], axis=0)
    dims = hi - lo
    values = {}
    for name, g in read.items():
        v = g["values"] if g["values"].ndim == 3 else g["values"].mean(axis=-1)  # a vector grid as its mean
        start = np.rint(np.array(g["origin"]) / zone_size).astype(int) - lo
        out = np.zeros((dims[2], dims[1], dims[0]), dtype=np.float32)
        out[start[2]:start[2] + v.shape[0], start[1]:start[1] + v.shape[1], start[0]:start[0] + v.shape[2]] = v
        values[name] = out
    return tuple(lo * zone_size), values


def _medium(obj, material, shader, origin, zone_size, grid_of, occupied, warnings):
    """Sums the shader's terms (coefficients by the core) into extinction, albedo and emission grids."""
    core = native.core()
    scattering = np.zeros(occupied.shape + (3,), dtype=np.float64)
    absorption, emission = np.zeros_like(scattering), np.zeros_like(scattering)
    for term in shader.terms:
        density = term.density * (occupied if term.density_grid is None else grid_of(term.density_grid))
        strength = term.emission_strength * (occupied if term.emission_grid is None else grid_of(term.emission_grid))
        c = core.principled_volume(term.color, density.astype(np.float64), term.absorption_color,
                                   np.asarray(strength, dtype=np.float64), term.emission_color)
        scattering += c["scattering"]
        absorption += c["absorption"]
        emission += c["emission"]
    extinction = scattering + absorption
    dark = extinction.max(axis=-1) <= 0.0
    if (emission[dark] > 0.0).any():
        warnings.append("Material '%s': emission where the medium has no density is not baked "
                        "(the zonal method needs density where a medium glows)" % material.name)
        emission[dark] = 0.0
    # Emission in a channel whose extinction is 0 cannot be absorbed there either.
    emission[extinction <= 0.0] = 0.0
    if not extinction.any():
        warnings.append("Object '%s': its volume has no density; not baked" % obj.name)
        return None
    albedo = np.divide(scattering, extinction, out=np.zeros_like(extinction), where=extinction > 0.0)
    grid = {"origin": tuple(float(x) for x in origin), "voxel_size": float(zone_size),
            "extinction": extinction.astype(np.float32), "albedo": np.clip(albedo, 0.0, 1.0).astype(np.float32),
            "emission": emission.astype(np.float32)}
    return Medium(object_name=obj.original.name, material_name=material.name, grid=grid)


def zone_count_estimate(media):
    """Cells with density, the zones the core will make."""
    return int(sum(np.count_nonzero(m.grid["extinction"].max(axis=-1) > 0.0) for m in media))


def describe(exported):
    """One line for the report: media, zone size and zones."""
    if not exported.media:
        return ""
    return "%d medium/media, zone size %.3g m, %d zones" % (
        len(exported.media), exported.zone_size, zone_count_estimate(exported.media))
