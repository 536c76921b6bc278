# ctest python_install: `cmake --install` puts the package where Debian's python3 imports it from the prefix,
# and the installed module measures (shaders and data from the installed share/hilite).
#   cmake -DHILITE_BUILD_DIR=... -DWORK_DIR=... -DPYTHON=... -DPYTHON_DIR=lib/python3.11/dist-packages -P run_install.cmake
include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/script_support.cmake)
hilite_require(run_install.cmake HILITE_BUILD_DIR WORK_DIR PYTHON PYTHON_DIR)
set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${HILITE_BUILD_DIR} --prefix ${prefix}
  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}): ${err}")
endif()
foreach(f __init__.py __init__.pyi brdf.pyi py.typed)
  if(NOT EXISTS ${prefix}/${PYTHON_DIR}/hilite/${f})
    message(FATAL_ERROR "not installed: ${prefix}/${PYTHON_DIR}/hilite/${f}")
  endif()
endforeach()
# From another folder, with only the installed tree: PYTHONPATH is the prefix's dist-packages.
# No HILITE_SHARE_DIR: the package finds its share files and probe helper beside itself.
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=HILITE_SHARE_DIR PYTHONPATH=${prefix}/${PYTHON_DIR}
    ${PYTHON} -c "import hilite, sys; assert hilite.__file__.startswith('${prefix}'), hilite.__file__; r = hilite.measure(model='ggx', roughness=0.1, incidence=60, size=128); print(r['aspect']); sys.exit(0 if 0.45 < r['aspect'] < 0.55 else 1)"
  WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed module failed (${rc}): ${out} ${err}")
endif()
message(STATUS "installed module: aspect ${out}")
