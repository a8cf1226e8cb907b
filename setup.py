"""Builds the penumbra Python package with the project's CMake (see pyproject.toml).

The module is compiled for the interpreter running pip, in build/pip, and
the package folder CMake assembles there (python/penumbra plus _penumbra.so)
is what gets installed.
"""
import os
import pathlib
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = ROOT / "build" / "pip"
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 2))
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                        "-DPENUMBRA_BUILD_TESTS=OFF", "-DPENUMBRA_BUILD_PYTHON=ON",
                        f"-DPython_EXECUTABLE={sys.executable}"], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "penumbra_python", "-j", jobs], check=True)
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).parent
        target.mkdir(parents=True, exist_ok=True)
        for file in (build / "python" / "penumbra").iterdir():
            self.copy_file(str(file), str(target / file.name))


setup(packages=["penumbra"], package_dir={"": "python"},
      ext_modules=[Extension("penumbra._penumbra", sources=[])], cmdclass={"build_ext": CMakeBuild})
