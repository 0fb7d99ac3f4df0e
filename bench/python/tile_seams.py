"""How far a tiled result is from the untiled one, and why (not a test: prints figures). The
terrain and filter of tests/python/test_tiles.py (procedural 257 x 257, seed 7, terrain-bms with 3
passes on 3 levels, 3 x 3 tiles), tiles run one after the other in this process (no Dask: the
numbers are the same, the tasks are pure), with the knobs of docs/tiles.md#suspects turned one at
a time.

    build/venv/bin/python bench/python/tile_seams.py [--variant NAME ...] [--size 257] [--tile 90]
"""
import argparse
import sys
import time

import numpy as np

import geoshift
from geoshift import tiles

SIGNAL = "_VEGETATION_HEIGHT"


class InProcess:
    """The two calls of a Dask client that filter_mesh_tiled makes, run here and now."""

    class Done:
        def __init__(self, value):
            self.value = value

    def submit(self, fn, *args, pure=True, **kwargs):
        return self.Done(fn(*args, **kwargs))

    def gather(self, futures, errors="raise"):
        return [f.value for f in futures]


def edges(faces):
    e = np.vstack([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    return np.unique(np.sort(e, axis=1), axis=0)


def figures(d, noise_steps_p99, border=None):
    a = np.abs(d)
    out = {"max": a.max(), "p99": np.percentile(a, 99), "over1": (a > 1).mean()}
    if border is not None:
        seam = np.abs(d[border[:, 0]] - d[border[:, 1]])
        out["seam_p99"] = np.percentile(seam, 99)
        out["seam_max"] = seam.max()
    return out


def line(label, f):
    s = f"| {label} | {f['max']:.3g} | {f['p99']:.3g} | {f['over1']:.2%} |"
    if "seam_p99" in f:
        s += f" {f['seam_p99']:.3g} | {f['seam_max']:.3g} |"
    else:
        s += " | |"
    return s


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=257)
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--tile", type=float, default=90)
    ap.add_argument("--halo", type=float)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--no-whole-order", action="store_true",
                    help="tiles analyse in their own wavelet order (as before docs/tiles.md#the-wavelet-order)")
    ap.add_argument("--exact", action="store_true", help="also the exact-charts noise (30x slower)")
    ap.add_argument("--option", action="append", default=[], help="NAME=VALUE for every run (tiled and untiled)")
    ap.add_argument("--tile-option", action="append", default=[], help="NAME=VALUE for the tiles only")
    a = ap.parse_args()

    def parse(items):
        out = {}
        for kv in items:
            k, v = kv.split("=", 1)
            out[k] = {"true": True, "false": False}.get(v.lower(), None)
            if out[k] is None:
                out[k] = float(v) if any(c in v for c in ".e") else int(v)
        return out

    common = parse(a.option)
    if a.no_whole_order:
        tiles._whole_order = lambda whole_index, bounds: geoshift.WaveletOptions()
    mesh = geoshift.procedural_terrain(a.size, seed=a.seed)
    base = dict(preset="terrain-bms", levels=3, passes=3, threads=a.threads, **common)

    def untiled(**extra):
        return geoshift.mean_shift(mesh, **dict(base, **extra)).mesh.attributes[SIGNAL]

    t0 = time.perf_counter()
    ref = untiled()
    print(f"untiled {time.perf_counter() - t0:.1f} s; options {common}", file=sys.stderr)
    e = edges(mesh.faces)
    noise = {"chart cubes h_s/2 vs h_s": untiled(chart_cell=0.5) - ref}
    if a.exact:
        noise["exact charts vs default"] = untiled(exact_charts=True) - ref
    steps = {k: np.abs(v[e[:, 0]] - v[e[:, 1]]) for k, v in noise.items()}

    request = tiles.FilterRequest(preset="terrain-bms", levels=3,
                                  options=dict({"passes": 3}, **common, **parse(a.tile_option)))
    t0 = time.perf_counter()
    r = tiles.filter_mesh_tiled(mesh, request, a.tile, InProcess(), halo=a.halo, threads=a.threads)
    print(f"tiled {time.perf_counter() - t0:.1f} s, {len(r.tiles)} tiles, halo {r.reach.halo:.1f}", file=sys.stderr)
    own = np.full(mesh.vertex_count, -1)
    for t in r.tiles:
        own[t.vertices[t.owned]] = t.index
    border = e[own[e[:, 0]] != own[e[:, 1]]]
    d = r.mesh.attributes[SIGNAL] - ref

    print("| comparison | max m | p99 m | > 1 m | step p99 | step max |")
    print("|---|---|---|---|---|---|")
    print(line(f"tiled vs untiled ({a.tile_option or 'as is'})", figures(d, None, border)))
    for k, v in noise.items():
        f = figures(v, None)
        f["seam_p99"] = np.percentile(steps[k], 99)
        f["seam_max"] = steps[k].max()
        print(line(f"{k} (own noise; steps over all edges)", f))


if __name__ == "__main__":
    main()
