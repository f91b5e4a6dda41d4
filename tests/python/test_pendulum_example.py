"""examples/python/pendulum.py against reeving-pendulum with the same options: the paper's four
cases n_a = 0..3 (20 s each, the demo's defaults). The Python cases run the demo's own loop, so
the integrator takes the same steps and every number the demo writes (12 significant digits, in
summary.json and timeseries.csv) is the Python number written the same way (%.12g)."""

import csv
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(__file__))
import support  # noqa: E402


def digits(x):
    """A number as the demo writes it: jsonNumber and setprecision(12), i.e. %.12g."""
    return "%.12g" % x


def test_pendulum_example_equals_the_demo():
    with tempfile.TemporaryDirectory() as tmp:
        demo = os.path.join(tmp, "demo")
        support.run([os.path.join(support.EXAMPLES, "reeving-pendulum"), "--out", demo, "--no-plots", "--quiet"])
        printed = support.python(os.path.join(support.PY_EXAMPLES, "pendulum.py"), "--no-plots", "--json",
                                 os.path.join(tmp, "py.json")).stdout
        cases = json.load(open(os.path.join(tmp, "py.json")))
        assert sorted(cases) == ["0", "1", "2", "3"]
        worst = 0.0
        for na, case in cases.items():
            summary = json.load(open(os.path.join(demo, "modes-%s" % na, "summary.json")))
            py = case["summary"]
            # The same run: the same steps and right-hand sides...
            for key in ["steps", "rhs_evaluations", "axial_modes", "transverse_modes", "termination", "integrator"]:
                assert py[key] == summary[key], (na, key, py[key], summary[key])
            # ...and every number of summary.json to its 12 digits (the energy drift among them).
            for key in ["max_energy_drift_J", "initial_kinetic_energy_J", "max_constraint_error_N", "t_reached"]:
                assert float(digits(py[key])) == summary[key], (na, key, repr(py[key]), summary[key])
                worst = max(worst, abs(py[key] - summary[key]) / abs(summary[key]) if summary[key] else 0.0)
            # The time series (payload-end force included), every row and column, as written.
            with open(os.path.join(demo, "modes-%s" % na, "timeseries.csv")) as f:
                rows = list(csv.reader(f))
            assert len(rows) - 1 == len(case["timeseries"]["t"]) == 2001
            for i, row in enumerate(rows[1:]):
                for column, cell in zip(rows[0], row):
                    assert digits(case["timeseries"][column][i]) == cell, (na, i, column, cell)
            with open(os.path.join(demo, "modes-%s" % na, "static_axial_force.csv")) as f:
                rows = list(csv.reader(f))
            for i, row in enumerate(rows[1:]):
                assert int(row[0]) == case["static_axial_force"]["span"][i]
                assert digits(case["static_axial_force"]["s"][i]) == row[1]
                assert digits(case["static_axial_force"]["axial_force"][i]) == row[2]
            # The printed line of the case: its drift and payload-end forces.
            force = case["timeseries"]["axial_force_payload"]
            line = "%3s %6d  %-20.12g  %26.12g %13.12g %13.12g" % (na, py["steps"], py["max_energy_drift_J"], force[0],
                                                                 min(force), max(force))
            assert line in printed, (line, printed)
        # The demo's own line: max energy drift %.3e over the cases.
        drift = max(c["summary"]["max_energy_drift_J"] for c in cases.values())
        assert "max energy drift over the cases: %.3e J" % drift in printed
        # The Python numbers differ from the 12-digit ones by the rounding alone.
        print("largest relative difference to summary.json's 12 digits: %.2e" % worst)
        assert worst <= 5e-12


if __name__ == "__main__":
    sys.exit(support.main(globals()))
