"""Mean shift and the hybrid filter, denoising, smoothing, wavelets, curvature."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _geoshift as _core
from ._geoshift import (BilateralNormalOptions, DenoiseOptions, InputError, MeanShiftOptions, TaubinOptions,
                        WaveletOptions)
from ._mesh import Mesh

Progress = Optional[Callable[[float, str], Optional[bool]]]


def _options(cls, base=None, values: Optional[Mapping] = None):
    """An options object: `base` (an instance, a dict or None for the defaults) with `values` set."""
    o = cls() if base is None else (cls(**base) if isinstance(base, dict) else cls(**base.to_dict()))
    if values:
        _core._apply_options(o, dict(values))
    return o


def presets() -> Dict[str, dict]:
    """The named parameter sets (the paper's and ours): name -> description, signal, options
    (MeanShiftOptions), levels and alpha of the hybrid filter."""
    return {p["name"]: p for p in _core._presets()}


def _signal_names(signal) -> List[str]:
    if isinstance(signal, str):
        return [s for s in signal.split(",") if s]
    return [str(s) for s in signal]


@dataclass
class FilterResult:
    """What mean_shift returns. `mesh` is the input with the result written back as `geoshift
    filter` writes a file: colors for "color", normals for "normal", the attribute (and a color map)
    for "curvature" ("_CURVATURE"), the attribute itself otherwise, "_SEGMENT" with segments, and
    the positions with filter_geometry. `signal` holds the filtered channels by name, per vertex.
    `iterations` and `converged` are per filtered vertex: the mesh's (caller layout) without levels,
    the coarse mesh's with levels."""
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
    segment: Optional[np.ndarray] = None
    segment_count: int = 0


def mean_shift(mesh: Mesh, signal: Union[str, Sequence[str], Mapping[str, np.ndarray], None] = None, *,
               preset: Optional[str] = None, levels: Optional[int] = None,
               alpha: Union[float, Sequence[float], None] = None, filter_geometry: bool = False,
               wavelet: Union[WaveletOptions, dict, None] = None, unit_vectors: Sequence[str] = (),
               weld: bool = True, unit: Optional[float] = None, progress: Progress = None,
               options: Union[MeanShiftOptions, dict, None] = None, **kwargs) -> FilterResult:
    """Riemannian mean shift (passes=1) or blurring mean shift (passes>1) of a vertex signal; with
    levels > 0 the hybrid filter (wavelet analysis, the mean shift on the coarse mesh, synthesis
    with detail gain alpha per level, finest first, or one for all).

    signal: "color" (RGB of the colors), "normal" (vertex normals, eq. 8 kernel), "curvature"
    (absolute), "terrain" (_HEIGHT_ABOVE_GROUND or _VEGETATION_HEIGHT, with _CLASS), the name of an
    attribute (with or without its leading "_"), several of these (a list or "a,b"), or a dict of
    arrays (N,) / (N, dim) filtered together (names in unit_vectors are unit vectors). Default:
    the preset's signal, else "color".

    Keyword arguments are the fields of MeanShiftOptions with the library's defaults (see
    MeanShiftOptions; also `threads`), over the preset's when one is named (color, curvature-ms,
    curvature-bms, terrain-ms, terrain-bms). Without range_bandwidth or a preset each signal gets
    its own h_r: color 0.1, normal 0.45, otherwise a tenth of its 10-90% spread.

    unit: spatial options in multiples of this length instead of the (coarse) mesh's average edge
    length, so that pieces of one surface filter alike (geoshift.tiles). progress(fraction, stage)
    is called from the calling thread; returning False cancels (geoshift.Cancelled). The GIL is
    released while the core computes; Ctrl-C stops the run and raises KeyboardInterrupt.
    """
    base = None
    range_given = False
    preset_levels, preset_alpha = 0, 0.0
    if preset is not None:
        _core._preset(preset)  # InputError listing the known names
        p = presets()[preset]
        base = p["options"]
        range_given = True
        if signal is None:
            signal = p["signal"]
        preset_levels, preset_alpha = p["levels"], p["alpha"]
    o = _options(MeanShiftOptions, base if options is None else options, kwargs)
    # An options object, or range_bandwidth named anywhere, fixes h_r for every channel.
    if isinstance(options, MeanShiftOptions) or "range_bandwidth" in kwargs or "range_bandwidth" in (options or {}):
        range_given = True
    levels = preset_levels if levels is None else int(levels)
    alpha = preset_alpha if alpha is None else alpha
    alpha = [float(a) for a in (alpha if isinstance(alpha, (list, tuple, np.ndarray)) else [alpha])]
    attributes = dict(mesh.attributes)
    if signal is None:
        signal = "color"
    if isinstance(signal, Mapping):
        for name, values in signal.items():
            attributes[str(name)] = values
        names = [str(n) for n in signal]
    else:
        names = _signal_names(signal)
    built = mesh._built(weld)
    r = _core._mean_shift(built, names, mesh.colors, attributes, list(unit_vectors), o, range_given, levels, alpha,
                          filter_geometry, _options(WaveletOptions, wavelet), float(unit or 0), progress)

    out = mesh.copy()
    filtered = {}
    for kind, name, values in r["signals"]:
        filtered[name] = values
        if kind == "color":
            if out.colors is None:
                out.colors = np.ones((mesh.vertex_count, 4))
            out.colors[:, :3] = values
        elif kind == "normal":
            out.normals = values.copy()
        else:
            if kind == "curvature":
                out.colors = np.hstack([_core.color_map(values), np.ones((mesh.vertex_count, 1))])
            out.attributes.pop(name, None)
            out.attributes[name] = values
    if filter_geometry:
        out.positions = r["positions"]
    segment = r.get("segment")
    if segment is not None:
        out.attributes.pop("_SEGMENT", None)
        out.attributes["_SEGMENT"] = segment.astype(np.float64)
    return FilterResult(mesh=out, signal=filtered, channels=[tuple(c) for c in r["channels"]],
                        iterations=r["iterations"], converged=r["converged"].astype(bool),
                        vertex_counts=list(r["vertex_counts"]), mean_iterations=r["mean_iterations"],
                        max_iterations=r["max_iterations"], converged_fraction=r["converged_fraction"],
                        threads=r["threads"], seconds=r["seconds"], start_charts=r["start_charts"],
                        charts_computed=r["charts_computed"], segment=segment,
                        segment_count=r.get("segment_count", 0))


@dataclass
class DenoiseResult:
    """A denoised mesh (positions moved; normals recomputed when the input had normals) and the
    run's figures."""
    mesh: Mesh
    stats: dict = field(default_factory=dict)


def _moved(mesh: Mesh, positions: np.ndarray) -> Mesh:
    # As the CLI writes a moved part back: positions, and normals (if any) on its own faces.
    out = mesh.copy()
    out.positions = positions
    if out.normals is not None:
        n = _core._vertex_normals(positions, mesh.faces)
        keep = np.einsum("ij,ij->i", n, n) > 0
        out.normals[keep] = n[keep]
    return out


def param_specs() -> Dict[str, dict]:
    """Every op's parameter table, as the CLI, the wasm module (paramSpecs()) and denoise() read it:
    op -> {doc, params: name -> {type, doc, default, min, max, minExclusive, values, list, when,
    cases}} (keys present only when they say something; docs/architecture.md#parameters)."""
    return _core._param_specs()


def _request_name(keyword: str) -> str:
    """A keyword in Python's spelling as the request's parameter name: vertex_iterations ->
    vertexIterations, lambda_ -> lambda."""
    head, *rest = keyword.rstrip("_").split("_")
    return head + "".join(w[:1].upper() + w[1:] for w in rest)


def denoise(mesh: Mesh, *, weld: bool = True, progress: Progress = None,
            options: Union[DenoiseOptions, dict, None] = None, **kwargs) -> DenoiseResult:
    """Mesh denoising (docs/denoising.md), as `geoshift denoise`. The default: the noise level is
    estimated from the mesh, face normals are filtered by blurring mean shift over geodesic
    neighbourhoods, the vertices follow, and the amount of smoothing is chosen by Stein's unbiased
    risk estimate; preset="paper" runs the paper's 4.1 pipeline; method="bilateral" or "taubin"
    the baselines.

    Keyword arguments are the parameters of the CLI's command and the wasm op, in snake_case
    (method, preset, noise, strength, hs, hr, radius, passes, vertex_iterations, sigma_s, ...;
    param_specs()["denoise"] lists them with defaults and ranges): the core checks them as it does
    for the CLI and the wasm op, so a parameter of another method or preset is refused with the
    same message. Fields of DenoiseOptions that are no such parameter (fixed_passes, noise_level,
    paper=dict(passes=2), ...) set the options directly, over `options`; levels > 0 denoises a
    wavelet-coarsened mesh. stats holds what was estimated and chosen."""
    names = param_specs()["denoise"]["params"]
    request, fields = {}, {}
    for key, value in kwargs.items():
        name = _request_name(key)
        if name in names:
            request[name] = value
        else:
            fields[key] = value
    o = _options(DenoiseOptions, options, fields)
    # The request decides the preset: an options object's own stands unless one is given.
    if "preset" not in request and o.preset == "paper" and request.get("method", "meanshift") == "meanshift":
        request["preset"] = "paper"
    r = _core._denoise(mesh._built(weld), request, o, progress)
    stats = {k: v for k, v in r.items() if k != "positions"}
    return DenoiseResult(_moved(mesh, r["positions"]), stats)


def bilateral_normal_denoise(mesh: Mesh, *, weld: bool = True, progress: Progress = None,
                             options: Union[BilateralNormalOptions, dict, None] = None, **kwargs) -> DenoiseResult:
    """Bilateral normal filtering (Zheng et al. 2011) and the vertex update; a baseline."""
    o = _options(BilateralNormalOptions, options, kwargs)
    r = _core._bilateral(mesh._built(weld), o, progress)
    return DenoiseResult(_moved(mesh, r["positions"]), {k: v for k, v in r.items() if k != "positions"})


def taubin_smooth(mesh: Mesh, *, weld: bool = True, progress: Progress = None,
                  options: Union[TaubinOptions, dict, None] = None, **kwargs) -> Mesh:
    """Taubin lambda|mu smoothing (not feature-preserving); fields of TaubinOptions as keywords."""
    o = _options(TaubinOptions, options, kwargs)
    return _moved(mesh, _core._taubin(mesh._built(weld), o, progress))


def curvatures(mesh: Mesh, *, weld: bool = True) -> Dict[str, np.ndarray]:
    """Discrete curvatures per vertex as MeshLab computes them: mean, gaussian, absolute
    (|k1|+|k2|), rms, and the mixed Voronoi area."""
    return _core._curvatures(mesh._built(weld))


def curvature(mesh: Mesh, kind: str = "absolute", *, weld: bool = True) -> np.ndarray:
    """One kind of curvature per vertex: absolute, mean, gaussian or rms."""
    k = curvatures(mesh, weld=weld)
    if kind not in ("absolute", "mean", "gaussian", "rms"):
        raise InputError(f"kind must be one of absolute, mean, gaussian, rms (got '{kind}')")
    return k[kind]


class Multiresolution:
    """A lifting wavelet analysis of a mesh (positions and attributes): the coarse mesh with its
    lifted attributes, and the details to synthesise the fine mesh from (filtered) coarse values."""

    def __init__(self, handle, mesh: Mesh):
        self._handle = handle
        self._mesh = mesh
        self.vertex_counts: List[int] = list(handle.vertex_counts)
        self.level_count: int = handle.level_count
        self.coarse_to_mesh: np.ndarray = handle.coarse_to_mesh
        # per level, the cost-band bounds its candidate order used (WaveletOptions.cost_bounds)
        self.cost_bounds: List[List[float]] = handle.cost_bounds
        self.coarse = Mesh(handle.coarse_positions, handle.coarse_faces, attributes=handle.coarse_attributes,
                           label=mesh.label + " (coarse)")

    def synthesize(self, alpha: Union[float, Sequence[float]] = 0.0, coarse_positions=None,
                   coarse_attributes: Optional[Mapping[str, np.ndarray]] = None,
                   progress: Progress = None) -> Mesh:
        """The fine mesh from coarse positions and attributes (default: the analysis' own) with
        detail gain alpha per level (finest first) or one for all: 1 restores, 0 drops, > 1 enhances."""
        alpha = [float(a) for a in (alpha if isinstance(alpha, (list, tuple, np.ndarray)) else [alpha])]
        r = _core._synthesize(self._handle, coarse_positions, coarse_attributes, alpha, progress)
        out = self._mesh.copy()
        out.positions = r["positions"]
        out.attributes.update(r["attributes"])
        return out


def analyze(mesh: Mesh, attributes: Union[Sequence[str], Mapping[str, np.ndarray], None] = None, *,
            unit_vectors: Sequence[str] = (), weld: bool = True, progress: Progress = None,
            options: Union[WaveletOptions, dict, None] = None, **kwargs) -> Multiresolution:
    """Lifting wavelet analysis (fields of WaveletOptions as keywords: levels=2, ...) of the
    positions and the named attributes of the mesh (or a dict of arrays)."""
    if attributes is None:
        attrs = {}
    elif isinstance(attributes, Mapping):
        attrs = dict(attributes)
    else:
        attrs = {name: mesh.attributes[name] for name in attributes}
    o = _options(WaveletOptions, options, kwargs)
    built = mesh._built(weld)
    return Multiresolution(_core._analyze(built, attrs, list(unit_vectors), o, progress), mesh)


def synthesize(analysis: Multiresolution, alpha: Union[float, Sequence[float]] = 0.0, coarse_positions=None,
               coarse_attributes=None, progress: Progress = None) -> Mesh:
    """Same as analysis.synthesize(...)."""
    return analysis.synthesize(alpha, coarse_positions, coarse_attributes, progress)


def wavelet_filter(mesh: Mesh, levels: int = 2, alpha: Union[float, Sequence[float]] = 0.0, *,
                   positions_only: bool = False, weld: bool = True, progress: Progress = None) -> Mesh:
    """Multiresolution smoothing (alpha < 1) or enhancement (alpha > 1) of the positions and colors,
    as `geoshift wavelet` does it."""
    if levels < 0:
        raise InputError(f"levels must be >= 0 (got {levels})")
    alpha = [float(a) for a in (alpha if isinstance(alpha, (list, tuple, np.ndarray)) else [alpha])]
    if len(alpha) not in (1, levels):
        raise InputError(f"alpha has {len(alpha)} values for {levels} levels; give one value or one per level")
    r = _core._wavelet_filter(mesh._built(weld), mesh.colors, levels, alpha, positions_only, progress)
    out = _moved(mesh, r["positions"])
    if "colors" in r:
        out.colors = r["colors"]
    return out
