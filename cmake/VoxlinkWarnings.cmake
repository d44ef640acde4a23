# Warnings for our own targets only (third-party headers are included as SYSTEM).
function(voxlink_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wno-missing-field-initializers)
endfunction()
