# ctest driver of python.install: install the build tree to a temporary prefix, then import the
# package from PREFIX/PACKAGE_DIR with no build folder on the path, run a pendulum case and a
# one-case study through the installed demos, and add a body to a System.
foreach(var BUILD_DIR WORK_DIR PYTHON PACKAGE_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "${var} not set")
  endif()
endforeach()
set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix}
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}): ${err}")
endif()
set(script [=[
import os, sys
import simbody_reeving as sr
prefix = os.path.realpath(sys.argv[1])
assert os.path.realpath(sr.__file__).startswith(prefix), sr.__file__
assert os.path.realpath(sr.demo_dir()) == os.path.join(prefix, "bin"), sr.demo_dir()
case = sr.run_pendulum(axial_modes=1, t_end=0.5)
assert case["summary"]["termination"] == "completed"
rows = sr.run_study({"scene": "pendulum", "fixed": {"axial-modes": 1, "t-end": 0.5}, "metrics": ["steps"]})
assert rows[0]["status"] == "ok" and rows[0]["steps"] == case["summary"]["steps"], rows
machine = sr.System()
drum = machine.add_pin(machine.ground, sr.MassProperties(1.0, (0, 0, 0), 1.0))
assert drum.kind == "Pin" and machine.num_bodies == 2
print("installed package:", sr.__file__)
]=])
file(WRITE ${WORK_DIR}/check.py "${script}")
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=SIMBODY_REEVING_DEMO_DIR PYTHONPATH=${prefix}/${PACKAGE_DIR}
                        ${PYTHON} ${WORK_DIR}/check.py ${prefix}
                WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed package failed (${rc}):\n${out}\n${err}")
endif()
file(REMOVE_RECURSE ${prefix})
