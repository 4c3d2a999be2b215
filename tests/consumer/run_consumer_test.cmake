# Installs ellipsect into a scratch prefix, then configures, builds and runs a small
# consumer project against it with find_package(ellipsect).
set(prefix ${BINARY_DIR}/prefix)
file(REMOVE_RECURSE ${BINARY_DIR})
foreach(step
    "${CMAKE_COMMAND};-S;${SOURCE_DIR};-B;${BINARY_DIR}/lib;-G;${GENERATOR};-DCMAKE_BUILD_TYPE=Release;-DELLIPSECT_BUILD_TESTS=OFF;-DELLIPSECT_BUILD_BENCH=OFF;-DELLIPSECT_BUILD_TOOLS=OFF;-DCMAKE_INSTALL_PREFIX=${prefix}"
    "${CMAKE_COMMAND};--build;${BINARY_DIR}/lib"
    "${CMAKE_COMMAND};--install;${BINARY_DIR}/lib"
    "${CMAKE_COMMAND};-S;${SOURCE_DIR}/tests/consumer;-B;${BINARY_DIR}/app;-G;${GENERATOR};-DCMAKE_PREFIX_PATH=${prefix}"
    "${CMAKE_COMMAND};--build;${BINARY_DIR}/app"
    "${BINARY_DIR}/app/consumer")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${step}\n${out}\n${err}")
  endif()
endforeach()
if(NOT out MATCHES "hit 4")
  message(FATAL_ERROR "consumer printed an unexpected answer: ${out}")
endif()
message(STATUS "consumer output: ${out}")
