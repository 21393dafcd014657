"""Builds the compiled part of the cablelab package (_core) with the project's CMake.

pip calls this through pyproject.toml. The CMake build tree is build-pip/ in the source tree
(kept between installs, so a second install only relinks), or CABLELAB_BUILD_DIR when set (an
existing configured tree: `pip install` then installs what it already built). CMAKE_ARGS adds
configure options, e.g. CMAKE_ARGS="-DCABLELAB_BUILD_UI=OFF" for a module without render().
"""
import os
import pathlib
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = pathlib.Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        given = os.environ.get("CABLELAB_BUILD_DIR")
        build = pathlib.Path(given or SOURCE / "build-pip").resolve()
        if not (given and (build / "CMakeCache.txt").exists()):
            # The interpreter behind a venv's python: the module is built for its ABI and headers.
            python = os.path.realpath(sys.executable)
            configure = ["cmake", "-S", str(SOURCE), "-B", str(build),
                         "-DCMAKE_BUILD_TYPE=Release", f"-DPython3_EXECUTABLE={python}"]
            if shutil.which("ninja") and not (build / "CMakeCache.txt").exists():
                configure += ["-G", "Ninja"]
            if shutil.which("ccache"):
                configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
            configure += shlex.split(os.environ.get("CMAKE_ARGS", ""))
            subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", str(build), "--target", "cablelab_python", "-j", jobs],
                       check=True)
        built = next((build / "python" / "cablelab").glob("_core*.so"))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built, target)


# setuptools' own staging goes next to the CMake tree, not into build/ (scripts/run's tree).
setup(ext_modules=[CMakeExtension("cablelab._core")], cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": str(SOURCE / "build-pip" / "setuptools")}})
