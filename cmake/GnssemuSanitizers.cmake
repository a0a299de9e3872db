# SPDX-License-Identifier: Apache-2.0
# Sanitizer and fuzzing builds (docs/robustness.md).
#
# GNSSEMU_SANITIZE=address,undefined instruments every target of the project
# (gcc or clang): errors abort, so a unit test that trips one fails. CI runs
# the unit tests in such a build (tools/test.sh, build-asan/).
#
# GNSSEMU_FUZZ=ON (clang only, a build of its own: tests/fuzz/fuzz.sh)
# adds libFuzzer's coverage instrumentation to every library and builds the
# fuzz targets of tests/fuzz; it implies address,undefined unless
# GNSSEMU_SANITIZE says otherwise.
set(GNSSEMU_SANITIZE "" CACHE STRING
    "Sanitizers for every target, comma-separated: address, undefined, leak, thread (empty: none)")
option(GNSSEMU_FUZZ "Build the libFuzzer targets of tests/fuzz (clang; instruments every library)" OFF)

if(GNSSEMU_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "GNSSEMU_FUZZ needs clang (libFuzzer): configure with CXX=clang++ "
                        "(tests/fuzz/fuzz.sh build does); this compiler is ${CMAKE_CXX_COMPILER_ID}")
  endif()
  if(GNSSEMU_SANITIZE STREQUAL "")
    set(GNSSEMU_SANITIZE "address,undefined" CACHE STRING "" FORCE)
  endif()
endif()

if(NOT GNSSEMU_SANITIZE STREQUAL "")
  string(REPLACE "," ";" _sanitizers "${GNSSEMU_SANITIZE}")
  foreach(s IN LISTS _sanitizers)
    if(NOT s MATCHES "^(address|undefined|leak|thread)$")
      message(FATAL_ERROR "GNSSEMU_SANITIZE: unknown sanitizer '${s}' (address, undefined, leak, thread)")
    endif()
  endforeach()
  if("thread" IN_LIST _sanitizers AND ("address" IN_LIST _sanitizers OR "leak" IN_LIST _sanitizers))
    message(FATAL_ERROR "GNSSEMU_SANITIZE: thread cannot be combined with address or leak")
  endif()
  # GCC leaves float-to-int overflow out of "undefined" (clang includes it):
  # it is undefined behaviour all the same (C++20 [conv.fpint]).
  if("undefined" IN_LIST _sanitizers AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    list(APPEND _sanitizers float-cast-overflow)
  endif()
  string(REPLACE ";" "," _flag "${_sanitizers}")
  # -g1: line tables for the reports; the rest stays a Release build.
  add_compile_options(-fsanitize=${_flag} -fno-sanitize-recover=all -fno-omit-frame-pointer -g1)
  add_link_options(-fsanitize=${_flag} -fno-sanitize-recover=all)
  message(STATUS "gnssemu: sanitizers ${_flag}")
endif()

if(GNSSEMU_FUZZ)
  # Coverage feedback for libFuzzer in every library; the fuzz targets link
  # the fuzzer's main (tests/fuzz/CMakeLists.txt).
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
