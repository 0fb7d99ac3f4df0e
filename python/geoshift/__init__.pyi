# Type stubs of the geoshift package (the pybind11 module's classes and the Python layer).
from typing import Any, Callable, Dict, Iterable, List, Literal, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

__version__: str

Progress = Optional[Callable[[float, str], Optional[bool]]]
Source = Union[int, Tuple[int, Sequence[float]]]
Kernel = Literal["gaussian", "normal_similarity"]

class InputError(ValueError): ...
class Cancelled(RuntimeError): ...

class ParallelOptions:
    threads: int
    chunk: int
    report_seconds: float
    def __init__(self, *, threads: int = 0, chunk: int = 16, report_seconds: float = 0.1) -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...

class SignalChannel:
    attribute: str
    range_bandwidth: float
    kernel: Kernel
    def __init__(self, *, attribute: str = "", range_bandwidth: float = 0.0, kernel: Kernel = "gaussian") -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...

class MeanShiftOptions:
    channels: List[SignalChannel]
    range_bandwidth: float
    range_kernel: Kernel
    spatial_bandwidth: float
    radius: float
    epsilon: float
    max_iterations: int
    passes: int
    range_update: Literal["sampled", "joint"]
    exact_charts: bool
    recentre: float
    chart_cell: float
    chart_distortion: float
    chart_cache_bytes: int
    area_weighted: bool
    single_precision_kernel: bool
    segments: bool
    parallel: ParallelOptions
    threads: int
    def __init__(self, *, channels: Sequence[Union[SignalChannel, dict, tuple]] = (), range_bandwidth: float = 0.1,
                 range_kernel: Kernel = "gaussian", spatial_bandwidth: float = 3.0, radius: float = 0.0,
                 epsilon: float = 0.2, max_iterations: int = 50, passes: int = 1,
                 range_update: Literal["sampled", "joint"] = "joint", exact_charts: bool = False,
                 recentre: float = 0.25, chart_cell: float = 1.0, chart_distortion: float = 0.1,
                 chart_cache_bytes: int = 1073741824, area_weighted: bool = True,
                 single_precision_kernel: bool = True, segments: bool = False,
                 parallel: Union[ParallelOptions, dict, None] = None, threads: int = 0) -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...

class WaveletOptions:
    levels: int
    cost: Literal["integral", "residual"]
    weights: Literal["mean_value", "inverse_distance", "uniform"]
    boundary_angle: float
    max_normal_change: float
    keep_level_meshes: bool
    whole_index: List[int]
    cost_bounds: List[List[float]]
    def __init__(self, *, levels: int = 2, cost: Literal["integral", "residual"] = "integral",
                 weights: Literal["mean_value", "inverse_distance", "uniform"] = "mean_value",
                 boundary_angle: float = 30.0, max_normal_change: float = 75.0,
                 keep_level_meshes: bool = False, whole_index: Sequence[int] = (),
                 cost_bounds: Sequence[Sequence[float]] = ()) -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...

class TaubinOptions:
    iterations: int
    lambda_: float
    mu: float
    parallel: ParallelOptions
    threads: int
    weights: Literal["uniform", "fujiwara", "cotangent"]
    def __init__(self, *, iterations: int = 10, lambda_: float = 0.5, mu: float = -0.53,
                 parallel: Union[ParallelOptions, dict, None] = None, threads: int = 0,
                 weights: Literal["uniform", "fujiwara", "cotangent"] = "uniform") -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...

class VertexUpdateOptions:
    iterations: int
    area_weighted: bool
    fixed_boundary: bool
    flip_guard: Literal["input", "input_or_target"]
    def __init__(self, *, iterations: int = 20, area_weighted: bool = False, fixed_boundary: bool = False,
                 flip_guard: Literal["input", "input_or_target"] = "input") -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...

class FaceNeighborhoodOptions:
    radius: float
    spatial_bandwidth: float
    parallel: ParallelOptions
    def __init__(self, *, radius: float = 1.75, spatial_bandwidth: float = 0.6,
                 parallel: Union[ParallelOptions, dict, None] = None) -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...

class PaperDenoiseOptions:
    passes: int
    face_normals: Literal["consensus", "mean"]
    consensus_bandwidth: float
    mean_shift: MeanShiftOptions
    support: TaubinOptions
    vertex_update: VertexUpdateOptions
    def __init__(self, *, passes: int = 3, face_normals: Literal["consensus", "mean"] = "consensus",
                 consensus_bandwidth: float = 0.25, mean_shift: Union[MeanShiftOptions, dict, None] = None,
                 support: Union[TaubinOptions, dict, None] = None,
                 vertex_update: Union[VertexUpdateOptions, dict, None] = None) -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...

class DenoiseOptions:
    preset: Literal["default", "paper"]
    noise_level: float
    strength: float
    range_bandwidths: List[float]
    neighborhood: FaceNeighborhoodOptions
    support_smoothing: TaubinOptions
    presmoothing: List[int]
    taubin_only_steps: List[int]
    candidate_taubin: TaubinOptions
    taubin_only_margin: float
    light_start: int
    light_start_turn: float
    blend_spread: float
    max_passes: int
    patience: int
    fixed_passes: int
    vertex_iterations: int
    risk_normal_smoothing: int
    probe_spacing: int
    bounded_divergence: bool
    gradient_risk_weight: float
    tie_probes: int
    tie_margin: float
    tie_standard_errors: float
    tie_by_normals: bool
    input_candidate: bool
    spatial_order: bool
    refine_noise: bool
    detail_bound_ratio: float
    high_frequency_level: bool
    level_lean: float
    high_frequency_min_samples: int
    planar_level_share: float
    planar_keep: float
    halving_race: bool
    impulse_kurtosis: float
    impulse_shrink: float
    impulse_spectrum_kurtosis: float
    impulse_spectrum_min_samples: int
    impulse_spectrum_veto: float
    seed: int
    threads: int
    paper: PaperDenoiseOptions
    min_piece_vertices: int
    levels: int
    alpha: List[float]
    wavelet: WaveletOptions
    def __init__(self, *, preset: Literal["default", "paper"] = "default", noise_level: float = 0.0,
                 strength: float = 1.0, range_bandwidths: Sequence[float] = (0.35, 0.5),
                 neighborhood: Union[FaceNeighborhoodOptions, dict, None] = None,
                 support_smoothing: Union[TaubinOptions, dict, None] = None, presmoothing: Sequence[int] = (3, 15),
                 taubin_only_steps: Sequence[int] = (5, 8, 12, 18, 27, 40, 60, 90),
                 candidate_taubin: Union[TaubinOptions, dict, None] = None, taubin_only_margin: float = 0.005,
                 light_start: int = 1, light_start_turn: float = 1.5, blend_spread: float = 1.0,
                 max_passes: int = 40, patience: int = 4, fixed_passes: int = 0, vertex_iterations: int = 10,
                 risk_normal_smoothing: int = 20, probe_spacing: int = 5, bounded_divergence: bool = True,
                 gradient_risk_weight: float = 0.0,
                 tie_probes: int = 4, tie_margin: float = 0.01, tie_standard_errors: float = 4.0,
                 tie_by_normals: bool = True, input_candidate: bool = True, spatial_order: bool = True,
                 refine_noise: bool = True,
                 detail_bound_ratio: float = 0.9, high_frequency_level: bool = True, level_lean: float = 1.1,
                 high_frequency_min_samples: int = 50, planar_level_share: float = 0.5,
                 planar_keep: float = 0.1, halving_race: bool = True,
                 impulse_kurtosis: float = 6.0, impulse_shrink: float = 2.0,
                 impulse_spectrum_kurtosis: float = 5.5, impulse_spectrum_min_samples: int = 100,
                 impulse_spectrum_veto: float = 4.0,
                 seed: int = 1, threads: int = 0, paper: Union[PaperDenoiseOptions, dict, None] = None,
                 min_piece_vertices: int = 50, levels: int = 0, alpha: Sequence[float] = (0.0,),
                 wavelet: Union[WaveletOptions, dict, None] = None) -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...

class BilateralNormalOptions:
    normal_iterations: int
    sigma_spatial: float
    sigma_range: float
    neighborhood: Literal["vertex", "edge"]
    vertex_update: VertexUpdateOptions
    def __init__(self, *, normal_iterations: int = 20, sigma_spatial: float = 0.0, sigma_range: float = 0.35,
                 neighborhood: Literal["vertex", "edge"] = "vertex",
                 vertex_update: Union[VertexUpdateOptions, dict, None] = None) -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...

class TerrainOptions:
    size: int
    seed: int
    cell_size: float
    relief: float
    roughness: float
    forest_cover: float
    max_vegetation_height: float
    water_level: float
    def __init__(self, *, size: int = 257, seed: int = 1, cell_size: float = 1.0, relief: float = 0.0,
                 roughness: float = 0.5, forest_cover: float = 0.45, max_vegetation_height: float = 30.0,
                 water_level: float = 0.12) -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...

class Mesh:
    positions: np.ndarray
    faces: np.ndarray
    normals: Optional[np.ndarray]
    colors: Optional[np.ndarray]
    attributes: Dict[str, np.ndarray]
    instances: np.ndarray
    label: str
    z_up: bool
    report: Optional[dict]
    def __init__(self, positions: Any, faces: Any, *, normals: Any = None, colors: Any = None,
                 attributes: Optional[Mapping[str, Any]] = None, instances: Any = None, label: str = "mesh",
                 z_up: bool = False, report: Optional[dict] = None) -> None: ...
    @property
    def vertex_count(self) -> int: ...
    @property
    def face_count(self) -> int: ...
    def copy(self) -> Mesh: ...
    def world_positions(self, instance: int = 0) -> np.ndarray: ...

class Document:
    path: str
    format: str
    parts: List[Mesh]
    warnings: List[str]
    @property
    def mesh(self) -> Mesh: ...

def read(path: Any) -> Document: ...
def write(what: Union[Document, Mesh, Iterable[Mesh]], path: Any) -> List[str]: ...

class FilterResult:
    mesh: Mesh
    signal: Dict[str, np.ndarray]
    channels: List[Tuple[str, float]]
    iterations: np.ndarray
    converged: np.ndarray
    vertex_counts: List[int]
    mean_iterations: float
    max_iterations: int
    converged_fraction: float
    threads: int
    seconds: float
    start_charts: int
    charts_computed: int
    segment: Optional[np.ndarray]
    segment_count: int

class DenoiseResult:
    mesh: Mesh
    stats: dict

def presets() -> Dict[str, dict]: ...
def param_specs() -> Dict[str, dict]: ...
def mean_shift(mesh: Mesh, signal: Union[str, Sequence[str], Mapping[str, np.ndarray], None] = None, *,
               preset: Optional[str] = None, levels: Optional[int] = None,
               alpha: Union[float, Sequence[float], None] = None, filter_geometry: bool = False,
               wavelet: Union[WaveletOptions, dict, None] = None, unit_vectors: Sequence[str] = (),
               weld: bool = True, unit: Optional[float] = None, progress: Progress = None,
               options: Union[MeanShiftOptions, dict, None] = None,
               channels: Sequence[Union[SignalChannel, dict, tuple]] = ..., range_bandwidth: float = ...,
               range_kernel: Kernel = ..., spatial_bandwidth: float = ..., radius: float = ...,
               epsilon: float = ..., max_iterations: int = ..., passes: int = ...,
               range_update: Literal["sampled", "joint"] = ..., exact_charts: bool = ..., recentre: float = ...,
               chart_cell: float = ..., chart_distortion: float = ..., chart_cache_bytes: int = ...,
               area_weighted: bool = ..., single_precision_kernel: bool = ..., segments: bool = ...,
               parallel: Union[ParallelOptions, dict] = ..., threads: int = ...) -> FilterResult: ...
def denoise(mesh: Mesh, *, weld: bool = True, progress: Progress = None,
            options: Union[DenoiseOptions, dict, None] = None,
            method: Literal["meanshift", "bilateral", "taubin"] = ..., preset: Literal["default", "paper"] = ...,
            **parameters_or_fields: Any) -> DenoiseResult: ...
def bilateral_normal_denoise(mesh: Mesh, *, weld: bool = True, progress: Progress = None,
                             options: Union[BilateralNormalOptions, dict, None] = None, **fields: Any) -> DenoiseResult: ...
def taubin_smooth(mesh: Mesh, *, weld: bool = True, progress: Progress = None,
                  options: Union[TaubinOptions, dict, None] = None, **fields: Any) -> Mesh: ...
def curvatures(mesh: Mesh, *, weld: bool = True) -> Dict[str, np.ndarray]: ...
def curvature(mesh: Mesh, kind: Literal["absolute", "mean", "gaussian", "rms"] = "absolute", *,
              weld: bool = True) -> np.ndarray: ...
def color_map(values: Any) -> np.ndarray: ...
def spread_bandwidth(values: Any) -> float: ...

class Multiresolution:
    vertex_counts: List[int]
    level_count: int
    coarse_to_mesh: np.ndarray
    cost_bounds: List[List[float]]
    coarse: Mesh
    def synthesize(self, alpha: Union[float, Sequence[float]] = 0.0, coarse_positions: Any = None,
                   coarse_attributes: Optional[Mapping[str, np.ndarray]] = None, progress: Progress = None) -> Mesh: ...

def analyze(mesh: Mesh, attributes: Union[Sequence[str], Mapping[str, np.ndarray], None] = None, *,
            unit_vectors: Sequence[str] = (), weld: bool = True, progress: Progress = None,
            options: Union[WaveletOptions, dict, None] = None, **fields: Any) -> Multiresolution: ...
def synthesize(analysis: Multiresolution, alpha: Union[float, Sequence[float]] = 0.0, coarse_positions: Any = None,
               coarse_attributes: Optional[Mapping[str, np.ndarray]] = None, progress: Progress = None) -> Mesh: ...
def wavelet_filter(mesh: Mesh, levels: int = 2, alpha: Union[float, Sequence[float]] = 0.0, *,
                   positions_only: bool = False, weld: bool = True, progress: Progress = None) -> Mesh: ...

class Geodesics:
    def __init__(self, mesh: Mesh, *, weld: bool = True) -> None: ...
    @property
    def average_edge_length(self) -> float: ...
    def log_map(self, source: Source, radius: float, *, absolute: bool = False) -> Dict[str, np.ndarray]: ...
    def exp_map(self, start: Source, vector: Optional[Sequence[float]] = None, *,
                toward: Optional[Sequence[float]] = None, length: Optional[float] = None, absolute: bool = False,
                record_path: bool = False) -> Dict[str, Any]: ...
    def distance_field(self, source: Source, radius: float = 0.0, *,
                       absolute: bool = False) -> Tuple[np.ndarray, np.ndarray]: ...

def log_map(mesh: Mesh, source: Source, radius: float, *, absolute: bool = False) -> Dict[str, np.ndarray]: ...
def exp_map(mesh: Mesh, start: Source, vector: Optional[Sequence[float]] = None, **kwargs: Any) -> Dict[str, Any]: ...

def read_las(path: Any) -> Dict[str, Any]: ...
def read_ply_points(path: Any) -> Dict[str, Any]: ...
def read_geotiff(path: Any) -> Dict[str, Any]: ...
def height_above_ground(ground: Any, points: Any) -> np.ndarray: ...
def delaunay_2d(points: Any) -> Tuple[np.ndarray, np.ndarray]: ...
def read_terrain(path: Any, *, ground_only: bool = False, ground_class: int = 2, geographic_to_meters: bool = True,
                 progress: Progress = None) -> Mesh: ...
def point_terrain(points: Any, classes: Any = None, colors: Any = None, *, ground_only: bool = False,
                  ground_class: int = 2, progress: Progress = None) -> Mesh: ...
def grid_terrain(values: Any, transform: Sequence[float] = (0, 1, 0, 0, 0, -1), *, geographic: bool = False,
                 geographic_to_meters: bool = True, progress: Progress = None) -> Mesh: ...
def procedural_terrain(size: int = 257, *, progress: Progress = None, seed: int = 1, cell_size: float = 1.0,
                       relief: float = 0.0, roughness: float = 0.5, forest_cover: float = 0.45,
                       max_vegetation_height: float = 30.0, water_level: float = 0.12) -> Mesh: ...
