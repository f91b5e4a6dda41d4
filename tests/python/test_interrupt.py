"""Ctrl-C: SIGINT to a Python process in the middle of a long run (run_pendulum, Simulation.run, a
study) raises KeyboardInterrupt there within a fraction of a second; the process goes on (the
next run works) or, uncaught, ends as Python ends on KeyboardInterrupt, never by a crash."""

import os
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(__file__))
import support  # noqa: E402

LONG_RUNS = {
    # about a minute or more each on the project's machine: far longer than the test waits
    "run_pendulum": "sr.run_pendulum(axial_modes=3, axial_dynamics='dynamic', t_end=1000)",
    "simulation": ("scene = sr.PendulumScene(spans=sr.SpanOptions(axial_modes=3, axial_dynamics=sr.AxialDynamics.Dynamic))\n"
                   "    scene.simulation(scene.make_initial_state()).run(t_end=1000)"),
    "study": ("sr.run_study({'scene': 'pendulum', 'fixed': {'axial-modes': 3, 'axial-dynamics': 'dynamic', "
              "'t-end': 1000}, 'vary': {'vx0': [1, 2]}, 'metrics': ['steps']}, out=OUT)"),
}

SCRIPT = """
import sys, time
import simbody_reeving as sr
OUT = sys.argv[1]
print('running', flush=True)
try:
    {run}
    print('finished', flush=True)
except KeyboardInterrupt:
    print('interrupted', flush=True)
case = sr.run_pendulum(axial_modes=1, t_end=0.2)
print('alive', case['summary']['steps'], flush=True)
"""


def interrupt(code, out, wait=1.0):
    p = subprocess.Popen([sys.executable, "-c", code, out], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True, env=support.environment())
    assert p.stdout.readline().strip() == "running"
    time.sleep(wait)
    assert p.poll() is None, "the run ended before the signal"
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    stdout, stderr = p.communicate(timeout=60)
    return p.returncode, stdout, stderr, time.monotonic() - sent


def test_keyboard_interrupt_ends_each_run_and_the_process_goes_on():
    import tempfile
    for name, run in LONG_RUNS.items():
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "study")
            # the study: past its --check of the two cases, into the first case
            status, stdout, stderr, took = interrupt(SCRIPT.format(run=run), out, 3.0 if name == "study" else 1.0)
            assert status == 0, (name, status, stdout, stderr)
            assert stdout.split("\n")[0] == "interrupted" and "alive" in stdout, (name, stdout, stderr)
            assert took < 10, (name, took)
            if name == "study":  # the runner's own end: the finished cases (none) in results.csv.partial
                assert os.path.exists(os.path.join(out, "results.csv.partial")), os.listdir(tmp)


def test_uncaught_keyboard_interrupt_ends_python_cleanly():
    code = "import simbody_reeving as sr, sys\nprint('running', flush=True)\n" + LONG_RUNS["run_pendulum"] + "\n"
    status, stdout, stderr, took = interrupt(code, "")
    # Python ends on an uncaught KeyboardInterrupt by SIGINT's default action after its traceback.
    assert status in (-signal.SIGINT, 130, 1), (status, stderr)
    assert "KeyboardInterrupt" in stderr and "Segmentation" not in stderr, stderr
    assert took < 10


if __name__ == "__main__":
    sys.exit(support.main(globals()))
