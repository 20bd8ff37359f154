# Warnings for kiri's own targets only (never exported to consumers).
function(kiri_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wno-missing-field-initializers)
endfunction()
