"""Benchmark of tiled filtering on Dask (not a test: prints a table). terrain-bms on a procedural
terrain of 2001 x 2001 = 4.0M vertices and on the autzen LiDAR (../shared/data, skipped when
absent), with a LocalCluster of 1 and of 2 single-threaded workers: wall time, speed-up, peak
resident memory per worker, tiles and halo overhead.

    build/venv/bin/python bench/python/tiles_bench.py [--size 2001] [--tile 1000] [--las PATH]
"""
import argparse
import os
import resource
import sys
import time
from pathlib import Path

import numpy as np

import geoshift
from geoshift import tiles

ROOT = Path(__file__).resolve().parents[2]
SHARED = Path(os.environ.get("GEOSHIFT_SHARED_DATA", ROOT.parent / "shared" / "data"))


def peak_rss_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def run(mesh, tile, workers, label):
    import distributed
    cluster = distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=50)
    client = distributed.Client(cluster)
    try:
        t0 = time.perf_counter()
        r = tiles.filter_mesh_tiled(mesh, tiles.FilterRequest(preset="terrain-bms"), tile, client)
        wall = time.perf_counter() - t0
        peaks = sorted(client.run(peak_rss_mb).values())
    finally:
        client.close()
        cluster.close()
    print(f"| {label} | {workers} | {len(r.tiles)} | {r.halo_vertices / mesh.vertex_count:.2f} | {r.reach.halo:.0f} "
          f"| {wall:.0f} | {max(peaks):.0f} |", flush=True)
    return wall, r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=2001)
    ap.add_argument("--tile", type=float, default=1000)
    ap.add_argument("--las", default=str(SHARED / "pdal_testdata/las/autzen_trim.las"))
    ap.add_argument("--las-tile", type=float, default=150)
    a = ap.parse_args()
    print(f"machine: {os.cpu_count()} cores; terrain-bms (10 passes, 6 levels); wall seconds, one run each")
    print("| input | workers | tiles | vertices with halos / vertices | halo (m or ft) | wall s | peak RSS per worker MB |")
    print("|---|---|---|---|---|---|---|")
    inputs = []
    if Path(a.las).exists():
        inputs.append((f"autzen LiDAR ({a.las_tile:g} AEL tiles)", geoshift.read_terrain(a.las), a.las_tile))
    else:
        print(f"(autzen LiDAR skipped: {a.las} absent)")
    t0 = time.perf_counter()
    big = geoshift.procedural_terrain(a.size, seed=7)
    print(f"(procedural {a.size}x{a.size} = {big.vertex_count} vertices generated in {time.perf_counter() - t0:.1f} s)",
          flush=True)
    inputs.append((f"procedural {big.vertex_count / 1e6:.1f}M ({a.tile:g} AEL tiles)", big, a.tile))
    for label, mesh, tile in inputs:
        one, _ = run(mesh, tile, 1, label)
        two, _ = run(mesh, tile, 2, label)
        print(f"| {label}: speed-up 1 -> 2 workers | | | | | {one / two:.2f}x | |", flush=True)


if __name__ == "__main__":
    sys.exit(main())
