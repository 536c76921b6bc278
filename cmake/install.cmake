# hilite as a library for other projects (`cmake --install build --prefix P`):
#   P/lib/libhilite.so.1              every installed layer and the GL loader in one shared library (hilite::hilite)
#   P/include/hilite/                 the public headers, include/hilite/ as it is (<hilite/hilite.hpp>,
#                                     <hilite/scene/registry.hpp>, ...) and the generated version.hpp and shaders/brdf.glsl
#   P/libexec/hilite-probe            the .brdf shader probe's child process (measurement/shader_probe.hpp)
#   P/lib/cmake/hilite/               hiliteConfig.cmake, hiliteConfigVersion.cmake, hiliteTargets*.cmake:
#                                     find_package(hilite 1.0) gives hilite::hilite
#   P/lib/pkgconfig/hilite.pc         `pkg-config --cflags --libs hilite`
# Shaders, data and experiments go to P/share/hilite/ (top-level CMakeLists.txt); the library finds them and
# the probe relative to itself (core/install_paths.hpp), under any prefix. The include path is P/include.
include(CMakePackageConfigHelpers)

# THE list of installed layers (src/<name>/, made by hilite_layer() in src/CMakeLists.txt), in link order:
# each layer before every layer it links. Every layer must be here or in HILITE_PRIVATE_LAYERS (not in the
# library: the CLI stays private to the executable); checked below.
set(HILITE_INSTALL_LAYERS experiments measurement scene render io gl analysis micro brdf_file brdf core)
set(HILITE_PRIVATE_LAYERS cli)

# -- Checks of the list against the layers the build made, so a new or renamed layer is not missed silently.
get_property(_hilite_made GLOBAL PROPERTY HILITE_LAYERS)
foreach(_layer IN LISTS _hilite_made)
  if(NOT _layer IN_LIST HILITE_INSTALL_LAYERS AND NOT _layer IN_LIST HILITE_PRIVATE_LAYERS)
    message(FATAL_ERROR "cmake/install.cmake: layer '${_layer}' (hilite_${_layer}) is neither in "
                        "HILITE_INSTALL_LAYERS nor in HILITE_PRIVATE_LAYERS: add it to one of them")
  endif()
endforeach()
foreach(_layer IN LISTS HILITE_INSTALL_LAYERS)
  if(NOT _layer IN_LIST _hilite_made)
    message(FATAL_ERROR "cmake/install.cmake: HILITE_INSTALL_LAYERS names '${_layer}', which no hilite_layer() made")
  endif()
  list(FIND HILITE_INSTALL_LAYERS ${_layer} _pos)
  get_target_property(_deps hilite_${_layer} LINK_LIBRARIES)
  foreach(_dep IN LISTS _deps)
    if(_dep MATCHES "^hilite_(.+)$" AND NOT _dep STREQUAL "hilite_glad")
      set(_used ${CMAKE_MATCH_1})
      list(FIND HILITE_INSTALL_LAYERS ${_used} _used_pos)
      if(_used_pos EQUAL -1)
        message(FATAL_ERROR "cmake/install.cmake: installed layer '${_layer}' links '${_dep}', which is not installed")
      elseif(_used_pos LESS _pos)
        message(FATAL_ERROR "cmake/install.cmake: HILITE_INSTALL_LAYERS is not in link order: "
                            "'${_layer}' links '${_used}', so it must come before it")
      endif()
    endif()
  endforeach()
endforeach()
list(TRANSFORM HILITE_INSTALL_LAYERS PREPEND hilite_ OUTPUT_VARIABLE _hilite_targets)

# -- include/hilite/version.hpp, from project(hilite VERSION ...).
configure_file(${PROJECT_SOURCE_DIR}/include/hilite/version.hpp.in ${PROJECT_BINARY_DIR}/include/hilite/version.hpp @ONLY)

# -- hilite_static: every installed layer and what they link, for the build tree's own programs (the Python
# module links it in, so that it carries its code and finds its files beside itself).
add_library(hilite_static INTERFACE)
target_link_libraries(hilite_static INTERFACE ${_hilite_targets} hilite_glad glm::glm nlohmann_json::nlohmann_json
  tomlplusplus::tomlplusplus Threads::Threads ${CMAKE_DL_LIBS})

# -- hilite::hilite: libhilite.so, the layers' objects whole (so nothing a consumer needs is dropped).
add_library(hilite_library SHARED ${PROJECT_SOURCE_DIR}/src/library.cpp)
set_target_properties(hilite_library PROPERTIES OUTPUT_NAME hilite EXPORT_NAME hilite
  VERSION ${hilite_VERSION} SOVERSION ${hilite_VERSION_MAJOR} LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/lib)
target_link_libraries(hilite_library PRIVATE -Wl,--whole-archive ${_hilite_targets} hilite_glad -Wl,--no-whole-archive
  PUBLIC glm::glm nlohmann_json::nlohmann_json tomlplusplus::tomlplusplus Threads::Threads ${CMAKE_DL_LIBS})
target_include_directories(hilite_library PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
  $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_compile_features(hilite_library PUBLIC cxx_std_17)
add_library(hilite::hilite ALIAS hilite_library)

# -- The probe's child process, a small program of its own (no CLI): installed in libexec/.
add_executable(hilite-probe ${PROJECT_SOURCE_DIR}/src/probe_main.cpp)
target_link_libraries(hilite-probe PRIVATE hilite_measurement hilite_warnings)
add_dependencies(hilite hilite-probe)

install(TARGETS hilite_library EXPORT hiliteTargets LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS hilite-probe RUNTIME DESTINATION ${CMAKE_INSTALL_LIBEXECDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/hilite/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hilite
  FILES_MATCHING PATTERN "*.hpp")
install(FILES ${PROJECT_BINARY_DIR}/include/hilite/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hilite)
# The terms' one source, which hilite/brdf/terms.hpp includes (as C++ double).
install(FILES ${PROJECT_SOURCE_DIR}/shaders/brdf.glsl DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hilite/shaders)

# -- The CMake package.
set(HILITE_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/hilite)
set(HILITE_SHARE_INSTALL_DIR ${CMAKE_INSTALL_DATADIR}/hilite)
install(EXPORT hiliteTargets NAMESPACE hilite:: DESTINATION ${HILITE_CMAKE_INSTALL_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/hiliteConfig.cmake.in
  ${PROJECT_BINARY_DIR}/hiliteConfig.cmake INSTALL_DESTINATION ${HILITE_CMAKE_INSTALL_DIR}
  PATH_VARS HILITE_SHARE_INSTALL_DIR CMAKE_INSTALL_INCLUDEDIR)
# 1.x: a new minor version adds to the API, a new major one may change it.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/hiliteConfigVersion.cmake
  VERSION ${hilite_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/hiliteConfig.cmake ${PROJECT_BINARY_DIR}/hiliteConfigVersion.cmake
  DESTINATION ${HILITE_CMAKE_INSTALL_DIR})

# -- The pkg-config file, relocatable (${pcfiledir}); the rpath lets the program run from any prefix.
file(RELATIVE_PATH HILITE_PC_PREFIX ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" HILITE_PC_PREFIX "${HILITE_PC_PREFIX}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/hilite.pc.in ${PROJECT_BINARY_DIR}/hilite.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/hilite.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
