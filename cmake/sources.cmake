# The library's sources and their per-file settings, for every build that compiles them: the
# library (../CMakeLists.txt) and the demo page's module (../web/CMakeLists.txt).
get_filename_component(ellipsect_source_root ${CMAKE_CURRENT_LIST_DIR}/../src ABSOLUTE)
# ellipsect_sources: every .cpp under src/, subfolders included.
file(GLOB_RECURSE ellipsect_sources CONFIGURE_DEPENDS ${ellipsect_source_root}/*.cpp)
# Every SIMD lane must round as the scalar code does (batch = scalar bit for bit), and the
# error-free products of detail/compensated.hpp stay error-free: no fused multiply-adds.
# (A unity build compiles files with options of their own alone.)
set_source_files_properties(${ellipsect_source_root}/many/batch_kernels.cpp ${ellipsect_source_root}/obstacles/half_space.cpp
                            ${ellipsect_source_root}/obstacles/triangle.cpp ${ellipsect_source_root}/geometry/inscribed.cpp
                            PROPERTIES COMPILE_OPTIONS -ffp-contract=off)
# The files that compute in rationals (detail/rational.hpp): GMP's where the build has it
# (the library), Boost's own otherwise (the page). Each is compiled alone, so that every
# file sees one rational type.
set(ellipsect_exact_sources ${ellipsect_source_root}/pair/exact_relation.cpp ${ellipsect_source_root}/geometry/enclosing.cpp
                           ${ellipsect_source_root}/geometry/hull.cpp)
# GCC 12 reads Eigen's long double packets in enclosing.cpp's Newton step as maybe
# uninitialized where only double is instantiated (ELLIPSECT_DOUBLE_ONLY): a false positive.
set_source_files_properties(${ellipsect_source_root}/geometry/enclosing.cpp PROPERTIES COMPILE_OPTIONS $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
