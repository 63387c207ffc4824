"""The native core's Python contract (native/python, pybind11): what the add-on's engine/ calls.

Arrays are numpy arrays of float32 (positions, colours) or int32 (indices) as the add-on's export
writes them (engine/scene.py); every function's docstring in the module has the full text of its
keywords and of the dict it returns."""

from typing import Any, Callable, Optional, Union

import numpy as np

DEFAULT_MATRIX_BUDGET_BYTES: int


class Error(Exception):
    """Every failure of the core is also an Error, beside its built-in base."""


class InputError(ValueError, Error):
    """Input the core refuses: the message names the polygon, light or setting."""


class BudgetError(InputError):
    """A bake that would pass its memory budget."""


class NotConverged(RuntimeError, Error):
    """A solve that diverged or stopped short of its tolerance."""


class FileError(OSError, Error):
    """An OpenVDB file that cannot be read or written."""


class Cancelled(Exception):
    """ProgressMonitor.cancel() stopped the bake."""


class NumericalError(RuntimeError, Error):
    """Light that is not a number; the message names the phase."""

    phase: str
    polygon: int  # the input polygon to blame; -1: none


class BakeCache:
    """What a uniform bake learned about the geometry (elements, form factors, the gather's hits),
    kept for the next bake of the same geometry (bake(..., cache=...))."""

    def __init__(self) -> None: ...
    @property
    def bytes(self) -> int: ...
    @property
    def empty(self) -> bool: ...
    def clear(self) -> None: ...


class ProgressMonitor:
    """Passed as bake(progress=...) from a worker thread, polled and cancelled from another."""

    def __init__(self) -> None: ...
    def snapshot(self, radiance: bool = True) -> Optional[dict[str, Any]]: ...
    @property
    def reports(self) -> int: ...
    def cancel(self) -> None: ...
    @property
    def cancelled(self) -> bool: ...


_Progress = Union[ProgressMonitor, Callable[[dict[str, Any]], None], None]


def bake(positions: np.ndarray, face_offsets: np.ndarray, corner_vertices: np.ndarray, reflectance: np.ndarray,
         emission: np.ndarray, material: Optional[np.ndarray] = None, *, front_only: Optional[np.ndarray] = None,
         textures: Optional[dict[str, Any]] = None, progress: _Progress = None, **settings: Any) -> dict[str, Any]:
    """Bakes the scene by the method the settings choose; one dict whatever the method (elements,
    corner and element radiance and light, the solve's numbers, seconds per phase, final_gather,
    cache, layers, media zones and grids)."""


def plan(positions: np.ndarray, face_offsets: np.ndarray, corner_vertices: np.ndarray, reflectance: np.ndarray,
         emission: np.ndarray, material: Optional[np.ndarray] = None, *, front_only: Optional[np.ndarray] = None,
         textures: Optional[dict[str, Any]] = None, **settings: Any) -> dict[str, Any]:
    """What bake() with the same arrays and settings will solve: its elements, solve_elements,
    solve_element_area, solve_element_polygon, matrix_bytes_bound, matrix_bytes_planned, matrix_stored,
    sight_distance and resolution_distance."""


def matrix_bytes_bound(element_count: int, resolution: int) -> int: ...


def layer_bytes_bound(layers: int, elements: int, corners: int) -> int: ...


def recommended_resolution(element_area: np.ndarray, distance: float, cells: float = 8.0) -> int: ...


def resolved_area(distance: float, resolution: int, cells: float) -> float: ...


def principled_volume(color: np.ndarray, density: np.ndarray, absorption_color: np.ndarray,
                      emission_strength: np.ndarray, emission_color: np.ndarray) -> dict[str, np.ndarray]: ...


def vdb_grids(path: str) -> list[tuple[str, str]]: ...


def read_vdb_grid(path: str, name: str, object_to_world: np.ndarray, cell_size: float,
                  samples: int = 2) -> dict[str, Any]: ...


def voxelize_mesh(positions: np.ndarray, face_offsets: np.ndarray, corner_vertices: np.ndarray, cell_size: float,
                  samples: int = 2) -> dict[str, Any]: ...


def write_vdb(path: str, origin: np.ndarray, cell_size: float, grids: dict[str, np.ndarray]) -> None: ...
