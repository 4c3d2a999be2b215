# Installs the build LIBRARY_BINARY_DIR (the one under test) into a scratch prefix, then
# configures, builds and runs a small consumer project against it with
# find_package(ellipsect): `consumer`, `engines` (the engine modules the package has), and the layout checks abi_* built with other SIMD
# flags and Eigen alignments (abi_avx512f runs only on a CPU with AVX-512; elsewhere it is
# only built).
set(prefix ${BINARY_DIR}/prefix)
file(REMOVE_RECURSE ${BINARY_DIR})
foreach(step
    "${CMAKE_COMMAND};--install;${LIBRARY_BINARY_DIR};--prefix;${prefix}"
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
execute_process(COMMAND ${BINARY_DIR}/app/engines RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR out MATCHES "failed")
  message(FATAL_ERROR "engines failed (${rc}):\n${out}\n${err}")
endif()
message(STATUS "engines output: ${out}")

file(READ /proc/cpuinfo cpuinfo)
file(GLOB abi_programs ${BINARY_DIR}/app/abi_*)
list(FILTER abi_programs INCLUDE REGEX "/abi_[a-z0-9]+$")
list(LENGTH abi_programs count)
if(count LESS 4)
  message(FATAL_ERROR "expected at least 4 abi_* programs, found: ${abi_programs}")
endif()
foreach(program ${abi_programs})
  if(program MATCHES "avx512" AND NOT cpuinfo MATCHES "avx512f")
    message(STATUS "${program}: built, not run (no avx512f in /proc/cpuinfo)")
    continue()
  endif()
  execute_process(COMMAND ${program} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out MATCHES ": ok ")
    message(FATAL_ERROR "${program} failed (${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endforeach()
