# The libFuzzer targets inside the sanitizer build (issue 23): with -DQUADRIX_FUZZ=ON (clang and
# QUADRIX_SANITIZE required) every target of the tree is compiled with the fuzzer's coverage
# instrumentation (-fsanitize=fuzzer-no-link) besides AddressSanitizer and UBSan, and the fuzz
# executables link the same quadrix_lib the sanitizer test suite runs. So one build serves the
# ASan+UBSan tests and all fuzz targets (scripts/test.sh), instead of a gcc build for the tests
# and separate clang builds for the fuzzers:
#
#   reader_fuzzer  the language reader           (tests/fuzz_reader/reader_fuzzer.cpp)
#   fuzz_v4 fuzz_v5 fuzz_comgeom fuzz_openscad fuzz_freeform fuzz_pipeline
#                  the importers and the whole pipeline (tests/fuzz_importers/importer_fuzzer.cpp)
#
# tests/fuzz_reader/CMakeLists.txt and tests/fuzz_importers/CMakeLists.txt stay as standalone
# projects for long fuzzing runs with RelWithDebInfo code (their README.md files).
option(QUADRIX_FUZZ "Build the libFuzzer targets (clang, with QUADRIX_SANITIZE)" OFF)
if(NOT QUADRIX_FUZZ)
  return()
endif()
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang" OR NOT QUADRIX_SANITIZE)
  message(FATAL_ERROR "QUADRIX_FUZZ needs clang (CXX=clang++) and -DQUADRIX_SANITIZE=ON")
endif()
target_compile_options(quadrix_flags INTERFACE -fsanitize=fuzzer-no-link)

add_executable(reader_fuzzer ${PROJECT_SOURCE_DIR}/tests/fuzz_reader/reader_fuzzer.cpp)
target_link_libraries(reader_fuzzer PRIVATE quadrix_lib)
target_link_options(reader_fuzzer PRIVATE -fsanitize=fuzzer)

set(index 1)
foreach(target IN ITEMS v4 v5 comgeom openscad freeform pipeline)
  add_executable(fuzz_${target} ${PROJECT_SOURCE_DIR}/tests/fuzz_importers/importer_fuzzer.cpp)
  target_compile_definitions(fuzz_${target} PRIVATE QUADRIX_FUZZ_TARGET=${index})
  target_link_libraries(fuzz_${target} PRIVATE quadrix_lib)
  target_link_options(fuzz_${target} PRIVATE -fsanitize=fuzzer)
  math(EXPR index "${index} + 1")
endforeach()
