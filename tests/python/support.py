"""What the Python tests share: the build and source folders (from ctest's environment), running
the demos and the examples, and a plain runner for a test file when pytest is absent."""

import os
import subprocess
import sys
import traceback

BUILD = os.environ.get("SIMBODY_REEVING_BUILD", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
SOURCE = os.environ.get("SIMBODY_REEVING_SOURCE", os.path.join(os.path.dirname(__file__), "..", ".."))
EXAMPLES = os.path.join(BUILD, "examples")
PY_EXAMPLES = os.path.join(SOURCE, "examples", "python")


def environment():
    """os.environ with the build tree's package first on PYTHONPATH."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.path.join(BUILD, "python") + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    return env


def run(args, **kwargs):
    """Runs a command; fails the test with its output if it exits non-zero."""
    p = subprocess.run(args, capture_output=True, text=True, env=environment(), **kwargs)
    assert p.returncode == 0, "%s: exit status %d\nstdout:\n%s\nstderr:\n%s" % (" ".join(args), p.returncode,
                                                                            p.stdout, p.stderr)
    return p


def python(script, *args, **kwargs):
    """Runs a Python script with this interpreter and the build tree's package."""
    return run([sys.executable, script] + list(args), **kwargs)


def main(namespace):
    """Runs every test_* function of a module (without pytest): 0 if all pass."""
    failed = 0
    tests = [(name, f) for name, f in namespace.items() if name.startswith("test_") and callable(f)]
    for name, f in tests:
        try:
            f()
            print("PASS %s" % name)
        except Exception:  # noqa: BLE001 - report every failure
            failed += 1
            print("FAIL %s\n%s" % (name, traceback.format_exc()))
    print("%d of %d passed" % (len(tests) - failed, len(tests)))
    return 1 if failed else 0
