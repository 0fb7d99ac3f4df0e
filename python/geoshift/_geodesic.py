"""Geodesics in the caller's numbering: log map (discrete geodesic polar coordinates), exp map
(straightest geodesics), distance fields. Lengths in multiples of the average edge length unless
absolute=True, for input and output alike (as the CLI's logmap / expmap)."""
from __future__ import annotations

from typing import Optional, Sequence, Tuple, Union

from . import _geoshift as _core
from ._mesh import Mesh

Source = Union[int, Tuple[int, Sequence[float]]]


class Geodesics:
    """The log and exp maps of one mesh, set up once (welding, angles, the solver's tables) for
    many calls. A source or start is a vertex index, or (face, (a, b, c)) barycentric. Tangent
    vectors are in the source's frame: geodesic polar at a vertex (angle 0 along one outgoing
    edge), the face's frame elsewhere (x along its first edge)."""

    def __init__(self, mesh: Mesh, *, weld: bool = True):
        self._g = _core._Geodesics(mesh._built(weld))

    @property
    def average_edge_length(self) -> float:
        return self._g.average_edge_length

    def log_map(self, source: Source, radius: float, *, absolute: bool = False) -> dict:
        """Every vertex within `radius`: dict of arrays vertex, distance, angle, x, y (x, y the
        point's coordinates in the source's frame), in order of distance."""
        return self._g.log_map(source, radius, absolute)

    def exp_map(self, start: Source, vector: Optional[Sequence[float]] = None, *,
                toward: Optional[Sequence[float]] = None, length: Optional[float] = None,
                absolute: bool = False, record_path: bool = False) -> dict:
        """Walks the tangent vector (x, y) from start, or `length` along the 3D direction `toward`
        projected onto the start face. Returns face, bary, point, hit_boundary, length,
        faces_crossed (and path with record_path)."""
        return self._g.exp_map(start, vector, toward, length, absolute, record_path)

    def distance_field(self, source: Source, radius: float = 0.0, *, absolute: bool = False):
        """(distance, angle) per vertex from the source, distance -1 beyond radius (0: whole mesh)."""
        return self._g.distance_field(source, radius, absolute)


def log_map(mesh: Mesh, source: Source, radius: float, *, absolute: bool = False) -> dict:
    """Geodesics(mesh).log_map(...) for one call."""
    return Geodesics(mesh).log_map(source, radius, absolute=absolute)


def exp_map(mesh: Mesh, start: Source, vector: Optional[Sequence[float]] = None, **kwargs) -> dict:
    """Geodesics(mesh).exp_map(...) for one call."""
    return Geodesics(mesh).exp_map(start, vector, **kwargs)
