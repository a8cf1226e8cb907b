# Sanitizer and fuzzing builds (docs/RELIABILITY.md). Both apply to every
# target, dependencies' headers included, so a report anywhere aborts the run.
#
#   -DPENUMBRA_SANITIZE=address,undefined   GCC or clang; `make sanitize` and CI use it
#   -DPENUMBRA_FUZZ=ON                      clang only: libFuzzer targets in tests/fuzz
#                                           (scripts/fuzz.sh builds and runs them)
set(PENUMBRA_SANITIZE "" CACHE STRING "Sanitizers for every target, e.g. address,undefined (empty: none)")
option(PENUMBRA_FUZZ "Build the libFuzzer targets of tests/fuzz, with ASan and UBSan (clang only)" OFF)

if(PENUMBRA_SANITIZE)
  set(_penumbra_sanitizers ${PENUMBRA_SANITIZE})
  # GCC's "undefined" leaves out float-cast-overflow (clang's includes it):
  # a NaN or 1e30 cast to int is exactly what the readers must not do.
  if(PENUMBRA_SANITIZE MATCHES "undefined" AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    string(APPEND _penumbra_sanitizers ",float-cast-overflow")
  endif()
  # -fno-sanitize-recover: a UBSan report aborts like an ASan one, so a test
  # run cannot pass with a report in its log.
  add_compile_options(-fsanitize=${_penumbra_sanitizers} -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${_penumbra_sanitizers})
endif()

if(PENUMBRA_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "PENUMBRA_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
  endif()
  # Every object gets the fuzzer's coverage counters; only the fuzz targets
  # link libFuzzer's main (-fsanitize=fuzzer, tests/fuzz/CMakeLists.txt).
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
