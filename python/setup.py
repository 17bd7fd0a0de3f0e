"""python/setup.py — builds polydec._polydec with the repository's CMake for the interpreter that
runs pip (Python_EXECUTABLE = sys.executable), then packages it with polydec/*.py.

Environment: POLYDEC_PREFIX (an installed shared polydec, `cmake --install`: then only the module's
own sources are compiled, against that installation: python/CMakeLists.txt as a project of its own),
POLYDEC_CMAKE_ARGS (extra CMake arguments, space-separated), CMAKE_BUILD_PARALLEL_LEVEL
(build jobs; default: all cores), POLYDEC_NO_CCACHE=1 (do not use ccache even when installed)."""

import os
import pathlib
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        if not (REPO / "CMakeLists.txt").exists():
            raise RuntimeError(f"polydec: the repository's CMakeLists.txt is not at {REPO} (install from a clone)")
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        build.mkdir(parents=True, exist_ok=True)
        prefix = os.environ.get("POLYDEC_PREFIX")
        if prefix:
            args = ["cmake", "-S", str(HERE), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                    f"-DCMAKE_PREFIX_PATH={pathlib.Path(prefix).resolve()}"]
        else:
            # Unity build: the sources in batches, fewer and larger compilations (run.sh's comment: 14.6
            # against about 25 CPU-minutes for the whole repository).
            args = ["cmake", "-S", str(REPO), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                    "-DPOLYDEC_BUILD_PYTHON=ON", "-DPOLYDEC_BUILD_TESTS=OFF", "-DPOLYDEC_BUILD_BENCH=OFF",
                    "-DPOLYDEC_UNITY_BUILD=ON"]
        args.append(f"-DPython_EXECUTABLE={sys.executable}")
        if shutil.which("ninja"):
            args += ["-G", "Ninja"]
        if shutil.which("ccache") and os.environ.get("POLYDEC_NO_CCACHE") != "1":
            args += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"]
        args += shlex.split(os.environ.get("POLYDEC_CMAKE_ARGS", ""))
        subprocess.run(args, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        # Only the module's target: the libraries it links, not the command line, paper or pictures.
        # Its progress lines reach the terminal with `pip install -v`.
        print(f"polydec: building the module in {build} with {jobs} jobs (pip install -v shows the progress)",
              flush=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "polydec_python", "-j", jobs], check=True)
        out = build / "polydec" if prefix else build / "python" / "polydec"
        built = list(out.glob("_polydec*.so"))
        if len(built) != 1:
            raise RuntimeError(f"polydec: expected one built extension in {out}, found {built}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(ext_modules=[CMakeExtension("polydec._polydec")], cmdclass={"build_ext": CMakeBuild})
