# SPDX-License-Identifier: BSD-3-Clause
# Sanitizer builds: VOXLINK_SANITIZE instruments every target (the ASan + UBSan test run in
# scripts/run-tests.sh); VOXLINK_FUZZ adds libFuzzer's coverage hooks on top of ASan + UBSan
# (fuzz/, clang only). Undefined behaviour stops the program so a test or fuzz run fails on it.
if(VOXLINK_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "VOXLINK_FUZZ needs clang (e.g. -DCMAKE_CXX_COMPILER=clang++-14)")
  endif()
  if(NOT VOXLINK_SANITIZE)
    set(VOXLINK_SANITIZE "address,undefined")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
  # libFuzzer's convention: code may skip checks a fuzzer cannot pass by mutation (the packed
  # file's payload checksums), so the decoders behind them are fuzzed too.
  add_compile_definitions(FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION)
endif()
if(VOXLINK_SANITIZE)
  add_compile_options(-fsanitize=${VOXLINK_SANITIZE} -fno-sanitize-recover=all
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${VOXLINK_SANITIZE})
endif()
