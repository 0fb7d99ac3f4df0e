# Builds geoshift._geoshift with the repository's own CMake tree (python/CMakeLists.txt, the core
# compiled position-independent) in build/python, so repeated installs are incremental; ccache is
# used when present. The bootstrap instead points GEOSHIFT_PYTHON_BUILD_DIR at its native build,
# which builds the module beside the CLI from the same core objects. Everything else is in pyproject.toml.
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def _configured_with_module(build_dir: Path) -> bool:
    """A CMake build of this tree that builds the module beside the CLI (-DGEOSHIFT_PYTHON=ON)."""
    cache = build_dir / "CMakeCache.txt"
    return cache.exists() and "GEOSHIFT_PYTHON:BOOL=ON" in cache.read_text(errors="replace")


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        # GEOSHIFT_PYTHON_BUILD_DIR: a native build configured with -DGEOSHIFT_PYTHON=ON (the
        # bootstrap's build/native-release) already compiled the core position-independent and the
        # module with it: only build the module target there. Any other build of its own is left
        # alone, and build/python (core and module only) is used.
        given = os.environ.get("GEOSHIFT_PYTHON_BUILD_DIR")
        build_dir = Path(given) if given else ROOT / "build" / "python"
        if not _configured_with_module(build_dir):
            if (build_dir / "CMakeCache.txt").exists() and given:
                build_dir = ROOT / "build" / "python"
            configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                         "-DGEOSHIFT_PYTHON_ONLY=ON", f"-DPython_EXECUTABLE={sys.executable}"]
            if shutil.which("ccache"):
                configure += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache", "-DCMAKE_C_COMPILER_LAUNCHER=ccache"]
            subprocess.run(configure, check=True, stdout=subprocess.DEVNULL)
        jobs = os.environ.get("GEOSHIFT_BUILD_JOBS", str(os.cpu_count() or 2))
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "_geoshift", "-j", jobs], check=True)
        built = sorted((build_dir / "python").glob("_geoshift*.so"))
        if not built:
            raise RuntimeError(f"no _geoshift module in {build_dir / 'python'}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(
    packages=["geoshift"],
    package_dir={"": "python"},
    package_data={"geoshift": ["*.pyi", "py.typed"]},
    ext_modules=[Extension("geoshift._geoshift", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
