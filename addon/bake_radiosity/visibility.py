"""What Cycles renders (F12), so that what renders is what bakes: the one rule for which objects
and lamps take part in a bake (export.py reads surfaces and lamps with it, media_export.py media).

Blender decides render visibility from flags, not from the viewport (source/blender/blenkernel
layer.cc and collection.cc: a base is enabled for render when some path to it has no collection
disabled in renders, collection_object_cache_fill; DEG builds the render graph from those bases):
- the object's "Disable in Renders" (hide_render);
- every collection on the way to it disabled in renders, at any depth, in the view layer and
  inside instanced collections (an instance of a collection shows only its render-enabled part);
- collections excluded from the view layer (LayerCollection.exclude, the checkbox);
- the view layer the bake uses (pipeline.view_layer_and_depsgraph).

Hiding in the viewport does not change a render: F12 renders objects hidden with the eye icon
(hide_set, and a collection's eye in the view layer) and objects disabled in viewports (monitor
icon). So the bake follows render visibility, not viewport visibility. The bake reads the
viewport's evaluated depsgraph (Python cannot build a render one), in which eye-hidden objects are
evaluated but left out of object_instances, so they are added here from the depsgraph; objects
disabled in viewports are not evaluated at all (no modifiers, no instances), so they cannot be
baked as they render and the bake names them instead of guessing. Instances that an eye-hidden
object makes are likewise not in the depsgraph's list and are named.
"""

from dataclasses import dataclass

from mathutils import Matrix

# Object types whose absence from a bake changes its light.
LIGHTING_TYPES = {"MESH", "CURVE", "SURFACE", "META", "FONT", "VOLUME", "LIGHT"}
# A list of names in a warning stops after this many ("and 27 more").
NAMES_SHOWN = 3


@dataclass
class Instance:
    """One rendered object instance: the evaluated object and where it sits."""
    object: object          # evaluated bpy.types.Object
    matrix_world: Matrix
    is_instance: bool


class _ViewLayerRender:
    """The original objects that render in a view layer, and per collection those an instance of
    it renders."""

    def __init__(self, view_layer):
        self.objects = set()
        self._through = {}
        self._walk(view_layer.layer_collection)

    def _walk(self, layer_collection):
        # The scene collection (the root) can be neither excluded nor disabled in renders.
        if layer_collection.exclude or layer_collection.collection.hide_render:
            return
        self.objects.update(o for o in layer_collection.collection.objects if not o.hide_render)
        for child in layer_collection.children:
            self._walk(child)

    def through(self, collection):
        """Objects an instance of `collection` renders: its objects and its children's, down every
        branch not disabled in renders, and those of collections it instances in turn."""
        found = self._through.get(collection)
        if found is None:
            found = self._through[collection] = set()  # guards against a collection instancing itself
            pending = [collection]
            while pending:
                current = pending.pop()
                if current.hide_render:
                    continue
                for obj in current.objects:
                    if obj.hide_render:
                        continue
                    found.add(obj)
                    if obj.instance_type == "COLLECTION" and obj.instance_collection is not None:
                        found |= self.through(obj.instance_collection)
                pending.extend(current.children)
        return found


def _renders_itself(evaluated, instancers):
    """An object that makes instances (instancing, particles, geometry nodes) shows itself in
    renders only with Instancing > Show Instancer > Render (BKE_object_visibility). Geometry-node
    instances do not set is_instancer: `instancers` holds the objects seen making instances."""
    makes_instances = (evaluated.is_instancer or len(evaluated.particle_systems) > 0
                       or evaluated.original in instancers)
    return not makes_instances or evaluated.original.show_instancer_for_render


def rendered_instances(depsgraph, view_layer, warnings=None, is_output=lambda original: False):
    """Every object instance Cycles renders in `view_layer`, as Instance records of evaluated
    objects, in depsgraph order. Appends to `warnings` (a list) the objects that render but cannot
    be baked because the viewport's depsgraph lacks them, except the bake's own output
    (`is_output` of the original object), which is never baked anyway."""
    render = _ViewLayerRender(view_layer)
    listed, instancers, undecided = set(), set(), []
    for instance in depsgraph.object_instances:
        obj = instance.object
        if instance.is_instance:
            # instance.parent is the top-level instancer, also for instances of instances.
            parent = instance.parent.original if instance.parent is not None else None
            if parent is None or parent not in render.objects:
                continue
            instancers.add(parent)
            if (parent.instance_type == "COLLECTION" and parent.instance_collection is not None
                    and obj.original not in render.through(parent.instance_collection)):
                continue
            yield Instance(obj, instance.matrix_world.copy(), True)
            continue
        listed.add(obj.original)
        if obj.original not in render.objects:
            continue
        if obj.original.show_instancer_for_render:
            yield Instance(obj, instance.matrix_world.copy(), False)
        else:
            # Shown only if it makes no instances; geometry-node instances come after it in the
            # list, so decide once all have been seen.
            undecided.append(Instance(obj, instance.matrix_world.copy(), False))
    for candidate in undecided:
        if _renders_itself(candidate.object, instancers):
            yield candidate

    not_evaluated, hidden_instancers = [], []
    for original in sorted(render.objects - listed, key=lambda o: o.name):
        if (original.type not in LIGHTING_TYPES and original.instance_type == "NONE") or is_output(original):
            continue
        evaluated = original.evaluated_get(depsgraph)
        if not evaluated.is_evaluated:
            not_evaluated.append(original.name)
            continue
        # Evaluated but not listed: hidden in the viewport (eye icon), or an instancer whose Show
        # Instancer is off in the viewport. Bake it as F12 renders it; the instances of a hidden
        # one are not listed either.
        if evaluated.is_instancer and original not in instancers:
            hidden_instancers.append(original.name)
        if original.type in LIGHTING_TYPES and _renders_itself(evaluated, instancers):
            yield Instance(evaluated, evaluated.matrix_world.copy(), False)
    if warnings is not None:
        if not_evaluated:
            warnings.append(listing("Disabled in viewports but not in renders, so not baked (Blender does not "
                                    "evaluate them for the viewport; enable them in viewports, or disable them "
                                    "in renders)", "object", not_evaluated))
        if hidden_instancers:
            warnings.append(listing("Instances made by objects hidden in the viewport are not baked, though they "
                                    "render (Blender does not list them for the viewport; unhide the objects)",
                                    "object", hidden_instancers))


def listing(problem, noun, items):
    """One warning for many objects: the problem, the count and the first few, e.g.
    "<problem>: 30 lamps, 'A', 'B', 'C' and 27 more"; for one: "<problem>: lamp 'A'"."""
    items = list(items)
    if len(items) == 1:
        return "%s: %s %s" % (problem, noun, _quoted(items[0]))
    shown = ", ".join(_quoted(item) for item in items[:NAMES_SHOWN])
    more = " and %d more" % (len(items) - NAMES_SHOWN) if len(items) > NAMES_SHOWN else ""
    return "%s: %d %ss, %s%s" % (problem, len(items), noun, shown, more)


def _quoted(item):
    """Names are quoted; an item given as (name, detail) reads 'name' (detail)."""
    if isinstance(item, tuple):
        return "'%s' (%s)" % item
    return "'%s'" % item
