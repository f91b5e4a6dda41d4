"""examples/python/elevator_traction_map.py against reeving-study: the small traction study
(--small, 8 cases) from Python and the runner's results.csv of the same study file are equal bit
for bit (every column but the cases' wall-clock times), and the rows run_study returns hold the
CSV's doubles exactly."""

import csv
import os
import struct
import sys
import tempfile

sys.path.insert(0, os.path.dirname(__file__))
import support  # noqa: E402


def without_wall(rows):
    wall = rows[0].index("wall_seconds")
    return [r[:wall] + r[wall + 1:] for r in rows]


def test_traction_study_equals_the_runner():
    import simbody_reeving as sr

    with tempfile.TemporaryDirectory() as tmp:
        study = os.path.join(tmp, "traction.json")
        printed = support.python(os.path.join(support.PY_EXAMPLES, "elevator_traction_map.py"), "--small", "--no-plots",
                                 "--out", os.path.join(tmp, "py"), "--write-study", study).stdout
        assert "8 cases:" in printed and "0 failed" in printed, printed
        support.run([os.path.join(support.EXAMPLES, "reeving-study"), study, "--out", os.path.join(tmp, "cpp"), "--quiet"])
        with open(os.path.join(tmp, "py", "results.csv")) as f:
            py = list(csv.reader(f))
        with open(os.path.join(tmp, "cpp", "results.csv")) as f:
            cpp = list(csv.reader(f))
        assert len(cpp) == 9 and py[0] == cpp[0]
        assert without_wall(py) == without_wall(cpp)
        # The dicts: resume=True reads the finished study back (no case runs again).
        rows = sr.run_study(study, out=os.path.join(tmp, "py"), resume=True)
        assert len(rows) == 8
        for row, cells in zip(rows, cpp[1:]):
            for column, cell in zip(cpp[0], cells):
                if column == "wall_seconds":
                    continue
                value = row[column]
                if isinstance(value, float):
                    assert struct.pack("<d", value) == struct.pack("<d", float(cell)), (column, value, cell)
                else:
                    assert str(value) == cell, (column, value, cell)
        table = sr.results_array(rows)
        assert table.dtype["traction_table.0.traction_margin"].kind == "f"
        assert list(table["traction_table.0.traction_margin"]) == [float(r[cpp[0].index("traction_table.0.traction_margin")])
                                                                    for r in cpp[1:]]


if __name__ == "__main__":
    sys.exit(support.main(globals()))
