"""Bad input from Python: ten wrong parameters, each raising ValueError with the C++ message (the
scene's, the span model's, the integrator factory's, the stepper's, the study runner's), none
taking the interpreter down; then a run in the same interpreter still works."""

import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(__file__))
import support  # noqa: E402

import simbody_reeving as sr  # noqa: E402


def raises(exception, message, call):
    try:
        call()
    except exception as e:
        assert str(e) == message, "%r != %r" % (str(e), message)
        return
    raise AssertionError("no %s: %s" % (exception.__name__, message))


def stepped_back():
    scene = sr.PendulumScene()
    sim = scene.simulation(scene.make_initial_state())
    sim.step_to(0.1)
    sim.step_to(0.05)


def test_ten_wrong_parameters_raise_the_cpp_message():
    cases = [
        (lambda: sr.PendulumScene(sr.PendulumParameters(EA=-1)),
         "PendulumParameters: EA = -1 must be finite and > 0"),
        (lambda: sr.run_pendulum(parameters=sr.PendulumParameters(M=math.nan)),
         "PendulumParameters: M = nan must be finite and > 0"),
        (lambda: sr.run_pendulum(axial_modes=17),
         "ReevingSubsystem: rope 'pendulum rope': SpanModel: SpanOptions::axialModes (n_a) = 17 is outside 0..16"),
        (lambda: sr.run_pendulum(integrator="bogus"),
         "unknown integrator 'bogus' (known: rk-merson, rk3, rk-feldberg, cpodes, verlet, semi-explicit-euler2, "
         "explicit-euler)"),
        (lambda: sr.ElevatorScene(sr.ElevatorParameters(car_load=2)),
         "ElevatorParameters: carLoad [-] = 2 must be in [0, 1.25] (of the rated load)"),
        (lambda: sr.ElevatorScene(sr.ElevatorParameters(car_position=30)),
         "ElevatorParameters: carPosition + tripDistance [m] = 42 must be < hoistway - 4 in the trip scenario"),
        (lambda: sr.CraneScene(sr.CraneParameters(falls=13)), "CraneParameters: falls = 13 must be in 1..12"),
        (stepped_back,
         "InterpolatingTimeStepper::stepTo: report time 0.050000000000000003 s is before the time already reached, "
         "0.10000000000000001 s"),
        (lambda: sr.run_study({"scene": "elevator", "metrics": ["traction_margin"]}),
         "<study dict>:4:5: unknown metric 'traction_margin' for scene elevator "
         "(did you mean traction_table.0.traction_margin?)"),
        (lambda: sr.run_study({"scene": "elevator", "vary": {"car-load": [0, 2]},
                               "metrics": ["traction_table.0.traction_margin"]}),
         "<study dict>:6:7: case 1 (car-load=2) is rejected by reeving-elevator: ElevatorParameters: carLoad [-] = 2 "
         "must be in [0, 1.25] (of the rated load) (scenario trip)"),
    ]
    for call, message in cases:
        raises(ValueError, message, call)
    # The study's errors are StudyError, a ValueError.
    raises(sr.StudyError, cases[8][1], cases[8][0])
    # The same messages as the demos print for the same input.
    check = subprocess.run([os.path.join(support.EXAMPLES, "reeving-pendulum"), "--set", "EA=-1", "--check"],
                           capture_output=True, text=True)
    assert check.returncode == 2 and cases[0][1] in check.stderr, check.stderr
    check = subprocess.run([os.path.join(support.EXAMPLES, "reeving-elevator"), "--car-load", "2", "--scenario",
                            "loading", "--check"], capture_output=True, text=True)
    assert check.returncode == 2 and cases[4][1] in check.stderr, check.stderr


def test_other_bad_input():
    raises(ValueError, "accuracy = 2 must be in (0, 1)", lambda: sr.run_pendulum(accuracy=2))
    raises(ValueError, "report_interval: 0.01 s must not exceed t_end (0.001 s)", lambda: sr.run_pendulum(t_end=0.001))
    raises(TypeError, "SpanOptions: unknown parameter 'bogus'", lambda: sr.SpanOptions(bogus=1))
    scene = sr.PendulumScene()
    state = scene.make_initial_state()
    raises(IndexError, "span 5 out of range: rope 0 has 2 span(s)", lambda: scene.reeving.axial_force(state, 0, 5, 1.0))
    raises(IndexError, "rope 1 out of range: there are 1 rope(s)", lambda: scene.reeving.num_spans(1))


def test_interpreter_alive_after_the_errors():
    test_ten_wrong_parameters_raise_the_cpp_message()
    case = sr.run_pendulum(axial_modes=1, t_end=0.5)
    assert case["summary"]["termination"] == "completed" and len(case["timeseries"]["t"]) == 51


if __name__ == "__main__":
    sys.exit(support.main(globals()))
