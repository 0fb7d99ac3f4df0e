"""Shared fixtures of the Python tests: the CLI built by the bootstrap, ../shared/data, and one
Dask LocalCluster of 2 worker processes that the tiled tests share (started and stopped here)."""
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import geoshift

ROOT = Path(__file__).resolve().parents[2]
CLI = ROOT / "build" / "native-release" / "cli" / "geoshift"
SHARED = Path(os.environ.get("GEOSHIFT_SHARED_DATA", ROOT.parent / "shared" / "data"))


def shared(relative: str) -> Path:
    """A file of the shared data folder; the test is skipped when it is absent (CI may lack it)."""
    p = SHARED / relative
    if not p.exists():
        pytest.skip(f"{relative} not found ({SHARED} absent); set GEOSHIFT_SHARED_DATA")
    return p


@pytest.fixture(scope="session")
def cli():
    """Runs the geoshift CLI; returns its stdout."""
    if not CLI.exists():
        pytest.skip(f"{CLI} not built (scripts/bootstrap.sh builds it)")

    def run(*args):
        r = subprocess.run([str(CLI), *map(str, args)], capture_output=True, text=True)
        assert r.returncode == 0, f"geoshift {' '.join(map(str, args))} failed: {r.stderr}"
        return r.stdout
    return run


@pytest.fixture(scope="session")
def terrain():
    """A small procedural terrain (65 x 65 vertices, attributes _VEGETATION_HEIGHT and _CLASS)."""
    return geoshift.procedural_terrain(65, seed=7)


@pytest.fixture(scope="session")
def cluster():
    """A LocalCluster of 2 single-threaded worker processes, as the issue asks; closed at the end."""
    distributed = pytest.importorskip("distributed")
    c = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                 silence_logs=40)
    yield c
    c.close()


@pytest.fixture
def client(cluster):
    distributed = pytest.importorskip("distributed")
    with distributed.Client(cluster) as c:
        yield c


def noisy_copy(mesh: geoshift.Mesh, amount: float, seed: int = 1) -> geoshift.Mesh:
    """The mesh with seeded Gaussian noise of `amount` average edge lengths on its positions."""
    rng = np.random.default_rng(seed)
    ael = geoshift.Geodesics(mesh).average_edge_length
    out = mesh.copy()
    out.positions = mesh.positions + rng.normal(scale=amount * ael, size=mesh.positions.shape)
    return out


REPORT = []


def report(line: str) -> None:
    """A figure the tests measured, printed at the end of the run (pytest's summary)."""
    REPORT.append(line)


def pytest_terminal_summary(terminalreporter):
    if REPORT:
        terminalreporter.write_sep("-", "figures measured by the tests")
        for line in REPORT:
            terminalreporter.write_line(line)
