# ctest python_pip: the package as pip builds and installs it (pyproject.toml, setup.py), used from outside the
# source tree with nothing telling it where its files are, and no hilite executable on PATH.
#   cmake -DSOURCE_DIR=... -DHILITE_BUILD_DIR=... -DWORK_DIR=... -DPYTHON=/usr/bin/python3 -P run_pip.cmake
# HILITE_BUILD_DIR: setup.py builds in the suite's build tree (already built: the package step only); a user's
# `pip install .` configures and builds build/pip-cmake from scratch. Exit 77 (skipped) without pip or venv.
include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/script_support.cmake)
hilite_require(run_pip.cmake SOURCE_DIR HILITE_BUILD_DIR WORK_DIR PYTHON)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
foreach(module pip venv ensurepip)
  execute_process(COMMAND ${PYTHON} -c "import ${module}" RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if(NOT rc EQUAL 0)
    message(STATUS "SKIP: ${PYTHON} has no ${module} module (Debian: python3-pip, python3-venv; scripts/quickstart installs them)")
    cmake_language(EXIT 77)
  endif()
endforeach()

set(venv ${WORK_DIR}/V)
run(${PYTHON} -m venv --system-site-packages ${venv})
run(${CMAKE_COMMAND} -E env HILITE_BUILD_DIR=${HILITE_BUILD_DIR}
    ${venv}/bin/pip install --no-build-isolation --no-index --quiet ${SOURCE_DIR})
set(clean_env --unset=HILITE_SHARE_DIR --unset=HILITE_SHADER_DIR --unset=HILITE_DATA_DIR --unset=PYTHONPATH
    PATH=/usr/bin:/bin MESA_SHADER_CACHE_DISABLE=true)
# The README's line, as a user types it (a newline for its ';': run() passes its arguments as a CMake list).
run(${CMAKE_COMMAND} -E env ${clean_env} ${venv}/bin/python -c
    "import hilite\nprint(hilite.measure(model=\"ggx\", incidence=60)[\"aspect\"])")
string(STRIP "${run_out}" aspect)
message(STATUS "pip-installed hilite: ggx at 60 deg: aspect ${aspect}")
if(NOT aspect MATCHES "^0\\.501[0-9]*$")
  message(FATAL_ERROR "expected the GGX aspect 0.5017 at 60 degrees, got '${aspect}'")
endif()
# Where it came from, and a .brdf measured through the package's own probe helper (no hilite on PATH).
run(${CMAKE_COMMAND} -E env ${clean_env} ${venv}/bin/python -c "
import hilite, os, shutil
here = os.path.dirname(hilite.__file__)
assert here.startswith('${venv}'), here
assert shutil.which('hilite') is None, shutil.which('hilite')
assert os.access(os.path.join(here, 'libexec', 'hilite-probe'), os.X_OK)
r = hilite.measure(brdf='${SOURCE_DIR}/experiments/brdfs/ggx.brdf', incidence=60)
g = hilite.measure(model='ggx', incidence=60)
assert r['flags'] == [], r['flags']
assert abs(r['aspect'] - g['aspect']) < 2e-3, (r['aspect'], g['aspect'])
print(here, r['aspect'])
")
message(STATUS "pip-installed hilite, .brdf probed by its own helper: ${run_out}")
