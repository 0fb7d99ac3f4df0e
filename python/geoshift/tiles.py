"""Tiled filtering on Dask: a terrain (DEM raster, LAS / PLY point set, procedural) or a large mesh
cut into tiles with a halo as wide as the filter's reach (docs/tiles.md derives it), one Dask task
a tile, the tiles' interiors stitched back into one result; and batches of files, one task a file.

    python -m geoshift.tiles IN -o OUT --preset terrain-bms --tile 2000 [--scheduler ADDRESS]

runs on a LocalCluster of this machine by default, on any Dask cluster given its address. The
output is written only when every tile has succeeded (atomically: a temporary file renamed), so it
appears whole or not at all; a worker that dies mid-run has its tiles recomputed elsewhere.
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import tempfile
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Sequence

import numpy as np

import geoshift
from . import _geoshift as _core
from ._filters import _options, presets
from ._geoshift import InputError, MeanShiftOptions

MESH_FORMATS = (".gltf", ".glb", ".obj", ".off")
RASTER_FORMATS = (".tif", ".tiff")
POINT_FORMATS = (".las", ".laz", ".ply")


# --- the request -------------------------------------------------------------------------------

@dataclass
class FilterRequest:
    """What every tile runs: mean_shift(mesh, signal, preset=..., levels=..., alpha=..., **options)."""
    signal: Optional[str] = None
    preset: Optional[str] = None
    levels: Optional[int] = None
    alpha: Optional[float] = None
    options: Dict[str, object] = field(default_factory=dict)

    def resolved(self):
        """(MeanShiftOptions, levels, alpha, signal) as mean_shift will use them."""
        base, levels, alpha, signal = None, 0, 0.0, "color"
        if self.preset is not None:
            _core._preset(self.preset)
            p = presets()[self.preset]
            base, levels, alpha, signal = p["options"], p["levels"], p["alpha"], p["signal"]
        o = _options(MeanShiftOptions, base, self.options)
        return (o, levels if self.levels is None else self.levels, alpha if self.alpha is None else self.alpha,
                signal if self.signal is None else self.signal)

    def run(self, mesh: geoshift.Mesh, unit: float, progress=None, wavelet=None) -> geoshift.FilterResult:
        return geoshift.mean_shift(mesh, self.signal, preset=self.preset, levels=self.levels, alpha=self.alpha,
                                   unit=unit, progress=progress, wavelet=wavelet, **self.options)


# --- the reach of a filter (docs/tiles.md) -------------------------------------------------------

# Levels of the hybrid filter: the coarse mesh's AEL is about this many times the input's per level
# (a level removes 20-35% of the vertices: 1/sqrt(0.7) ~ 1.2). Used to size tiles before any
# analysis; the filter itself uses the measured coarse AEL.
COARSENING_PER_LEVEL = 1.2


@dataclass
class Reach:
    """How far a filtered value may depend on the input, in absolute units (docs/tiles.md)."""
    bandwidth: float      # h_s
    radius: float         # r, the kernel's truncation radius
    climb: float          # how far an iterate may travel in one pass, bounded by k_max steps of at most r
    passes: int
    wavelet: float        # the hybrid filter's analysis and synthesis footprint
    bound: float          # the worst case: P (r + climb) + wavelet
    halo: float           # the halo used (filter_reach)

    def describe(self) -> str:
        return (f"h_s {self.bandwidth:.4g}, r {self.radius:.4g}, climb <= {self.climb:.4g} a pass, {self.passes} "
                f"pass(es), wavelet {self.wavelet:.4g}: worst-case reach {self.bound:.4g}, halo {self.halo:.4g}")


def filter_reach(options: MeanShiftOptions, levels: int, unit: float, fine_unit: float) -> Reach:
    """The reach of mean shift with these options whose spatial unit is `unit` (the coarse mesh's AEL
    with levels > 0) on an input of AEL `fine_unit` (docs/tiles.md).

    Worst case: a pass reads samples within r of its iterate, which climbs at most k_max steps of at
    most r, so P passes depend on data up to P (r + k_max r) away (terrain-bms: 900 coarse AEL).
    The halo used: r, which the first pass reads in full, plus max(r, h_s sqrt(P)), the width of the
    Gaussian that P blurring passes compose into (beyond it the missing outside weighs little and
    the range kernel cuts it further), plus the wavelet footprint (one ring of each level's mesh,
    twice for the odd/even choices near the cut). Measured: with it, differences near tile borders
    are below the filter's own noise (docs/tiles.md)."""
    hs = options.spatial_bandwidth * unit
    r = (options.radius if options.radius > 0 else 3 * options.spatial_bandwidth) * unit
    passes = max(1, options.passes)
    climb = options.max_iterations * r
    wavelet = 2.0 * levels * unit + 2.0 * fine_unit
    bound = passes * (r + climb) + wavelet
    halo = min(bound, r + max(r, hs * math.sqrt(passes)) + wavelet)
    return Reach(hs, r, climb, passes, wavelet, bound, halo)


# --- tiles -------------------------------------------------------------------------------------

@dataclass
class Tile:
    index: int
    name: str               # "tile (col, row)" for messages
    lo: np.ndarray          # core box, inclusive low
    hi: np.ndarray          # core box, exclusive high
    vertices: np.ndarray    # global vertex ids in the expanded box (sorted)
    owned: np.ndarray       # bool per entry of vertices: in the core box


def _boxes(points: np.ndarray, side: float):
    lo = points.min(axis=0)
    hi = points.max(axis=0)
    counts = np.maximum(1, np.ceil((hi - lo) / side).astype(int))
    counts[2] = 1 if (hi[2] - lo[2]) <= side else counts[2]
    return lo, hi, counts


def cut(mesh: geoshift.Mesh, side: float, halo: float) -> List[Tile]:
    """Tiles of `side` (absolute; in x, y, and z when the mesh is taller than a tile) over the
    mesh's vertices, each with the vertices within `halo` of its box. Every vertex is owned by one
    tile. Tiles owning no vertex are dropped."""
    p = mesh.positions
    lo, hi, counts = _boxes(p, side)
    cell = np.minimum(((p - lo) // side).astype(np.int64), counts - 1)
    cell[:, 2] = np.minimum(cell[:, 2], counts[2] - 1) if counts[2] > 1 else 0
    tiles = []
    for iz in range(counts[2]):
        for iy in range(counts[1]):
            for ix in range(counts[0]):
                key = np.array([ix, iy, iz])
                owned_mask = np.all(cell == key, axis=1)
                if not owned_mask.any():
                    continue
                blo = lo + key * side
                bhi = blo + side
                if counts[2] == 1:
                    blo[2], bhi[2] = -np.inf, np.inf
                inside = np.all((p >= blo - halo) & (p <= bhi + halo), axis=1)
                vertices = np.flatnonzero(inside | owned_mask)
                name = f"tile ({ix}, {iy})" if counts[2] == 1 else f"tile ({ix}, {iy}, {iz})"
                tiles.append(Tile(len(tiles), name, blo, bhi, vertices, owned_mask[vertices]))
    return tiles


def submesh(mesh: geoshift.Mesh, tile: Tile) -> geoshift.Mesh:
    """The faces of the mesh whose three vertices are in the tile, renumbered, with their data."""
    local = np.full(mesh.vertex_count, -1, dtype=np.int64)
    local[tile.vertices] = np.arange(len(tile.vertices))
    f = local[mesh.faces]
    faces = f[np.all(f >= 0, axis=1)]
    take = tile.vertices
    return geoshift.Mesh(mesh.positions[take], faces,
                         normals=None if mesh.normals is None else mesh.normals[take],
                         colors=None if mesh.colors is None else mesh.colors[take],
                         attributes={k: v[take] for k, v in mesh.attributes.items()},
                         label=f"{mesh.label} {tile.name}")


def _whole_order(whole_index: Optional[np.ndarray], bounds) -> geoshift.WaveletOptions:
    """The wavelet options under which a tile's analysis removes, inside the tile, the vertices the
    whole's analysis removes: its vertices' indices in the whole and the whole's cost-band bounds
    (docs/tiles.md#the-wavelet-order)."""
    w = geoshift.WaveletOptions()
    if whole_index is not None:
        w.whole_index = whole_index
    if bounds is not None:
        w.cost_bounds = bounds
    return w


def _edge_stats(piece: geoshift.Mesh, owned: np.ndarray, levels: int, name: str,
                whole_index: Optional[np.ndarray] = None):
    """(sum, count, cost bounds per level) of the piece's coarse edges with an owned end."""
    try:
        return _core._coarse_edge_stats(piece._built(), levels, _whole_order(whole_index, None),
                                        owned.astype(np.float64), None)
    except InputError as e:
        raise InputError(f"{name}: {e}") from None


def _filter_tile(piece: geoshift.Mesh, owned: np.ndarray, whole_index: np.ndarray, request: FilterRequest,
                 unit: float, bounds, name: str, threads: int):
    """One task: the filtered channels (and positions) of the tile's owned vertices. whole_index
    (the tile's vertices' indices in the whole) and bounds (the whole's cost bands, or None) make its
    wavelet analysis follow the whole's."""
    try:
        req = FilterRequest(request.signal, request.preset, request.levels, request.alpha,
                            dict(request.options, threads=threads))
        r = req.run(piece, unit, wavelet=_whole_order(whole_index, bounds))
    except InputError as e:
        raise InputError(f"{name}: {e}") from None
    out = {name_: values[owned] for name_, values in r.signal.items()}
    kinds = {}
    if r.mesh.colors is not None and piece.colors is not None:
        kinds["__colors__"] = r.mesh.colors[owned]
    if r.mesh.normals is not None:
        kinds["__normals__"] = r.mesh.normals[owned]
    attrs = {k: v[owned] for k, v in r.mesh.attributes.items()}
    return {"signal": out, "attributes": attrs, "extra": kinds, "positions": r.mesh.positions[owned],
            "iterations": r.mean_iterations, "vertices": int(owned.sum()), "seconds": r.seconds,
            "coarse": r.vertex_counts[-1], "pid": os.getpid()}


@dataclass
class TiledResult:
    mesh: geoshift.Mesh          # the input with every tile's interior written back
    tiles: List[Tile]
    reach: Reach
    unit: float                  # the spatial unit every tile used (the whole's coarse AEL)
    fine_unit: float
    seconds: float
    tile_seconds: List[float]
    halo_vertices: int           # vertices filtered in all tiles, halos included
    workers: List[int]           # pid of the worker of each tile


def _client(scheduler=None, workers: int = 2, threads: int = 1):
    import distributed
    if scheduler is not None and not isinstance(scheduler, str):
        return scheduler, None  # a Client
    if scheduler:
        return distributed.Client(scheduler), None
    cluster = distributed.LocalCluster(n_workers=workers, threads_per_worker=threads, processes=True,
                                       dashboard_address=None, silence_logs=40)
    return distributed.Client(cluster), cluster


def filter_mesh_tiled(mesh: geoshift.Mesh, request: FilterRequest, tile: float, client, *,
                      halo: Optional[float] = None, threads: int = 1, unit: str = "whole", log=None) -> TiledResult:
    """Filters the mesh tile by tile on the Dask client. `tile` is the tile side in average edge
    lengths of the mesh (about tile x tile vertices on a terrain); `halo` (absolute) overrides the
    derived one. The spatial unit of every tile is the whole mesh's coarse AEL, as the untiled
    filter's: unit="whole" analyses the whole mesh here for it (exact), "tiles" sums the tiles' own
    coarse edges (no whole analysis; off by ~0.1%, which moves the result by the filter's own noise
    under such a bandwidth change). Raises the first tile's error (naming the tile); nothing is
    returned then."""
    start = time.perf_counter()
    options, levels, alpha, signal = request.resolved()
    built = mesh._built()
    fine = built.average_edge_length
    est_unit = fine * COARSENING_PER_LEVEL ** levels
    reach = filter_reach(options, levels, est_unit, fine)
    side = tile * fine
    tiles = cut(mesh, side, reach.halo if halo is None else halo)
    pieces = [submesh(mesh, t) for t in tiles]
    if log:
        log(f"{len(tiles)} tiles of {side:.4g} (tile {tile} x AEL {fine:.4g}), halo {reach.halo:.4g}; "
            f"{sum(len(t.vertices) for t in tiles)} vertices with halos for {mesh.vertex_count}")
    # 1. The unit of the spatial options, the whole surface's coarse AEL, and the cost bands of the
    # whole's wavelet analysis, which the tiles' analyses follow (docs/tiles.md#the-wavelet-order).
    if unit == "whole":
        stats = [_edge_stats(mesh, np.ones(mesh.vertex_count, dtype=bool), levels, mesh.label)]
        bounds = stats[0][2]
    else:
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", message="Large object of size")
            stats = client.gather([client.submit(_edge_stats, pieces[t.index], t.owned, levels, t.name, t.vertices,
                                                 pure=False) for t in tiles])
        bounds = None  # each tile its own: the whole's need the whole's analysis
    unit = sum(s[0] for s in stats) / max(1e-300, sum(s[1] for s in stats))
    estimated = reach
    reach = filter_reach(options, levels, unit, fine)
    if halo is None and reach.halo > estimated.halo:
        # the measured coarse AEL reaches farther than the estimate: cut again with the real halo
        tiles = cut(mesh, side, reach.halo)
        pieces = [submesh(mesh, t) for t in tiles]
    if log:
        log(f"coarse AEL {unit:.4g} ({levels} levels); {reach.describe()}")
    # 2. The filter, one task a tile. The tiles travel in the task graph, not scattered: a task whose
    # worker dies is re-run elsewhere from it (scattered data would die with the worker).
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="Large object of size")
        futures = [client.submit(_filter_tile, pieces[t.index], t.owned, t.vertices, request, unit, bounds, t.name,
                                 threads, pure=False) for t in tiles]
    if log:
        import distributed
        for k, _ in enumerate(distributed.as_completed(futures), 1):
            log(f"{k}/{len(futures)} tiles done")
    results = client.gather(futures)
    # 3. Stitch: every vertex from the tile that owns it.
    out = mesh.copy()
    for t, r in zip(tiles, results):
        ids = t.vertices[t.owned]
        for name, values in r["attributes"].items():
            if name not in out.attributes:
                out.attributes[name] = np.zeros((mesh.vertex_count,) + values.shape[1:])
            out.attributes[name][ids] = values
        if "__colors__" in r["extra"]:
            out.colors[ids] = r["extra"]["__colors__"]
        if "__normals__" in r["extra"]:
            if out.normals is None:
                out.normals = np.zeros((mesh.vertex_count, 3))
            out.normals[ids] = r["extra"]["__normals__"]
        out.positions[ids] = r["positions"]
    return TiledResult(out, tiles, reach, unit, fine, time.perf_counter() - start,
                       [r["seconds"] for r in results], sum(len(t.vertices) for t in tiles),
                       [r["pid"] for r in results])


# --- rasters: dask.array.map_overlap -----------------------------------------------------------

def _raster_block(block: np.ndarray, rank: np.ndarray, transform, request: FilterRequest, unit: float, bounds,
                  signal: str, tile: int, halo_cells: int, block_info=None):
    """One raster task: the grid terrain of the block (with its halo), filtered; NaN stays NaN. rank:
    each cell's vertex index in the whole raster's terrain, for the whole's wavelet order."""
    # map_overlap's blocks start `depth` before their chunk (not before the raster's first cell)
    chunk = block_info[0]["chunk-location"] if block_info is not None else (0, 0)
    r0, c0 = max(0, chunk[0] * tile - halo_cells), max(0, chunk[1] * tile - halo_cells)
    t = list(transform)
    # the block's own geotransform: its first cell is (c0, r0) of the raster
    t[0] = transform[0] + c0 * transform[1] + r0 * transform[2]
    t[3] = transform[3] + c0 * transform[4] + r0 * transform[5]
    out = np.full(block.shape, np.nan)
    if np.count_nonzero(~np.isnan(block)) < 3:
        return out
    name = f"raster block at row {r0}, col {c0}"
    try:
        mesh = geoshift.grid_terrain(block, t, geographic_to_meters=False)
        req = FilterRequest(signal, request.preset, request.levels, request.alpha, dict(request.options, threads=1))
        filtered = req.run(mesh, unit, wavelet=_whole_order(rank[~np.isnan(block)], bounds)).signal[signal]
    except InputError as e:
        raise InputError(f"{name}: {e}") from None
    valid = ~np.isnan(block)
    out[valid] = filtered  # grid_terrain makes one vertex per valid cell, row-major
    return out


def filter_raster_tiled(values: np.ndarray, transform, request: FilterRequest, tile: int, client, *,
                        halo_cells: Optional[int] = None, unit: Optional[float] = None, bounds=None, log=None):
    """The elevation raster filtered as the signal _ELEVATION of its grid terrain, in chunks of
    tile x tile cells with map_overlap (depth = the halo in cells). unit and bounds (the whole
    terrain's coarse AEL and wavelet cost bands, _raster_stats) default to the whole raster's,
    analysed here. Returns (the filtered raster, the reach, the unit)."""
    import dask.array as da
    options, levels, alpha, signal = request.resolved()
    cell = math.hypot(transform[1], transform[4])
    fine = cell * (2 + math.sqrt(2)) / 3  # a grid's AEL: two axis edges and a diagonal per quad
    if unit is None:
        # the whole raster's coarse AEL and cost bands, as for meshes (unit="whole")
        total, count, bounds = _raster_stats(values, levels, tuple(transform))
        unit = total / max(1e-300, count)
    reach = filter_reach(options, levels, unit, fine)
    depth = halo_cells if halo_cells is not None else int(math.ceil(reach.halo / cell))
    depth = min(depth, tile)
    if log:
        log(f"raster {values.shape}, chunks {tile}, halo {depth} cells; coarse AEL {unit:.4g}; {reach.describe()}")
    arr = da.from_array(values, chunks=(tile, tile))
    # a cell's vertex in the whole raster's terrain: grid_terrain makes one per valid cell, row-major
    valid = ~np.isnan(values)
    rank = da.from_array((np.cumsum(valid.ravel()) - 1).reshape(values.shape), chunks=(tile, tile))
    req = FilterRequest(signal if request.signal is None else request.signal, request.preset, request.levels,
                        request.alpha, request.options)
    sig = req.signal or "_ELEVATION"
    if sig == "terrain":
        sig = "_ELEVATION"
    filtered = da.map_overlap(_raster_block, arr, rank, depth=depth, boundary="none", dtype=np.float64, trim=True,
                              transform=tuple(transform), request=req, unit=unit, bounds=bounds, signal=sig,
                              tile=tile, halo_cells=depth)
    return client.compute(filtered).result(), reach, unit


def _raster_stats(block: np.ndarray, levels: int, transform=(0, 1, 0, 0, 0, -1)):
    # edge lengths depend on the cell size, not on where the block is
    mesh = geoshift.grid_terrain(block, tuple(transform), geographic_to_meters=False)
    return _core._coarse_edge_stats(mesh._built(), levels, geoshift.WaveletOptions(),
                                    np.ones(mesh.vertex_count), None)


# --- batches of files --------------------------------------------------------------------------

def _denoise_file(src: str, dst: str, options: dict):
    """One task of a batch: denoise one file into dst (atomically, by the core's writer)."""
    doc = geoshift.read(src)
    doc.parts = [geoshift.denoise(part, **options).mesh for part in doc.parts]
    geoshift.write(doc, dst)
    return dst


def _filter_file(src: str, dst: str, request: FilterRequest):
    doc = geoshift.read(src)
    doc.parts = [request.run(part, 0.0).mesh for part in doc.parts]
    geoshift.write(doc, dst)
    return dst


def batch(inputs: Sequence[str], out_dir: str, client, *, denoise_options: Optional[dict] = None,
          request: Optional[FilterRequest] = None) -> List[str]:
    """One task a file: denoise (default) or filter every input into out_dir under its own name.
    Every output is written atomically; a file that fails raises its error (naming the file) after
    the others have finished, so good files are not lost to a bad one."""
    os.makedirs(out_dir, exist_ok=True)
    futures = []
    for src in inputs:
        dst = os.path.join(out_dir, os.path.basename(src))
        if request is None:
            futures.append(client.submit(_denoise_file, str(src), dst, denoise_options or {}, pure=False))
        else:
            futures.append(client.submit(_filter_file, str(src), dst, request, pure=False))
    results = client.gather(futures, errors="skip")
    failed = [(src, f.exception()) for src, f in zip(inputs, futures) if f.status == "error"]
    if failed:
        src, e = failed[0]
        raise InputError(f"{len(failed)} of {len(inputs)} files failed; first: {src}: {e}")
    return results


# --- whole inputs ------------------------------------------------------------------------------

def load(path: str, procedural: Optional[int] = None, seed: int = 1):
    """The input as ('mesh', Document or Mesh) or ('raster', read_geotiff dict)."""
    if procedural:
        return "mesh", geoshift.procedural_terrain(procedural, seed=seed)
    ext = Path(path).suffix.lower()
    if ext in RASTER_FORMATS:
        return "raster", geoshift.read_geotiff(path)
    if ext in POINT_FORMATS and not (ext == ".ply" and _ply_has_faces(path)):
        return "mesh", geoshift.read_terrain(path)
    return "mesh", geoshift.read(path)


def _ply_has_faces(path: str) -> bool:
    with open(path, "rb") as f:
        head = f.read(4096).decode("latin-1")
    return "element face" in head and "element face 0" not in head


def _atomic(path: str, write) -> None:
    """Writes through a temporary file in the same folder, renamed into place."""
    d = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".geoshift-", suffix=Path(path).suffix, dir=d)
    os.close(fd)
    try:
        write(tmp)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def save(result_mesh: geoshift.Mesh, doc, path: str) -> None:
    ext = Path(path).suffix.lower()
    if ext in (".npz",):
        def w(tmp):
            with open(tmp, "wb") as f:
                np.savez(f, positions=result_mesh.positions, faces=result_mesh.faces,
                         **{k.lstrip("_") or k: v for k, v in result_mesh.attributes.items()})
        _atomic(path, w)
        return
    if doc is not None:
        doc.parts[0] = result_mesh
        geoshift.write(doc, path)
    else:
        geoshift.write(result_mesh, path)


def main(argv: Optional[Sequence[str]] = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m geoshift.tiles", description=__doc__.split("\n\n")[0])
    ap.add_argument("input", nargs="?", help="a DEM (.tif), a point set (.las .ply), a mesh (.glb .gltf .obj .off), "
                                             "or a folder of meshes (--batch)")
    ap.add_argument("-o", "--output", required=True, help="output file (.glb .gltf .obj .off .npz; rasters .npy "
                                                          "or a mesh format), or folder with --batch")
    ap.add_argument("--preset", help="color, curvature-ms, curvature-bms, terrain-ms, terrain-bms")
    ap.add_argument("--signal", help="what to filter (default: the preset's; rasters _ELEVATION)")
    ap.add_argument("--levels", type=int, help="wavelet levels of the hybrid filter (default: the preset's)")
    ap.add_argument("--hr", type=float, help="range bandwidth h_r in the signal's units")
    ap.add_argument("--tile", type=float, default=2000, help="tile side: raster cells, or average edge lengths "
                                                             "of the terrain or mesh (about tile x tile vertices)")
    ap.add_argument("--halo", type=float, help="halo override in the input's units (default: the filter's reach)")
    ap.add_argument("--scheduler", help="address of a Dask scheduler (default: a LocalCluster here)")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster workers (default 2)")
    ap.add_argument("--threads", type=int, default=1, help="threads per task (default 1)")
    ap.add_argument("--procedural", type=int, help="filter an N x N procedural terrain instead of IN")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--batch", action="store_true", help="IN is a folder: one task a file (denoise, or --preset)")
    a = ap.parse_args(argv)

    def log(msg):
        print(f"geoshift.tiles: {msg}", file=sys.stderr, flush=True)

    if not a.input and not a.procedural:
        ap.error("give IN or --procedural N")
    options = {}
    if a.hr is not None:
        options["range_bandwidth"] = a.hr
    request = FilterRequest(a.signal, a.preset, a.levels, None, options)
    try:
        client, cluster = _client(a.scheduler, a.workers, a.threads)
    except Exception as e:  # no scheduler there
        print(f"geoshift.tiles: cannot reach the Dask scheduler: {e}", file=sys.stderr)
        return 1
    try:
        if a.batch:
            files = sorted(str(p) for p in Path(a.input).iterdir() if p.suffix.lower() in MESH_FORMATS)
            if not files:
                raise InputError(f"{a.input}: no mesh files (.gltf .glb .obj .off)")
            done = batch(files, a.output, client,
                         request=request if (a.preset or a.signal) else None)
            log(f"{len(done)} files -> {a.output}")
            return 0
        kind, data = load(a.input, a.procedural, a.seed)
        if kind == "raster":
            if data["geographic"]:
                raise InputError(f"{a.input}: a geographic (longitude/latitude) raster; tiles need projected "
                                 "coordinates (metres) that mean the same in every tile: reproject it first")
            values = np.asarray(data["values"], dtype=np.float64)
            out, reach, unit = filter_raster_tiled(values, data["transform"], request, int(a.tile), client,
                                                   log=log)
            ext = Path(a.output).suffix.lower()
            if ext == ".npy":
                _atomic(a.output, lambda tmp: np.save(open(tmp, "wb"), out))
            else:
                mesh = geoshift.grid_terrain(out, data["transform"], geographic=data["geographic"])
                save(mesh, None, a.output)
            log(f"wrote {a.output}")
            return 0
        doc = data if isinstance(data, geoshift.Document) else None
        mesh = doc.mesh if doc is not None else data
        r = filter_mesh_tiled(mesh, request, a.tile, client, halo=a.halo, threads=a.threads, log=log)
        save(r.mesh, doc, a.output)
        log(f"{len(r.tiles)} tiles, {r.halo_vertices} vertices with halos for {mesh.vertex_count}, "
            f"{r.seconds:.2f} s -> {a.output}")
        return 0
    except InputError as e:
        print(f"geoshift.tiles: error: {e}", file=sys.stderr)
        return 1
    finally:
        if cluster is not None:
            client.close()
            cluster.close()


if __name__ == "__main__":
    sys.exit(main())
