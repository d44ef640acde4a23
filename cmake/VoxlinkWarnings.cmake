# SPDX-License-Identifier: BSD-3-Clause
# Warnings for our own targets only (third-party headers are included as SYSTEM).
# CI builds with VOXLINK_WERROR=ON (scripts/run-tests.sh): a warning there fails the build.
option(VOXLINK_WERROR "Treat compiler warnings in the project's own code as errors" OFF)
function(voxlink_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wno-missing-field-initializers)
  if(VOXLINK_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
