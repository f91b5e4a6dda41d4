# Warnings for the project's own code; third-party headers (Simbody, Eigen) come in as SYSTEM.
function(simbodyreeving_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Werror)
endfunction()
