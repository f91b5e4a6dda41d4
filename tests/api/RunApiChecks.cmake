# ctest driver of tests/api (see its CMakeLists.txt). CHECK selects the check:
#   installed_tree  install BUILD_DIR into PREFIX; compare PREFIX/include with PUBLIC_HEADERS, and
#                   the headers under each of PUBLIC_DIRS (the layers' include/ folders) with it too;
#   headers_alone   build PROJECT_DIR with one TU per installed header against PREFIX;
#   wrong_kind      build PROJECT_DIR's wrong-kind cases (each must fail, with its diagnostic) and its
#                   control (must build and run).
foreach(var CHECK BUILD_DIR PREFIX WORK_DIR PUBLIC_HEADERS PUBLIC_DIRS PROJECT_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "${var} not set")
  endif()
endforeach()
string(REPLACE "|" ";" public_headers "${PUBLIC_HEADERS}")
string(REPLACE "|" ";" public_dirs "${PUBLIC_DIRS}")
list(SORT public_headers)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()

# "a;b" against "a;c": FATAL_ERROR listing what is only in one of them.
function(compare_lists what expected actual)
  set(missing ${expected})
  set(extra ${actual})
  if(actual)
    list(REMOVE_ITEM missing ${actual})
  endif()
  if(expected)
    list(REMOVE_ITEM extra ${expected})
  endif()
  if(missing OR extra)
    string(REPLACE ";" "\n  " missing "${missing}")
    string(REPLACE ";" "\n  " extra "${extra}")
    message(FATAL_ERROR "${what}\nin the public list only:\n  ${missing}\nthere only:\n  ${extra}")
  endif()
  list(LENGTH actual n)
  message(STATUS "${what}: the ${n} public headers, no other file")
endfunction()

# Configures PROJECT_DIR against PREFIX into WORK_DIR/<name> with the given -D options.
function(configure_project name)
  set(dir ${WORK_DIR}/${name})
  file(REMOVE_RECURSE ${dir})
  set(compiler)
  if(CXX_COMPILER)
    set(compiler -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
  endif()
  run(${CMAKE_COMMAND} -S ${PROJECT_DIR} -B ${dir} -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_BUILD_TYPE=Release
      ${compiler} ${ARGN})
endfunction()

if(CHECK STREQUAL "installed_tree")
  file(REMOVE_RECURSE ${PREFIX})
  run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})
  # Every file under include/, and every C/C++ header anywhere in the prefix.
  file(GLOB_RECURSE installed RELATIVE ${PREFIX}/include ${PREFIX}/include/*)
  list(SORT installed)
  compare_lists("installed ${PREFIX}/include" "${public_headers}" "${installed}")
  file(GLOB_RECURSE stray RELATIVE ${PREFIX} ${PREFIX}/*.h ${PREFIX}/*.hpp ${PREFIX}/*.hxx ${PREFIX}/*.inl)
  list(FILTER stray EXCLUDE REGEX "^include/")
  if(stray)
    message(FATAL_ERROR "headers installed outside include/: ${stray}")
  endif()
  # The source side: a header under a layer's include/ is public (listed), else it belongs in
  # that layer's src/ or internal/.
  set(in_source)
  foreach(dir IN LISTS public_dirs)
    file(GLOB_RECURSE found RELATIVE ${dir} ${dir}/*)
    list(APPEND in_source ${found})
  endforeach()
  list(SORT in_source)
  compare_lists("the layers' include/ folders" "${public_headers}" "${in_source}")
elseif(CHECK STREQUAL "headers_alone")
  string(REPLACE ";" "|" list_arg "${public_headers}")
  configure_project(headers_alone "-DHEADERS=${list_arg}")
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/headers_alone -j2
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "a header does not compile alone:\n${out}\n${err}")
  endif()
  list(LENGTH public_headers n)
  message(STATUS "each of the ${n} installed headers compiles alone")
elseif(CHECK STREQUAL "wrong_kind")
  configure_project(wrong_kind -DWRONG_KIND=ON)
  # The control first: right handles, built, linked and run.
  run(${CMAKE_COMMAND} --build ${WORK_DIR}/wrong_kind --target right_kind)
  run(${WORK_DIR}/wrong_kind/right_kind)
  message(STATUS "right_kind: builds and runs")
  # Each case: the source that must not compile, and what the compiler must say about it.
  set(cases
    drum_slip_rate "getSlipRate"
    drum_as_traction_sheave "conversion from .*WinchDrumHandle.* to .*TractionSheaveHandle"
    turning_sheave_rope_on_drum "getRopeOnDrum"
    slip_rate_by_indices "getSlipRate"
    sheave_at_rope_end "DeviationSheave"
    drum_in_path "WinchDrum")
  list(LENGTH cases len)
  math(EXPR last "${len} - 1")
  foreach(i RANGE 0 ${last} 2)
    math(EXPR j "${i} + 1")
    list(GET cases ${i} name)
    list(GET cases ${j} diagnostic)
    execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/wrong_kind --target wrong_${name}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(rc EQUAL 0)
      message(FATAL_ERROR "wrong_${name} compiled: it must not")
    endif()
    # The failure must be the wrong kind itself: an error on the marked line naming it.
    string(REGEX MATCH "wrong_kind\\.cpp:[0-9]+:[0-9]+: error: [^\n]*" first_error "${out}${err}")
    if(NOT "${out}${err}" MATCHES "error: [^\n]*${diagnostic}")
      message(FATAL_ERROR "wrong_${name} failed, but not with an error naming '${diagnostic}':\n${out}\n${err}")
    endif()
    if(NOT first_error)
      message(FATAL_ERROR "wrong_${name} failed without an error in wrong_kind.cpp:\n${out}\n${err}")
    endif()
    message(STATUS "wrong_${name}: does not compile (${first_error})")
  endforeach()
else()
  message(FATAL_ERROR "unknown CHECK ${CHECK}")
endif()
