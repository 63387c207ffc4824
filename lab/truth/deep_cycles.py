"""A deep Cycles truth: the mean of many independent Cycles bakes of a scene's corners, good enough
to judge a bake at 0.5%. Run inside Blender:

    blender -b --factory-startup --python-exit-code 1 --python lab/truth/deep_cycles.py -- \\
        [--scene cornell|small-emitter|cluttered] [--samples 4096] [--target-noise 0.003] \\
        [--max-minutes 60] [--cache DIR]

Each seed is Cycles' Combined bake to the corners with unbiased light paths
(harness.use_unbiased_cycles: 128 bounces, no clamping, no denoiser, no adaptive sampling) at
`samples` samples and its own seed. The truth's own noise is measured from the spread between
seeds (lab/truth/vertex_error.py: per vertex std / sqrt(N), as a relative RMS); seeds are added
until it is at most the target or the time budget is spent. The budget is planned from the
seeds' own times: after two seeds the noise falls as 1 / sqrt(N), so the seeds still needed are
known. The budget counts every seed the cache holds, so a rerun only finishes what is left.

The result is cached outside git, in --cache, $BAKE_RADIOSITY_TRUTH or build/truth of this tree:
one .npz per scene and per-seed sample count, named by a hash of the scene's corner positions
and materials, holding every seed's corner colours (float32), the seeds, the samples and each
seed's seconds. A changed scene has another hash, so it gets a truth of its own; a file that
exists is reused and extended seed by seed (saved after each one, so a stopped run resumes)."""

import argparse
import hashlib
import math
import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(ROOT, "blender_tests"))
sys.path.insert(0, HERE)
import harness  # noqa: E402
import scenes  # noqa: E402
import vertex_error  # noqa: E402

# Seeds of the truth; bakes measured against it use others (docs/charts/cycles_race.py: the sample count).
FIRST_SEED = 100_001
CORNELL_EMITTER_MATERIAL = 3


def cache_folder(explicit=None):
    return os.path.abspath(explicit or os.environ.get("BAKE_RADIOSITY_TRUTH") or os.path.join(ROOT, "build", "truth"))


def mesh_arrays(obj):
    """(corner vertex index, corner positions, corner material index) of obj's mesh."""
    mesh = obj.data
    corner_vertex = np.empty(len(mesh.loops), dtype=np.int64)
    mesh.loops.foreach_get("vertex_index", corner_vertex)
    material = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("material_index", material)
    total = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("loop_total", total)
    return corner_vertex, harness.corner_positions(mesh), np.repeat(material, total)


def scene_hash(obj):
    """Hash of the corners' positions (to 1e-6 m) and material indices and of the materials'
    colours and emission as the add-on and Cycles read them: a changed scene misses the cache."""
    _, positions, material = mesh_arrays(obj)
    digest = hashlib.sha256()
    digest.update(np.round(positions, 6).astype(np.float64).tobytes())
    digest.update(material.astype(np.int64).tobytes())
    for slot in obj.data.materials:
        for node in slot.node_tree.nodes if slot and slot.node_tree else ():
            for socket in node.inputs:
                value = getattr(socket, "default_value", None)
                if isinstance(value, (float, int)) or hasattr(value, "__len__"):
                    digest.update(repr((node.name, socket.name, tuple(np.ravel(value)))).encode())
    for lamp in bpy.data.lights:
        digest.update(repr((lamp.type, lamp.energy, tuple(lamp.color))).encode())
    return digest.hexdigest()


def vertex_luminance_of(obj, skip_material=None):
    """vertex_error.VertexLuminance for obj's corners, corners of `skip_material` (an emitter) left out."""
    corner_vertex, _, material = mesh_arrays(obj)
    return vertex_error.VertexLuminance(corner_vertex, material != skip_material)


def _seed_bake(obj, seed, samples):
    with harness.Stopwatch() as seconds:
        colors = harness.cycles_corner_bake(obj, samples, seed)
    attributes = obj.data.color_attributes
    attributes.remove(attributes["Cycles %d" % seed])
    return colors.astype(np.float32), seconds.cpu, seconds.wall


def deep_truth(obj, name, samples, target_noise, max_seconds, luminance, folder=None, log=print):
    """The cached truth of `obj` (dict of arrays: colors (seeds, corners, 3), seeds, samples,
    cpu_seconds, wall_seconds, hash), extended with seeds of `samples` samples until its noise
    (vertex_error.Truth.noise of `luminance`) is at most `target_noise` or its seeds together
    took `max_seconds` of wall time (over all runs: a rerun does not start the budget again)."""
    digest = scene_hash(obj)
    folder = cache_folder(folder)
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "%s-%s-%dspp.npz" % (name, digest[:12], samples))
    if os.path.exists(path):
        stored = dict(np.load(path))
        assert str(stored["hash"]) == digest and int(stored["samples"]) == samples, "%s is of another scene" % path
        log("truth %s: %d seeds cached" % (path, len(stored["seeds"])))
    else:
        stored = dict(colors=np.zeros((0, len(obj.data.loops), 3), np.float32), seeds=np.zeros(0, np.int64),
                      cpu_seconds=np.zeros(0), wall_seconds=np.zeros(0), samples=samples, hash=digest)
    while True:
        seeds = len(stored["seeds"])
        truth = vertex_error.Truth([luminance(c) for c in stored["colors"]]) if seeds else None
        noise = truth.noise() if seeds else math.nan
        if seeds >= 2 and noise <= target_noise:
            break
        per_seed = float(np.mean(stored["wall_seconds"])) if seeds else 0.0
        spent = float(np.sum(stored["wall_seconds"]))
        if seeds >= 2:
            needed = math.ceil(seeds * (noise / target_noise) ** 2) - seeds
            log("truth: %d seeds, noise %.3f%%: %d more seeds of %d samples for %.2f%%, about %.0f s wall"
                % (seeds, 100 * noise, needed, samples, 100 * target_noise, needed * per_seed))
        if seeds and spent + per_seed > max_seconds:
            log("truth: its time budget of %.0f s wall is spent, noise %.3f%% (target %.3f%%)"
                % (max_seconds, 100 * noise, 100 * target_noise))
            break
        seed = FIRST_SEED + (int(stored["seeds"].max()) - FIRST_SEED + 1 if seeds else 0)
        colors, cpu, wall = _seed_bake(obj, seed, samples)
        log("truth: seed %d, %d samples: %.1f CPU s, %.1f s wall" % (seed, samples, cpu, wall))
        stored["colors"] = np.concatenate([stored["colors"], colors[None]])
        for key, value in (("seeds", seed), ("cpu_seconds", cpu), ("wall_seconds", wall)):
            stored[key] = np.append(stored[key], value)
        np.savez(path + ".partial.npz", **stored)
        os.replace(path + ".partial.npz", path)
    log("truth %s: %d seeds x %d samples = %d samples, noise %.3f%% per vertex (relative RMS), %.0f CPU s"
        % (name, len(stored["seeds"]), samples, len(stored["seeds"]) * samples, 100 * noise,
           float(np.sum(stored["cpu_seconds"]))))
    stored["path"] = path
    return stored, truth


def awkward_room(scene, **keywords):
    """A room of lab/awkward_rooms/measure.py (its Room object: the emitting panel is another object)."""
    sys.path.insert(0, os.path.join(ROOT, "lab", "awkward_rooms"))
    import measure
    return measure.build(scene, **keywords)


SCENES = {"cornell": (lambda: scenes.cornell_box("MESH"), CORNELL_EMITTER_MATERIAL),
          "small-emitter": (lambda: awkward_room("small-emitter", emitter_side=0.01, blocks=0), None),
          "cluttered": (lambda: awkward_room("cluttered", emitter_side=0.01, blocks=1000), None)}


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser()
    parser.add_argument("--scene", default="cornell", choices=sorted(SCENES))
    parser.add_argument("--samples", type=int, default=4096)
    parser.add_argument("--target-noise", type=float, default=0.003)
    parser.add_argument("--max-minutes", type=float, default=60.0, help="wall minutes of all the seeds together")
    parser.add_argument("--cache")
    args = parser.parse_args(argv)
    scenes.clear_scene()
    make, emitter = SCENES[args.scene]
    obj = make()
    deep_truth(obj, args.scene, args.samples, args.target_noise, 60 * args.max_minutes,
               vertex_luminance_of(obj, emitter), args.cache, log=lambda s: print(s, flush=True))


if __name__ == "__main__":
    main()
