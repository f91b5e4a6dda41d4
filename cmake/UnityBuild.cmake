# Unity builds of the plugin's Simbody-side libraries (CMake >= 3.16 UNITY_BUILD).
# Each Simbody-side translation unit spends most of its compile time instantiating and generating
# the same Simbody and Eigen inline code; compiling a library's sources as one or two combined
# translation units does that once. Measured on the 2-core project machine (fresh clone, the
# pendulum demo's targets, Ninja): 314 s of CPU without, 235 s with. The element layer is not
# combined: its translation units are costly in their own code and gain nothing from it.
# Configure with -DSIMBODYREEVING_UNITY_BUILD=OFF for one translation unit per source (e.g. to check
# that every source includes what it uses).
option(SIMBODYREEVING_UNITY_BUILD "Compile the Simbody-side libraries as combined translation units" ON)

# simbodyreeving_unity_build(<target> <batch size>): <target>'s sources are combined <batch size> at a
# time, in the order they are listed (so a two-core build gets two balanced halves).
function(simbodyreeving_unity_build target batch_size)
  if(SIMBODYREEVING_UNITY_BUILD)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${batch_size})
  endif()
endfunction()
