# Builds geoshift._geoshift with the repository's own CMake tree (python/CMakeLists.txt, the core
# compiled position-independent) in build/python, so repeated installs are incremental; ccache is
# used when present. Everything else is in pyproject.toml.
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = Path(os.environ.get("GEOSHIFT_PYTHON_BUILD_DIR", ROOT / "build" / "python"))
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
