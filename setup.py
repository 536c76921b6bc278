"""Builds the hilite Python package with CMake (pyproject.toml): configures the project with the module and
nothing else (no tests, no benchmarks), builds the module, its stubs and the probe helper, and installs
CMake's `python` component (python/CMakeLists.txt) into the wheel: the same package `cmake --install` makes.

$HILITE_BUILD_DIR: an already configured hilite build tree to build in (the test suite's, which has built
everything already); else <source>/build/pip-cmake. $HILITE_BUILD_JOBS: parallel jobs (default: all CPUs)."""
import os
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def version():
    """project(hilite VERSION x.y.z) in CMakeLists.txt: the one place it is written."""
    text = open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8").read()
    return re.search(r"project\(hilite VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.environ.get("HILITE_BUILD_DIR") or os.path.join(ROOT, "build", "pip-cmake")
        jobs = os.environ.get("HILITE_BUILD_JOBS") or str(os.cpu_count() or 1)
        if not os.path.isfile(os.path.join(build, "CMakeCache.txt")):
            subprocess.run(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                            "-DHILITE_BUILD_TESTS=OFF", "-DHILITE_BUILD_BENCH=OFF", "-DHILITE_BUILD_PYTHON=ON",
                            f"-DPython_EXECUTABLE={sys.executable}"], check=True)
        subprocess.run(["cmake", "--build", build, "-j", jobs, "--target", "hilite_python", "hilite_python_stubs",
                        "hilite-probe"], check=True)
        stage = os.path.join(os.path.abspath(self.build_temp), "stage")
        shutil.rmtree(stage, ignore_errors=True)
        subprocess.run(["cmake", "--install", build, "--component", "python", "--prefix", stage], check=True)
        # The component installs <stage>/<HILITE_PYTHON_INSTALL_DIR>/hilite: find it, copy it whole.
        found = [d for d, _, files in os.walk(stage) if os.path.basename(d) == "hilite" and "__init__.py" in files]
        if len(found) != 1:
            raise RuntimeError(f"cmake --install --component python: expected one hilite package under {stage}, found {found}")
        target = os.path.dirname(os.path.abspath(self.get_ext_fullpath(ext.name)))
        shutil.rmtree(target, ignore_errors=True)
        shutil.copytree(found[0], target, symlinks=False)


# setuptools' own files (build/, *.egg-info) go under build/ beside CMake's, never among the sources.
os.makedirs(os.path.join("build", "pip-setuptools"), exist_ok=True)
setup(version=version(), packages=[], ext_modules=[Extension("hilite._hilite", sources=[])],
      cmdclass={"build_ext": CMakeBuild}, options={"build": {"build_base": os.path.join("build", "pip-setuptools")},
               "egg_info": {"egg_base": os.path.join("build", "pip-setuptools")}},
      zip_safe=False)
