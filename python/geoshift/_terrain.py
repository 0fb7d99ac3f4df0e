"""Terrain import: LAS / PLY points (2.5D Delaunay, height above ground), GeoTIFF DEMs (grid),
the procedural fractal terrain. Positions are absolute and z-up; write() places them as
`geoshift terrain` does."""
from __future__ import annotations

from typing import Optional, Sequence

import numpy as np

from . import _geoshift as _core
from ._filters import Progress, _options
from ._geoshift import TerrainOptions
from ._mesh import Mesh


def _terrain(d: dict) -> Mesh:
    return Mesh._from_dict(d, z_up=True, report=d["report"])


def read_terrain(path, *, ground_only: bool = False, ground_class: int = 2, geographic_to_meters: bool = True,
                 progress: Progress = None) -> Mesh:
    """A terrain mesh from a file: .las / .ply points (attributes _HEIGHT_ABOVE_GROUND, _CLASS,
    colors) or a .tif / .tiff DEM (_ELEVATION). `report` says what was read and assumed."""
    return _terrain(_core._read_terrain(str(path), ground_only, ground_class, geographic_to_meters, progress))


def point_terrain(points, classes=None, colors=None, *, ground_only: bool = False, ground_class: int = 2,
                  progress: Progress = None) -> Mesh:
    """2.5D Delaunay terrain of points (N, 3), or of the dict read_las returns."""
    if isinstance(points, dict):
        classes = points.get("classes") if classes is None else classes
        colors = points.get("colors") if colors is None else colors
        points = points["positions"]
    return _terrain(_core._point_terrain(points, classes, colors, ground_only, ground_class, progress))


def grid_terrain(values, transform: Sequence[float] = (0, 1, 0, 0, 0, -1), *, geographic: bool = False,
                 geographic_to_meters: bool = True, progress: Progress = None) -> Mesh:
    """A grid terrain of an elevation raster (rows, cols; NaN = nodata), or of the dict
    read_geotiff returns; transform is GDAL's geotransform."""
    if isinstance(values, dict):
        transform = values["transform"]
        geographic = values["geographic"]
        values = values["values"]
    return _terrain(_core._grid_terrain(np.asarray(values, dtype=np.float64), list(transform), geographic,
                                        geographic_to_meters, progress))


def procedural_terrain(size: int = 257, *, progress: Progress = None, **kwargs) -> Mesh:
    """A size x size fractal terrain (fields of TerrainOptions as keywords: seed, cell_size, ...)
    with _VEGETATION_HEIGHT and _CLASS; the same options give the same terrain everywhere."""
    o = _options(TerrainOptions, None, dict(kwargs, size=size))
    return _terrain(_core._procedural_terrain(o, progress))


def read_las(path) -> dict:
    """LAS 1.0-1.4 points: dict of positions (N, 3), classes (N,) or None, colors (N, 3) in [0, 1]
    or None, notes. LAZ is refused with a message (no LASzip in Debian 12)."""
    return _core.read_las(str(path))


def read_ply_points(path) -> dict:
    """A PLY point set (vertex x y z, optional colors and class), as read_las."""
    return _core.read_ply_points(str(path))


def read_geotiff(path) -> dict:
    """A DEM GeoTIFF: dict of values (rows, cols; NaN = nodata), transform (GDAL geotransform),
    geographic, notes."""
    return _core.read_geotiff(str(path))
