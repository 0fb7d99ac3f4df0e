"""The package's surface: options with the library's defaults (and the stubs saying the same),
errors as geoshift.InputError with the core's message, files in and out, progress, cancelling,
the GIL released while the core computes, Ctrl-C."""
import ast
import pickle
import signal
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest

import geoshift

STUBS = Path(geoshift.__file__).with_name("__init__.pyi")
OPTION_CLASSES = ["MeanShiftOptions", "ParallelOptions", "SignalChannel", "WaveletOptions", "TaubinOptions",
                  "VertexUpdateOptions", "FaceNeighborhoodOptions", "PaperDenoiseOptions", "DenoiseOptions", "BilateralNormalOptions", "TerrainOptions"]


def stub_defaults(tree, cls_name):
    cls = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == cls_name)
    init = next(n for n in cls.body if isinstance(n, ast.FunctionDef) and n.name == "__init__")
    return {a.arg: ast.literal_eval(d) for a, d in zip(init.args.kwonlyargs, init.args.kw_defaults)}


@pytest.mark.parametrize("name", OPTION_CLASSES)
def test_stubs_list_every_option_with_the_library_default(name):
    tree = ast.parse(STUBS.read_text())
    defaults = stub_defaults(tree, name)
    actual = getattr(geoshift, name)().to_dict()
    assert sorted(defaults) == sorted(actual), f"{name}: the stub's fields differ from the module's"
    for field, value in actual.items():
        if isinstance(value, (dict, list)) or defaults[field] is None:
            continue  # nested options: checked through their own class
        assert defaults[field] == value, f"{name}.{field}: stub says {defaults[field]!r}, library {value!r}"


def test_mean_shift_takes_every_option_as_keyword():
    tree = ast.parse(STUBS.read_text())
    fn = next(n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "mean_shift")
    keywords = {a.arg for a in fn.args.kwonlyargs}
    assert set(geoshift.MeanShiftOptions().to_dict()) <= keywords


def test_options_from_keywords_nested_dicts_and_pickle():
    o = geoshift.DenoiseOptions(preset="paper", strength=1.5,
                                paper={"passes": 2, "face_normals": "mean",
                                       "mean_shift": {"range_bandwidth": 0.3, "threads": 1}})
    assert o.preset == "paper" and o.strength == 1.5
    assert o.paper.passes == 2 and o.paper.face_normals == "mean"
    assert o.paper.mean_shift.range_bandwidth == 0.3 and o.paper.mean_shift.parallel.threads == 1
    assert o.paper.mean_shift.range_kernel == "normal_similarity"  # the paper's denoising defaults stay
    assert pickle.loads(pickle.dumps(o)) == o
    m = geoshift.MeanShiftOptions(channels=[("_A", 2.0), {"attribute": "_B", "kernel": "gaussian"}])
    assert [c.attribute for c in m.channels] == ["_A", "_B"] and m.channels[0].range_bandwidth == 2.0
    with pytest.raises(TypeError, match="no option 'bandwidth'.*spatial_bandwidth"):
        geoshift.MeanShiftOptions(bandwidth=3)
    with pytest.raises(geoshift.InputError, match="range_update must be one of sampled, joint"):
        geoshift.MeanShiftOptions(range_update="both")


def test_bad_input_raises_input_error_with_the_core_message(tmp_path, terrain):
    with pytest.raises(geoshift.InputError, match="face 1, corner 2: vertex index 9 is out of range"):
        geoshift.curvatures(geoshift.Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2], [0, 1, 9]]))
    p = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]])
    p[1, 0] = np.nan
    with pytest.raises(geoshift.InputError, match="vertex 1"):
        geoshift.curvatures(geoshift.Mesh(p, [[0, 1, 2]]))
    with pytest.raises(geoshift.InputError, match=r"shape \(N, 3\)"):
        geoshift.Mesh(np.zeros((4, 2)), [[0, 1, 2]])
    with pytest.raises(geoshift.InputError, match="nothing.obj"):
        geoshift.read(tmp_path / "nothing.obj")
    with pytest.raises(geoshift.InputError, match="unknown preset 'terain'.*terrain-bms"):
        geoshift.mean_shift(terrain, preset="terain")
    with pytest.raises(geoshift.InputError, match="no vertex colors"):
        geoshift.mean_shift(terrain, "color")
    with pytest.raises(geoshift.InputError, match="range bandwidth"):
        geoshift.mean_shift(terrain, "_CLASS", range_bandwidth=-1)
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n")
    with pytest.raises(geoshift.InputError, match="bad.off"):
        geoshift.read(bad)
    assert issubclass(geoshift.InputError, ValueError)


def test_write_read_round_trip_keeps_arrays(tmp_path, terrain):
    m = terrain.copy()
    m.z_up = False
    m.colors = np.random.default_rng(1).random((m.vertex_count, 4)).astype(np.float32).astype(np.float64)
    geoshift.write(m, tmp_path / "t.glb")
    back = geoshift.read(tmp_path / "t.glb").mesh
    np.testing.assert_array_equal(back.faces, m.faces)
    np.testing.assert_array_equal(back.positions, m.positions.astype(np.float32))
    np.testing.assert_array_equal(back.attributes["_CLASS"], m.attributes["_CLASS"])
    np.testing.assert_allclose(back.colors, m.colors, atol=1e-7)
    geoshift.write(m, tmp_path / "t.off")
    np.testing.assert_allclose(geoshift.read(tmp_path / "t.off").mesh.positions, m.positions, rtol=1e-6)


def test_progress_is_reported_and_false_cancels(terrain):
    seen = []
    geoshift.mean_shift(terrain, "_VEGETATION_HEIGHT", passes=3, progress=lambda f, s: seen.append((f, s)))
    assert seen and all(0 <= f <= 1 for f, _ in seen)
    assert any("blurring pass 3/3" in s for _, s in seen)
    with pytest.raises(geoshift.Cancelled):
        geoshift.mean_shift(terrain, "_VEGETATION_HEIGHT", passes=3, progress=lambda f, s: False)

    def boom(f, s):
        raise ZeroDivisionError("from the callback")
    with pytest.raises(ZeroDivisionError, match="from the callback"):
        geoshift.denoise(terrain, progress=boom)


def test_gil_is_released_while_the_core_computes(terrain):
    done = threading.Event()
    counted = [0]

    def work():
        geoshift.mean_shift(terrain, "_VEGETATION_HEIGHT", passes=4, threads=1)
        done.set()
    t = threading.Thread(target=work)
    t.start()
    while not done.is_set():
        counted[0] += 1
    t.join()
    # With the GIL held for the whole filter this loop would run only between progress reports
    # (a few dozen times); released, it spins freely.
    assert counted[0] > 10000


def test_ctrl_c_stops_a_run_with_keyboard_interrupt(tmp_path):
    script = (
        "import sys, geoshift\n"
        "t = geoshift.procedural_terrain(257, seed=3)\n"
        "def p(f, s):\n"
        "    print('started', flush=True)\n"
        "try:\n"
        "    geoshift.mean_shift(t, '_VEGETATION_HEIGHT', passes=1000, threads=1, progress=p)\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', flush=True)\n"
        "    sys.exit(3)\n"
    )
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "started"
    proc.send_signal(signal.SIGINT)
    out, _ = proc.communicate(timeout=120)
    assert proc.returncode == 3 and "interrupted" in out


def test_geodesics_walk_back_to_the_vertex(terrain):
    g = geoshift.Geodesics(terrain)
    lm = g.log_map(2080, 5)
    i = int(np.flatnonzero(lm["vertex"] == 2081)[0])
    e = g.exp_map(2080, (lm["x"][i], lm["y"][i]))
    np.testing.assert_allclose(e["point"], terrain.positions[2081], atol=1e-6 * g.average_edge_length)


def test_face_points_on_faces_wound_backwards_use_the_callers_corners(terrain):
    """A face the build turns over to agree with its neighbours keeps the caller's corners for face
    points given and reported (docs/denoising.md#bad-input)."""
    mixed_faces = terrain.faces.copy()
    mixed_faces[6::7] = mixed_faces[6::7][:, [0, 2, 1]]
    mixed = geoshift.Mesh(terrain.positions, mixed_faces)
    face = 300 - 300 % 7 + 6  # one of the faces given the other way round
    a = geoshift.exp_map(terrain, (face, (0.2, 0.3, 0.5)), (0.01, 0.01))
    b = geoshift.exp_map(mixed, (face, (0.2, 0.5, 0.3)), (0.01, 0.01))
    assert b["face"] == a["face"] == face
    scale = np.abs(terrain.positions).max()
    np.testing.assert_allclose(b["point"], a["point"], rtol=0, atol=1e-12 * scale)
    for result, faces in ((a, terrain.faces), (b, mixed_faces)):
        corners = terrain.positions[faces[result["face"]]]
        np.testing.assert_allclose(np.asarray(result["bary"]) @ corners, result["point"], rtol=0, atol=1e-12 * scale)


def test_denoise_keywords_are_the_cli_and_wasm_request(terrain):
    """The request's parameters in snake_case are checked by the core as the CLI and the wasm op
    check them (tests/wasm/denoise-requests.test.mjs compares the three on one table)."""
    with pytest.raises(geoshift.InputError,
                       match='denoise: parameter hs belongs to method "meanshift"; hs does not apply to method "taubin"'):
        geoshift.denoise(terrain, method="taubin", hs=3)
    with pytest.raises(geoshift.InputError, match=r"parameter vertexIterations is outside \[1, 10000\] \(got 0\)"):
        geoshift.denoise(terrain, vertex_iterations=0)
    # A request keyword and a DenoiseOptions field together: the field sets what the request does not.
    smoothed = geoshift.denoise(terrain, method="taubin", iterations=2, lambda_=0.4, mu=-0.45)
    assert smoothed.stats["method"] == "taubin" and smoothed.stats["iterations"] == 2
    fixed = geoshift.denoise(terrain, fixed_passes=1, hs=0.8)
    assert fixed.stats["passes"] == 1


def test_taubin_gives_the_same_positions_on_any_number_of_threads(terrain):
    one = geoshift.taubin_smooth(terrain, iterations=5, threads=1)
    assert not np.array_equal(one.positions, terrain.positions)
    for threads in (2, 3):
        np.testing.assert_array_equal(geoshift.taubin_smooth(terrain, iterations=5, threads=threads).positions, one.positions)
    assert geoshift.TaubinOptions(threads=2).parallel.threads == 2
    request = geoshift.denoise(terrain, method="taubin", iterations=5, threads=1)
    np.testing.assert_array_equal(request.mesh.positions, one.positions)


def test_param_specs_give_the_options_structs_defaults():
    specs = geoshift.param_specs()
    assert {"noise", "smooth", "curvature", "geodesic", "filter", "denoise", "wavelet"} <= set(specs)
    d = geoshift.DenoiseOptions()
    p = specs["denoise"]["params"]
    assert p["strength"]["default"] == d.strength
    assert p["hs"]["default"] == d.neighborhood.spatial_bandwidth
    assert p["hr"]["default"] == list(d.range_bandwidths)  # the candidates SURE picks from
    assert p["passes"]["cases"][0]["default"] == d.paper.passes
    assert p["method"]["values"] == ["meanshift", "bilateral", "taubin"]
    assert specs["smooth"]["params"]["mu"]["default"] == geoshift.TaubinOptions().mu


def test_denoise_says_when_the_noise_looks_impulsive(terrain):
    """A tenth of the vertices moved (docs/denoising.md#impulsive-noise): the correction fires, most
    vertices keep the input's position and the result is nearer the clean terrain than without it;
    impulse_shrink=0 turns it off."""
    p, f = terrain.positions, terrain.faces
    ael = np.mean(np.linalg.norm(p[f[:, [1, 2, 0]]] - p[f], axis=2))
    rng = np.random.default_rng(6)
    noisy = terrain.copy()
    moved = rng.random(len(p)) < 0.1
    noisy.positions = p + np.outer(moved * rng.normal(0, 0.5 * ael, len(p)), [0, 0, 1])
    on = geoshift.denoise(noisy)
    off = geoshift.denoise(noisy, impulse_shrink=0)
    assert on.stats["impulse_garrote"] is True
    assert off.stats["impulse_garrote"] is False
    # What fired it: the kurtosis of the input's highest frequencies or of the winner's displacement.
    assert max(on.stats["spectrum_kurtosis"] - geoshift.DenoiseOptions().impulse_spectrum_kurtosis,
               on.stats["displacement_kurtosis"] - geoshift.DenoiseOptions().impulse_kurtosis) > 0
    kept = np.all(on.mesh.positions == noisy.positions, axis=1)
    assert kept.mean() > 0.8
    assert np.all(off.mesh.positions == noisy.positions, axis=1).mean() < 0.5

    def rms(m):
        return np.sqrt(np.mean(np.sum((m.positions - p) ** 2, axis=1)))
    assert rms(on.mesh) < rms(off.mesh) < rms(noisy)


def test_denoise_reports_a_taubin_only_winner(terrain):
    """docs/denoising.md#taubin-only-candidates: where the candidates with passes may start only from
    the raw input and run one pass, a Taubin-only candidate wins under dense noise, reported as such
    with no pass; with none offered, it cannot."""
    p, f = terrain.positions, terrain.faces
    ael = np.mean(np.linalg.norm(p[f[:, [1, 2, 0]]] - p[f], axis=2))
    noisy = terrain.copy()
    noisy.positions = p + np.random.default_rng(8).normal(0, 0.5 * ael, p.shape)
    on = geoshift.denoise(noisy, presmoothing=[0], max_passes=1)
    off = geoshift.denoise(noisy, presmoothing=[0], max_passes=1, taubin_only_steps=[])
    assert on.stats["taubin_only"] is True and on.stats["passes"] == 0
    assert on.stats["presmoothing_steps"] in geoshift.DenoiseOptions().taubin_only_steps
    assert off.stats["taubin_only"] is False


def test_denoise_keeps_pieces_too_small_to_denoise(terrain):
    """docs/denoising.md#small-pieces: a lone triangle beside the noisy terrain keeps its positions
    and is counted; the terrain comes out as it does alone; min_piece=0 denoises the triangle too."""
    p, f = terrain.positions, terrain.faces
    ael = np.mean(np.linalg.norm(p[f[:, [1, 2, 0]]] - p[f], axis=2))
    noisy = terrain.copy()
    noisy.positions = p + np.random.default_rng(10).normal(0, 0.3 * ael, p.shape)
    n = len(p)
    triangle = p.max(axis=0) + np.array([[1.0, 0, 0], [1.0 + ael, 0, 0], [1.0, ael, 0.2 * ael]])
    both = geoshift.Mesh(np.vstack([noisy.positions, triangle]), np.vstack([f, [[n, n + 1, n + 2]]]))
    kept = geoshift.denoise(both)
    assert kept.stats["kept_pieces"] == 1 and kept.stats["kept_vertices"] == 3
    np.testing.assert_array_equal(kept.mesh.positions[n:], triangle)
    np.testing.assert_array_equal(kept.mesh.positions[:n], geoshift.denoise(noisy).mesh.positions)
    every = geoshift.denoise(both, min_piece=0)
    assert every.stats["kept_pieces"] == 0
    assert not np.array_equal(every.mesh.positions[n:], triangle)
    assert geoshift.DenoiseOptions().min_piece_vertices == 50


def _box_surface(n):
    """The surface of the unit cube, each side an n x n grid of squares split in two."""
    index, positions, faces = {}, [], []

    def vertex(c):
        if c not in index:
            index[c] = len(positions)
            positions.append(c)
        return index[c]

    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        for side in (0, n):
            for i in range(n):
                for j in range(n):
                    quad = []
                    for a, b in ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)):
                        c = [0, 0, 0]
                        c[axis], c[u], c[v] = side, a, b
                        quad.append(vertex(tuple(c)))
                    if side == 0:
                        quad.reverse()
                    faces += [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]]
    return geoshift.Mesh(np.array(positions, dtype=float) / n, np.array(faces))


def test_denoise_returns_a_mesh_no_candidate_improves_as_it_was():
    """docs/denoising.md#the-input-as-a-candidate: a noisy box denoised once is smoothed; denoised
    again it comes back as it went in, with kept_input; input_candidate=False smooths it again."""
    box = _box_surface(12)
    direction = np.random.default_rng(3).normal(size=box.positions.shape)
    noisy = box.copy()
    noisy.positions = box.positions + 0.5 / 12 * direction / np.linalg.norm(direction, axis=1)[:, None]
    once = geoshift.denoise(noisy)
    assert once.stats["kept_input"] is False and once.stats["kept_pieces"] == 0
    twice = geoshift.denoise(once.mesh)
    assert twice.stats["kept_input"] is True
    assert twice.stats["passes"] == 0 and twice.stats["presmoothing_steps"] == 0
    np.testing.assert_array_equal(twice.mesh.positions, once.mesh.positions)
    again = geoshift.denoise(once.mesh, input_candidate=False)
    assert again.stats["kept_input"] is False
    assert not np.array_equal(again.mesh.positions, once.mesh.positions)
    assert geoshift.DenoiseOptions().input_candidate is True


def test_denoise_keeps_a_clean_coarse_part_measured_against_its_planes():
    """docs/denoising.md#the-noise-level ("Planes left untouched"): a clean box too coarse for the
    spectrum reads no noise against its own planes and comes back as it went in; with
    planar_level_share=0 the level refined from the candidates moves it."""
    box = _box_surface(5)
    kept = geoshift.denoise(box)
    assert kept.stats["planar_level"] is True and kept.stats["kept_input"] is True
    assert kept.stats["planar_kept"] == 0
    np.testing.assert_array_equal(kept.mesh.positions, box.positions)
    moved = geoshift.denoise(box, planar_level_share=0)
    assert moved.stats["planar_level"] is False
    assert not np.array_equal(moved.mesh.positions, box.positions)
    assert geoshift.DenoiseOptions().planar_level_share == 0.5
    assert geoshift.DenoiseOptions().planar_keep == 0.1


def test_denoise_takes_the_risk_estimate_options(terrain):
    """The risk estimate's settings reach the denoiser: out-of-range values are refused with the
    core's message, and the noise level without its refinement is the race's upper estimate, at
    least the refined one."""
    p, f = terrain.positions, terrain.faces
    ael = np.mean(np.linalg.norm(p[f[:, [1, 2, 0]]] - p[f], axis=2))
    noisy = terrain.copy()
    noisy.positions = p + np.random.default_rng(9).normal(0, 0.3 * ael, p.shape)
    with pytest.raises(ValueError, match="detail bound ratio must be within"):
        geoshift.denoise(noisy, detail_bound_ratio=1.5)
    with pytest.raises(ValueError, match="tie probes must be in"):
        geoshift.denoise(noisy, tie_probes=-1)
    with pytest.raises(ValueError, match="probe spacing must be in"):
        geoshift.denoise(noisy, probe_spacing=0)
    with pytest.raises(ValueError, match="gradient risk weight must be within"):
        geoshift.denoise(noisy, gradient_risk_weight=-0.1)
    with pytest.raises(ValueError, match="tie standard errors must be"):
        geoshift.denoise(noisy, tie_standard_errors=-1)
    # A tie no probe can settle (docs/denoising.md#ties-between-starts): the normals decide, and say so.
    tied = geoshift.denoise(noisy, tie_margin=1e9, tie_probes=1, tie_standard_errors=1e9)
    assert tied.stats["tie_probes"] == 1 and tied.stats["tie_by_normals"] is True
    assert geoshift.denoise(noisy, tie_margin=1e9, tie_probes=1, tie_standard_errors=1e9,
                            tie_by_normals=False).stats["tie_by_normals"] is False
    refined = geoshift.denoise(noisy)
    raw = geoshift.denoise(noisy, refine_noise=False)
    assert raw.stats["noise_level"] >= refined.stats["noise_level"] > 0
