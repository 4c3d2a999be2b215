# The modules' library targets (modules/<name>/CMakeLists.txt), each on the core's public API.

# ellipsect_add_module(TARGET EXPORT_NAME SOURCES...): the library TARGET from SOURCES, as
# ellipsect::EXPORT_NAME, with the module's include/ (installed beside the core's headers),
# linking the core, warnings as errors at the top level, installed and exported beside the core.
function(ellipsect_add_module target export_name)
  add_library(${target} ${ARGN})
  add_library(ellipsect::${export_name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} PUBLIC ellipsect::ellipsect)
  if(PROJECT_IS_TOP_LEVEL)
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Werror)
  endif()
  install(TARGETS ${target} EXPORT ellipsectTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ellipsect DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# ellipsect_engine_or_return(FOUND ENGINE PACKAGE): in an engine integration's CMakeLists.txt,
# returns from it, saying why, where the engine was not found (FOUND false) or where the build is
# the emulated wide type's test build (which tests the core's certified fallbacks alone).
macro(ellipsect_engine_or_return found engine package)
  if(NOT ${found})
    message(STATUS "ellipsect: ${engine} integration OFF (${package} not found)")
    return()
  endif()
  if(ELLIPSECT_EMULATED_WIDE)
    message(STATUS "ellipsect: ${engine} integration OFF in the emulated wide type's test build")
    return()
  endif()
endmacro()
