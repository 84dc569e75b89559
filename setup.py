# Builds the Python module spring_motion (python/spring_motion_module.cpp) by
# running the project's own CMake build with SPRING_MOTION_BUILD_PYTHON=ON and
# copying the module where setuptools expects the extension:
#   pip install --no-build-isolation .
#
# Why a build_ext that calls CMake rather than scikit-build: the module links
# the C++ library, whose dependencies (CGAL, Boost, OpenMP, pybind11) CMake
# already finds; a plain setuptools Extension would repeat all of that, and
# scikit-build is one more package to install (Debian's python3-skbuild),
# while setuptools, wheel and cmake are there already. Nothing is fetched:
# CMake uses Debian's pybind11 (find_package(pybind11 CONFIG)).
#
# CMAKE_BUILD_PARALLEL_LEVEL sets the number of compile jobs (default 2).
import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = pathlib.Path(__file__).resolve().parent


def project_version():
    text = (SOURCE / "CMakeLists.txt").read_text()
    return re.search(r"project\(SpringMotion VERSION ([0-9.]+)", text).group(1)


class CMake_extension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMake_build(build_ext):
    def build_extension(self, ext):
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        subprocess.run(["cmake", "-S", str(SOURCE), "-B", str(build),
                        "-DCMAKE_BUILD_TYPE=Release",
                        "-DSPRING_MOTION_BUILD_PYTHON=ON",
                        "-DSPRING_MOTION_BUILD_TESTS=OFF",
                        "-DSPRING_MOTION_BUILD_EXAMPLES=OFF",
                        "-DSPRING_MOTION_BUILD_BENCH=OFF",
                        # the interpreter pip runs: the module is built for its ABI
                        "-DPython_EXECUTABLE=" + sys.executable,
                        "-DPYTHON_EXECUTABLE=" + sys.executable], check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.run(["cmake", "--build", str(build), "--target", "spring_motion_python", "-j", jobs],
                       check=True)
        built = build / "python" / ("spring_motion" + sysconfig.get_config_var("EXT_SUFFIX"))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


setup(
    name="spring_motion",
    version=project_version(),
    description="Spring-analogy mesh motion for triangle and tetrahedral meshes (Python module)",
    license="see LICENSE",
    python_requires=">=3.9",
    install_requires=["numpy"],
    ext_modules=[CMake_extension("spring_motion")],
    cmdclass={"build_ext": CMake_build},
    zip_safe=False,
)
