"""Builds the Python module `mbfe` with the project's CMake for `pip install .`.

The module is the one `scripts/build.sh` builds into build/python (pybind11,
python/CMakeLists.txt), configured here for the interpreter pip runs under, in
a CMake build folder of its own: $MBFE_PIP_BUILD_DIR, or build/pip beside the
sources. It compiles solvers at run time with this build's compiler and
carries the ABI header inside, so the installed module needs no source tree.
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = Path(__file__).resolve().parent


class CMakeModule(Extension):
    """The module CMake builds (target mbfe_python); setuptools compiles nothing itself."""

    def __init__(self, name: str):
        super().__init__(name, sources=[])


class BuildWithCMake(build_ext):
    def build_extension(self, ext: Extension) -> None:
        build = Path(os.environ.get("MBFE_PIP_BUILD_DIR", SOURCE / "build" / "pip")).resolve()
        configure = [
            "cmake", "-S", str(SOURCE), "-B", str(build),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DMBFE_BUILD_TESTS=OFF", "-DMBFE_BUILD_BENCHMARKS=OFF", "-DMBFE_BUILD_PYTHON=ON",
            f"-DPython_EXECUTABLE={sys.executable}",
        ]
        if shutil.which("ccache"):
            configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        subprocess.run(configure, check=True)
        jobs = str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(build), "--target", "mbfe_python", "-j", jobs], check=True)
        built = sorted((build / "python").glob("mbfe*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one module in {build / 'python'}, found {[p.name for p in built]}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(ext_modules=[CMakeModule("mbfe")], cmdclass={"build_ext": BuildWithCMake})
