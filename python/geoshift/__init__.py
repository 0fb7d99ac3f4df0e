"""geoshift: Riemannian mean shift and blurring mean shift of signals on triangle meshes
(normals, colors, curvature, terrain attributes), graph-wavelet multiresolution and the hybrid
filter, terrain import, geodesics. Arrays in and out are numpy: positions float64 (N, 3), faces
int32 (M, 3), attributes (N,) or (N, dim) by name. Long calls release the GIL, take a progress
callback and stop on Ctrl-C. Bad input raises geoshift.InputError (a ValueError) with the core's
message. geoshift.tiles filters terrains and meshes too large for one machine on Dask.
"""
from ._geoshift import (BilateralNormalOptions, Cancelled, DenoiseOptions, FaceNeighborhoodOptions, InputError,
                        MeanShiftOptions, PaperDenoiseOptions, ParallelOptions, SignalChannel, TaubinOptions, TerrainOptions, VertexUpdateOptions,
                        WaveletOptions, color_map, delaunay_2d, height_above_ground, spread_bandwidth)
from ._filters import (DenoiseResult, FilterResult, Multiresolution, analyze, bilateral_normal_denoise, curvature,
                       curvatures, denoise, mean_shift, param_specs, presets, synthesize, taubin_smooth,
                       wavelet_filter)
from ._geodesic import Geodesics, exp_map, log_map
from ._mesh import Document, Mesh, read, write
from ._terrain import (grid_terrain, point_terrain, procedural_terrain, read_geotiff, read_las, read_ply_points,
                       read_terrain)

__version__ = "0.1.0"

__all__ = [
    "BilateralNormalOptions", "Cancelled", "DenoiseOptions", "DenoiseResult", "Document", "FaceNeighborhoodOptions",
    "FilterResult", "Geodesics", "InputError", "MeanShiftOptions", "Mesh", "Multiresolution", "PaperDenoiseOptions", "ParallelOptions", "SignalChannel",
    "TaubinOptions", "TerrainOptions", "VertexUpdateOptions", "WaveletOptions", "analyze",
    "bilateral_normal_denoise", "color_map", "curvature", "curvatures", "delaunay_2d", "denoise", "exp_map",
    "grid_terrain", "height_above_ground", "log_map", "mean_shift", "param_specs", "point_terrain", "presets",
    "procedural_terrain", "read", "read_geotiff", "read_las", "read_ply_points", "read_terrain",
    "spread_bandwidth", "synthesize", "taubin_smooth", "wavelet_filter", "write",
]
