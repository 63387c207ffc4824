"""The session's bake cache: what the last uniform bake learned about the geometry (its elements,
form factors and the final gather's rays' hits, `_core.BakeCache`), kept in memory between bakes
in this Blender session, never in the .blend. The core decides whether a bake may reuse it: it
hashes what the exported arrays say of the geometry (every baked object's evaluated positions and
faces, so modifiers and visibility too, the material slots, which faces emit) and the settings that
choose the elements; a bake whose hash differs bakes afresh and keeps its own. One cache a session:
a bake of another scene or geometry replaces it, so it never holds more than one bake's memory.
No bpy."""

from typing import Any, Dict, Optional

from . import native

MEBIBYTE = 1 << 20

_session: Optional[Any] = None


def session_cache(reuse: bool) -> Optional[Any]:
    """The session's `_core.BakeCache` for a bake (made on first use); with `reuse` False, None, and
    what the cache held is let go (a bake from scratch keeps nothing)."""
    global _session
    if not reuse:
        clear()
        return None
    if _session is None:
        _session = native.core().BakeCache()
    return _session


def clear() -> None:
    """Lets go of what the session's cache holds."""
    global _session
    if _session is not None:
        _session.clear()
    _session = None


def held_bytes() -> int:
    """The bytes the session's cache holds (0: none)."""
    return int(_session.bytes) if _session is not None else 0


def cache_text(cache: Optional[Dict[str, Any]]) -> str:
    """The summary's words for what a bake did with the cache (the core's result["cache"]): whether
    it reused the previous bake's geometry and whether it kept its own, with their memory; "" for a
    bake given no cache."""
    if not cache:
        return ""
    size = "%.0f MB" % (cache["bytes"] / MEBIBYTE)
    if cache.get("direct_bytes"):
        size += ", %.0f MB of it the direct light per source" % (cache["direct_bytes"] / MEBIBYTE)
    reused = "Reused the geometry of the previous bake"
    if cache.get("merged_again"):
        reused += ", its form factors computed again (the faces beside the moved lamps merge otherwise)"
    if cache["reused"] and cache["kept"]:
        return "%s (%s)" % (reused, size)
    if cache["reused"]:
        return "%s; not kept for the next: %s" % (reused, cache["not_kept"])
    if cache["kept"]:
        return "Baked the geometry afresh (%s) and kept it for the next bake (%s)" % (cache["not_reused"], size)
    return "Baked the geometry afresh (%s); not kept for the next bake: %s" % (
        cache["not_reused"], cache["not_kept"])
