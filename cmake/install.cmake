# hilite as a library for other projects (`cmake --install build --prefix P`):
#   P/lib/libhilite_<layer>.a         one static library per installed layer, and libhilite_glad.a (the GL loader)
#   P/include/hilite/<layer>/*.hpp    each installed layer's headers, the src/ layout kept ("render/scene.hpp")
#   P/include/hilite/hilite.hpp       the public umbrella header (include/hilite/), and version.hpp
#   P/lib/cmake/hilite/               hiliteConfig.cmake, hiliteConfigVersion.cmake, hiliteTargets*.cmake:
#                                     find_package(hilite 0.1) gives hilite::hilite (every layer + dependencies)
#   P/lib/pkgconfig/hilite.pc         `pkg-config --cflags --libs hilite`
# Shaders, data and experiments go to P/share/hilite/ (top-level CMakeLists.txt). Both P/include/hilite (the
# layers include each other as "core/math.hpp") and P/include (<hilite/hilite.hpp>) are on the include path.
include(CMakePackageConfigHelpers)

# THE list of installed layers (src/<name>/, made by hilite_layer() in src/CMakeLists.txt), in link order:
# each layer before every layer it links (the order of the pkg-config Libs line). Headers are globbed from
# each one's folder, so adding or renaming a layer is a change of this list only. Every layer must be here
# or in HILITE_PRIVATE_LAYERS (not installed: the CLI stays private to the executable); checked below.
set(HILITE_INSTALL_LAYERS experiments measurement scene render io gl measure micro brdf_file brdf core)
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

# -- hilite::hilite: every installed layer and what they link. The same name in the build tree (ALIAS).
add_library(hilite_library INTERFACE)
set_target_properties(hilite_library PROPERTIES EXPORT_NAME hilite)
target_link_libraries(hilite_library INTERFACE ${_hilite_targets} hilite_glad glm::glm nlohmann_json::nlohmann_json
  tomlplusplus::tomlplusplus Threads::Threads ${CMAKE_DL_LIBS})
target_include_directories(hilite_library INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
  $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
add_library(hilite::hilite ALIAS hilite_library)

install(TARGETS ${_hilite_targets} hilite_glad hilite_library EXPORT hiliteTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(_layer IN LISTS HILITE_INSTALL_LAYERS)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/${_layer}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hilite/${_layer}
    FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h")
endforeach()
# The terms' one source, which brdf/terms.hpp includes (as C++ double) from the include path.
install(FILES ${PROJECT_SOURCE_DIR}/shaders/brdf.glsl DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hilite/shaders)
install(FILES ${PROJECT_SOURCE_DIR}/include/hilite/hilite.hpp ${PROJECT_BINARY_DIR}/include/hilite/version.hpp
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hilite)

# -- The CMake package.
set(HILITE_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/hilite)
set(HILITE_SHARE_INSTALL_DIR ${CMAKE_INSTALL_DATADIR}/hilite)
install(EXPORT hiliteTargets NAMESPACE hilite:: DESTINATION ${HILITE_CMAKE_INSTALL_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/hiliteConfig.cmake.in
  ${PROJECT_BINARY_DIR}/hiliteConfig.cmake INSTALL_DESTINATION ${HILITE_CMAKE_INSTALL_DIR}
  PATH_VARS HILITE_SHARE_INSTALL_DIR CMAKE_INSTALL_INCLUDEDIR)
# 0.x: a new minor version may change the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/hiliteConfigVersion.cmake
  VERSION ${hilite_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/hiliteConfig.cmake ${PROJECT_BINARY_DIR}/hiliteConfigVersion.cmake
  DESTINATION ${HILITE_CMAKE_INSTALL_DIR})

# -- The pkg-config file, relocatable (${pcfiledir}): Libs in link order, then the system libraries.
set(HILITE_PC_LIBS "")
foreach(_target IN LISTS _hilite_targets ITEMS hilite_glad)
  string(APPEND HILITE_PC_LIBS " -l${_target}")
endforeach()
file(RELATIVE_PATH HILITE_PC_PREFIX ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" HILITE_PC_PREFIX "${HILITE_PC_PREFIX}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/hilite.pc.in ${PROJECT_BINARY_DIR}/hilite.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/hilite.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# -- The library finds shaders and data by the prefix compiled in (HILITE_INSTALL_SHADER_DIR / _DATA_DIR, the
# configured CMAKE_INSTALL_PREFIX): a program linked against it is not in P/bin. Installed elsewhere
# (--prefix), such a program needs HILITE_SHARE_DIR=P/share/hilite; the hilite executable finds them either way.
install(CODE "
if(NOT CMAKE_INSTALL_PREFIX STREQUAL \"${CMAKE_INSTALL_PREFIX}\")
  message(NOTICE \"hilite: installed to \${CMAKE_INSTALL_PREFIX} but configured for ${CMAKE_INSTALL_PREFIX}: \"
    \"programs linked against the installed libraries look for shaders and data in ${CMAKE_INSTALL_FULL_DATADIR}/hilite \"
    \"unless HILITE_SHARE_DIR=\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DATADIR}/hilite is set \"
    \"(or configure with -DCMAKE_INSTALL_PREFIX=\${CMAKE_INSTALL_PREFIX})\")
endif()")
