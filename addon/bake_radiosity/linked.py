"""Meshes linked from another .blend file. Linked data is not saved with the file that links it,
nor is a library override's geometry (only its overridden properties are), so light written into
such a mesh is gone once the file is reopened. A bake onto Original Meshes finds, before any work,
every object whose mesh it would write that is not saved with this file; it refuses with their
names, or with Make Linked Meshes Local gives each a local mesh, as Object > Relations > Make Local
does, when it writes the light (after the solve, in the bake's one undo step)."""

from dataclasses import dataclass

import bpy

from .engine.errors import BakeError
from .writeback import light_attribute_name, name_taken_by_other_attribute

DO_WHAT = ("Turn on Make Linked Meshes Local (bake(..., make_linked_local=True)) to bake into local copies of "
           "their meshes, make them local first (Object > Relations > Make Local > Selected Objects and Data), or "
           "bake to Target: Subdivided Copies")
IN_LINKED_COLLECTION = ("Make a library override of the collection (Object > Library Override > Make) and bake "
                        "with Make Linked Meshes Local, make the collection local (Object > Relations > Make Local "
                        "> All), or bake to Target: Subdivided Copies")


@dataclass
class LinkedObject:
    """A baked object whose mesh is not saved with this file."""
    part_indices: list  # the exported parts it shows (an object is exported once per instance)
    name: str
    library: str        # where its mesh comes from (a library's file name)
    how: str            # "linked", "override with a linked mesh" or "overridden mesh"
    collection: str     # a linked collection holding a linked object: it cannot be made local alone ("" = can)

    def described(self):
        """(name, where its mesh comes from) for messages."""
        if self.how == "linked":
            return (self.name, "from %s" % self.library)
        if self.how == "override with a linked mesh":
            return (self.name, "a library override, its mesh from %s" % self.library)
        return (self.name, "its mesh a library override of %s's, whose geometry is not saved" % self.library)


def find(exported, settings):
    """Every object whose mesh a bake with `settings` would write that is not saved with this
    file, as LinkedObjects (none for Target: Subdivided Copies, which writes new local meshes)."""
    if settings["target"] != "ORIGINAL":
        return []
    names = [settings["attribute_name"]]
    if settings.get("write_light_only"):
        names.append(light_attribute_name(names[0]))
    found = {}
    for index, part in enumerate(exported.parts):
        # The parts writeback writes onto their object's mesh (writeback._write_original).
        if part.unwritable or (part.shares_mesh and not settings["separate_linked_duplicates"]):
            continue
        obj = bpy.data.objects.get((part.object_name, part.object_library or None))
        if obj is None or obj.type != "MESH" or obj.data is None:
            continue
        key = (part.object_name, part.object_library)
        if key in found:
            found[key].part_indices.append(index)
            continue
        mesh = obj.data
        if any(name_taken_by_other_attribute(mesh, name) for name in names):
            continue  # writeback refuses this mesh and says why
        linked = _linked(obj, index)
        if linked is not None:
            found[key] = linked
    return list(found.values())


def _linked(obj, index):
    mesh = obj.data
    if obj.library is not None or mesh.library is not None:
        library = (mesh.library or obj.library).filepath
        how = "linked" if obj.override_library is None or obj.library is not None else "override with a linked mesh"
    elif mesh.override_library is not None:
        reference = mesh.override_library.reference
        library = reference.library.filepath if reference is not None and reference.library else "a library"
        how = "overridden mesh"
    else:
        return None
    collection = ""
    if obj.library is not None and not any(c.library is None for c in obj.users_collection):
        # Only linked collections hold it: making it local would leave the local copy out of the scene.
        collection = next((c.name for c in obj.users_collection), "")
    return LinkedObject([index], obj.name, bpy.path.basename(library), how, collection)


def refusal(linked, make_local):
    """Why a bake cannot write `linked` (LinkedObjects), naming each, and what to do; "" if it can
    (with `make_local`, all but the objects held only by linked collections)."""
    messages = []
    stuck = [o for o in linked if o.collection]
    if stuck:
        messages.append("The light cannot be saved on objects held only by a linked collection (linked data is not "
                        "saved with this file, and such an object cannot be made local alone): %s. %s" % (
                            _named([(o.name, "in collection '%s' from %s" % (o.collection, o.library))
                                    for o in stuck]), IN_LINKED_COLLECTION))
    rest = [o for o in linked if not o.collection]
    if rest and not make_local:
        messages.append("The light would be lost: linked data is not saved with this file, and these objects' meshes "
                        "are linked: %s. %s" % (_named([o.described() for o in rest]), DO_WHAT))
    return "; ".join(messages)


def _named(items):
    """Every (name, detail) item (an artist fixes each): "'A' (detail)" or "2 objects, 'A' (...), 'B' (...)"."""
    listed = ", ".join("'%s' (%s)" % item for item in items)
    return listed if len(items) == 1 else "%d objects, %s" % (len(items), listed)


def make_local(exported, linked):
    """Gives each of `linked` (LinkedObjects) a local mesh of its own, as Make Local does, and points
    the exported parts at the local object. Returns the warning that says so ("" for none)."""
    for item in linked:
        part = exported.parts[item.part_indices[0]]
        obj = bpy.data.objects.get((part.object_name, part.object_library or None))
        if obj.library is not None:
            obj = obj.make_local()
        mesh = obj.data
        if mesh.library is not None:
            local = mesh.make_local()
        elif mesh.override_library is not None:
            # An override's geometry is its reference's (geometry cannot be overridden): copy that,
            # with the materials the override shows.
            local = mesh.override_library.reference.copy()
            for slot, material in enumerate(mesh.materials):
                local.materials[slot] = material
        else:
            local = mesh
        if obj.data != local:
            obj.data = local
        if obj.library is not None or obj.data.library is not None or obj.data.override_library is not None:
            raise BakeError("Could not make the mesh of '%s' local" % obj.name)
        for index in item.part_indices:
            exported.parts[index].object_name, exported.parts[index].object_library = obj.name, ""
            exported.parts[index].mesh_name = obj.data.name
    if not linked:
        return ""
    return ("Made the linked meshes of %s local to hold their light: it is saved with this file, and later changes "
            "to the library's meshes no longer reach them" % _named([o.described() for o in linked]))
