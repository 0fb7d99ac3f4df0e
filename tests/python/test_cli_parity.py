"""The Python package gives the CLI's numbers on the same input: both run the same core calls with
the same request rules, so outputs are compared for equality, not closeness."""
import csv
import io
import json

import numpy as np
import pytest

import geoshift
from conftest import noisy_copy, shared


def same_part(a: geoshift.Mesh, b: geoshift.Mesh):
    np.testing.assert_array_equal(a.positions, b.positions)
    np.testing.assert_array_equal(a.faces, b.faces)
    assert (a.colors is None) == (b.colors is None)
    if a.colors is not None:
        np.testing.assert_array_equal(a.colors, b.colors)
    assert (a.normals is None) == (b.normals is None)
    if a.normals is not None:
        np.testing.assert_array_equal(a.normals, b.normals)
    assert sorted(a.attributes) == sorted(b.attributes)
    for name in a.attributes:
        np.testing.assert_array_equal(a.attributes[name], b.attributes[name], err_msg=name)
    np.testing.assert_array_equal(a.instances, b.instances)


def test_procedural_terrain_file_matches_cli(cli, tmp_path):
    cli("terrain", "--procedural", 65, "--seed", 7, "-o", tmp_path / "cli.glb")
    geoshift.write(geoshift.procedural_terrain(65, seed=7), tmp_path / "py.glb")
    same_part(geoshift.read(tmp_path / "cli.glb").mesh, geoshift.read(tmp_path / "py.glb").mesh)


def test_terrain_bms_matches_cli(cli, tmp_path, terrain):
    geoshift.write(terrain, tmp_path / "in.glb")
    cli("filter", tmp_path / "in.glb", "-o", tmp_path / "cli.glb", "--preset", "terrain-bms")
    doc = geoshift.read(tmp_path / "in.glb")
    r = geoshift.mean_shift(doc.mesh, preset="terrain-bms", threads=1)
    assert r.vertex_counts[0] == terrain.vertex_count and len(r.vertex_counts) == 7
    doc.parts[0] = r.mesh
    geoshift.write(doc, tmp_path / "py.glb")
    cli_mesh = geoshift.read(tmp_path / "cli.glb").mesh
    same_part(cli_mesh, geoshift.read(tmp_path / "py.glb").mesh)
    # and the filter did something: heights moved
    assert np.abs(cli_mesh.attributes["_VEGETATION_HEIGHT"] - terrain.attributes["_VEGETATION_HEIGHT"]).max() > 0.1


def test_color_filter_with_segments_matches_cli(cli, tmp_path, terrain):
    colored = terrain.copy()
    z = terrain.positions[:, 2]
    t = (z - z.min()) / np.ptp(z)
    colored.colors = np.stack([t, 1 - t, (t > 0.5) * 1.0, np.ones_like(t)], axis=1)
    geoshift.write(colored, tmp_path / "in.glb")
    cli("filter", tmp_path / "in.glb", "-o", tmp_path / "cli.glb", "--hr", 0.2, "--segments")
    doc = geoshift.read(tmp_path / "in.glb")
    r = geoshift.mean_shift(doc.mesh, "color", range_bandwidth=0.2, segments=True)
    assert r.segment_count > 1
    doc.parts[0] = r.mesh
    geoshift.write(doc, tmp_path / "py.glb")
    same_part(geoshift.read(tmp_path / "cli.glb").mesh, geoshift.read(tmp_path / "py.glb").mesh)


def test_curvature_signal_with_levels_matches_cli(cli, tmp_path, terrain):
    geoshift.write(terrain, tmp_path / "in.obj")
    cli("filter", tmp_path / "in.obj", "-o", tmp_path / "cli.glb", "--preset", "curvature-ms", "--threads", 2)
    doc = geoshift.read(tmp_path / "in.obj")
    r = geoshift.mean_shift(doc.mesh, preset="curvature-ms", threads=2)
    geoshift.write([r.mesh], tmp_path / "py.glb")
    a, b = geoshift.read(tmp_path / "cli.glb").mesh, geoshift.read(tmp_path / "py.glb").mesh
    np.testing.assert_array_equal(a.attributes["_CURVATURE"], b.attributes["_CURVATURE"])
    np.testing.assert_array_equal(a.colors, b.colors)


def test_denoise_matches_cli(cli, tmp_path, terrain):
    noisy = noisy_copy(terrain, 0.3)
    noisy.z_up = False
    geoshift.write(noisy, tmp_path / "noisy.obj")
    cli("denoise", tmp_path / "noisy.obj", "-o", tmp_path / "cli.obj", "--passes", 2)
    r = geoshift.denoise(geoshift.read(tmp_path / "noisy.obj").mesh, fixed_passes=2)
    geoshift.write(r.mesh, tmp_path / "py.obj")
    np.testing.assert_array_equal(geoshift.read(tmp_path / "cli.obj").mesh.positions,
                                  geoshift.read(tmp_path / "py.obj").mesh.positions)
    assert r.stats["filtered_vertices"] == terrain.vertex_count


def test_wavelet_and_curvature_commands_match_cli(cli, tmp_path, terrain):
    geoshift.write(terrain, tmp_path / "in.glb")
    cli("wavelet", tmp_path / "in.glb", "-o", tmp_path / "cli.glb", "--levels", 3, "--alpha", "0,0.5,1")
    doc = geoshift.read(tmp_path / "in.glb")
    doc.parts[0] = geoshift.wavelet_filter(doc.mesh, 3, [0, 0.5, 1])
    geoshift.write(doc, tmp_path / "py.glb")
    same_part(geoshift.read(tmp_path / "cli.glb").mesh, geoshift.read(tmp_path / "py.glb").mesh)
    cli("curvature", tmp_path / "in.glb", "-o", tmp_path / "k.glb", "--kind", "mean")
    k = geoshift.curvature(geoshift.read(tmp_path / "in.glb").mesh, "mean")
    # glTF stores float32: the same numbers once rounded as the writer rounds them
    np.testing.assert_array_equal(geoshift.read(tmp_path / "k.glb").mesh.attributes["_CURVATURE"],
                                  k.astype(np.float32).astype(np.float64))


def test_log_and_exp_maps_match_cli(cli, tmp_path, terrain):
    geoshift.write(terrain, tmp_path / "in.obj")
    mesh = geoshift.read(tmp_path / "in.obj").mesh
    rows = list(csv.DictReader(io.StringIO(cli("logmap", tmp_path / "in.obj", "--source", 2080, "--radius", 4))))
    lm = geoshift.log_map(mesh, 2080, 4)
    assert len(rows) == len(lm["vertex"]) > 20
    np.testing.assert_array_equal([int(r["vertex"]) for r in rows], lm["vertex"])
    for key, col in (("u", "distance"), ("theta", "angle"), ("x", "x"), ("y", "y")):
        np.testing.assert_array_equal([float(r[key]) for r in rows], lm[col])
    j = json.loads(cli("expmap", tmp_path / "in.obj", "--face", 12, "--bary", "0.2,0.3,0.5", "--vector=3,-2", "--json"))
    e = geoshift.exp_map(mesh, (12, (0.2, 0.3, 0.5)), (3, -2))
    assert e["face"] == j["face"] and e["hit_boundary"] == j["hitBoundary"]
    np.testing.assert_array_equal(e["bary"], j["bary"])
    np.testing.assert_array_equal(e["point"], j["point"])


def test_las_terrain_matches_cli(cli, tmp_path):
    las = shared("pdal_testdata/las/simple.las")
    cli("terrain", las, "-o", tmp_path / "cli.glb")
    mesh = geoshift.read_terrain(las)
    assert mesh.report["points_read"] == 1065 and mesh.colors is not None
    geoshift.write(mesh, tmp_path / "py.glb")
    same_part(geoshift.read(tmp_path / "cli.glb").mesh, geoshift.read(tmp_path / "py.glb").mesh)


def test_geotiff_terrain_matches_cli(cli, tmp_path):
    tif = shared("dem_debian_r_packages/stars/olinda_dem_utm25s.tif")
    cli("terrain", tif, "-o", tmp_path / "cli.glb")
    mesh = geoshift.read_terrain(tif)
    grid = geoshift.read_geotiff(tif)
    assert grid["values"].shape == (111, 111)
    np.testing.assert_array_equal(geoshift.grid_terrain(grid).positions, mesh.positions)
    geoshift.write(mesh, tmp_path / "py.glb")
    same_part(geoshift.read(tmp_path / "cli.glb").mesh, geoshift.read(tmp_path / "py.glb").mesh)
