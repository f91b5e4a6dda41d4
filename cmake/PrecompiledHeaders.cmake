# Shared precompiled headers (CMake >= 3.16). Simbody.h, Eigen and gtest.h are most of the compile
# time of each test, example and benchmark translation unit; a PCH target compiles them once and the
# executables reuse it (target_precompile_headers REUSE_FROM), instead of once per target.
#
# REUSE_FROM needs the reusing target's compile flags to match the PCH target's (macros, -std, PIC,
# sanitizers): so a PCH target links what its users link (usage requirements alike: SYSTEM includes,
# -UNDEBUG of the Simbody layer, GTEST_HAS_PTHREAD) and takes the project's warnings. GCC checks the
# rest: CMake compiles every user with -Winvalid-pch, which -Werror makes an error, so a user whose
# flags drift from its PCH fails to build instead of silently reparsing the headers.
# Configure with -DCMAKE_DISABLE_PRECOMPILE_HEADERS=ON to build without any PCH.

# simbodyreeving_add_pch(<name> HEADERS <header>... LINK <target>...): an object library that only
# compiles the precompiled header of HEADERS with the usage requirements of LINK.
function(simbodyreeving_add_pch name)
  cmake_parse_arguments(P "" "" "HEADERS;LINK" ${ARGN})
  add_library(${name} OBJECT ${PROJECT_SOURCE_DIR}/cmake/pch/pch_anchor.cpp)
  target_link_libraries(${name} PRIVATE ${P_LINK})
  simbodyreeving_set_warnings(${name})
  target_precompile_headers(${name} PRIVATE ${P_HEADERS})
endfunction()

# simbodyreeving_use_pch(<target> <pch>): <target> reuses the precompiled header of <pch>.
function(simbodyreeving_use_pch target pch)
  target_precompile_headers(${target} REUSE_FROM ${pch})
endfunction()

# simbodyreeving_use_library_pch(<target>): an example or benchmark reuses the Simbody layer's
# precompiled header (<Simbody.h>, target SimbodyReevingSimbodyPch in plugin/CMakeLists.txt), so a build that needs one demo compiles one PCH, not two. The
# target takes the flags the library's PCH was compiled with (-fPIC, which CMake gives a library
# with POSITION_INDEPENDENT_CODE, where an executable would get -fPIE; Eigen's run-time assertions
# off as in the library): GCC rejects a PCH whose flags differ (see above).
function(simbodyreeving_use_library_pch target)
  target_compile_options(${target} PRIVATE -fPIC)
  target_compile_definitions(${target} PRIVATE $<$<NOT:$<CONFIG:Debug>>:EIGEN_NO_DEBUG>)
  target_precompile_headers(${target} REUSE_FROM SimbodyReevingSimbodyPch)
endfunction()
