# ctest downstream_install (label install): hilite installed and used by other projects.
#   cmake -DHILITE_BUILD_DIR=... -DWORK_DIR=... -DCXX=... -DGENERATOR=... -P run_downstream.cmake
# 1. cmake --install HILITE_BUILD_DIR to WORK_DIR/prefix (a fresh one each run), and checks the tree;
# 2. configures and builds tests/downstream (find_package(hilite), doctest) against it, runs its ctest;
# 3. builds pkgconfig_consumer.cpp with `pkg-config --cflags --libs hilite` alone, and runs it;
# 4. moves the share files away: the consumer fails with a message naming HILITE_SHARE_DIR and the places.
# Nothing is told where hilite is at run time: no HILITE_SHARE_DIR, and no hilite executable in the prefix
# (removed after the install) or on PATH (the system's folders only).
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/script_support.cmake)
hilite_require(run_downstream.cmake HILITE_BUILD_DIR WORK_DIR CXX GENERATOR)
set(src ${CMAKE_CURRENT_LIST_DIR})
set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

string(TIMESTAMP t0 "%s")
macro(step what)
  string(TIMESTAMP _now "%s")
  math(EXPR _dt "${_now} - ${t0}")
  message(STATUS "[${_dt} s] ${what}")
endmacro()

# -- 1. Install, then check what the tree holds.
step("cmake --install ${HILITE_BUILD_DIR} --prefix ${prefix}")
execute_process(COMMAND ${CMAKE_COMMAND} --install ${HILITE_BUILD_DIR} --prefix ${prefix}
  RESULT_VARIABLE rc OUTPUT_FILE ${WORK_DIR}/install.log ERROR_FILE ${WORK_DIR}/install.err)
if(NOT rc EQUAL 0)
  file(READ ${WORK_DIR}/install.err err)
  message(FATAL_ERROR "cmake --install failed (${rc}):\n${err}")
endif()
foreach(f bin/hilite lib/cmake/hilite/hiliteConfig.cmake lib/cmake/hilite/hiliteConfigVersion.cmake
          lib/cmake/hilite/hiliteTargets.cmake lib/pkgconfig/hilite.pc lib/libhilite.so libexec/hilite-probe
          include/hilite/hilite.hpp include/hilite/version.hpp include/hilite/scene/registry.hpp
          include/hilite/shaders/brdf.glsl share/hilite/shaders/brdf.glsl
          share/hilite/data/colorimetry/cie1931_2deg_cmf.csv share/hilite/experiments/brdfs/ggx.brdf)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${prefix}/${f}")
  endif()
endforeach()
foreach(f lib/libhilite_cli.a lib/libhilite_core.a include/hilite/cli include/hilite/render/renderer.hpp
          include/hilite/gl/context.hpp include/hilite/render/shader_source.hpp)
  if(EXISTS ${prefix}/${f})
    message(FATAL_ERROR "installed, but internal: ${prefix}/${f}")
  endif()
endforeach()
# Every project include of an installed header is "hilite/..." and resolves inside the installed tree.
file(GLOB_RECURSE headers ${prefix}/include/hilite/*.hpp)
foreach(h IN LISTS headers)
  file(STRINGS ${h} includes REGEX "^#include \"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" inc "${line}")
    if(NOT inc MATCHES "^hilite/" OR NOT EXISTS ${prefix}/include/${inc})
      message(FATAL_ERROR "${h} includes \"${inc}\", which is not installed")
    endif()
  endforeach()
endforeach()
list(LENGTH headers nheaders)
step("installed tree checked (${nheaders} headers)")
file(REMOVE ${prefix}/bin/hilite)  # the library must not need it (the .brdf probe runs libexec/hilite-probe)
set(clean_env --unset=HILITE_SHARE_DIR --unset=HILITE_SHADER_DIR --unset=HILITE_DATA_DIR PATH=/usr/bin:/bin
    MESA_SHADER_CACHE_DISABLE=true)

# -- 2. The CMake package: find_package(hilite 1.0 REQUIRED), hilite::hilite, doctest.
run(${CMAKE_COMMAND} -S ${src} -B ${WORK_DIR}/cmake-consumer -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${prefix})
step("downstream project configured")
run(${CMAKE_COMMAND} --build ${WORK_DIR}/cmake-consumer -j2)
step("downstream project built")
execute_process(COMMAND ${CMAKE_COMMAND} -E env ${clean_env} ${CMAKE_CTEST_COMMAND} --output-on-failure -V --no-tests=error
  WORKING_DIRECTORY ${WORK_DIR}/cmake-consumer RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the downstream project's test failed (${rc})")
endif()
step("downstream project's test passed")

# -- 3. pkg-config alone.
find_program(PKG_CONFIG NAMES pkg-config pkgconf REQUIRED)
execute_process(COMMAND ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${prefix}/lib/pkgconfig
                        ${PKG_CONFIG} --cflags --libs hilite
  RESULT_VARIABLE rc OUTPUT_VARIABLE flags ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config --cflags --libs hilite failed (${rc}): ${err}")
endif()
message(STATUS "pkg-config --cflags --libs hilite: ${flags}")
separate_arguments(flags UNIX_COMMAND "${flags}")
# In a folder of its own: beside the build tree's bin/, ../share/hilite would be the build's share files.
file(MAKE_DIRECTORY ${WORK_DIR}/pkgconfig/bin)
run(${CXX} -std=c++17 -O2 ${src}/pkgconfig_consumer.cpp ${flags} -o ${WORK_DIR}/pkgconfig/bin/pkgconfig_consumer)
step("pkg-config consumer built")
run(${CMAKE_COMMAND} -E env ${clean_env} ${WORK_DIR}/pkgconfig/bin/pkgconfig_consumer)
step("pkg-config consumer passed")

# -- 4. Without its share files the library says where it looked and how to tell it (exit 2 from the consumer).
file(RENAME ${prefix}/share ${prefix}/share.away)
execute_process(COMMAND ${CMAKE_COMMAND} -E env ${clean_env} ${WORK_DIR}/pkgconfig/bin/pkgconfig_consumer
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(RENAME ${prefix}/share.away ${prefix}/share)
if(NOT rc EQUAL 2 OR NOT err MATCHES "HILITE_SHARE_DIR" OR NOT err MATCHES "looked in .*/share/hilite/shaders \\(beside [^)]*libhilite")
  message(FATAL_ERROR "without share/hilite: expected exit 2 and a message naming HILITE_SHARE_DIR and the "
                      "places looked in beside libhilite.so; got ${rc}: ${err}")
endif()
message(STATUS "without share/hilite: ${err}")
step("missing share files named")
