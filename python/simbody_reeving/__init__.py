"""SimbodyReeving from Python: the bundled scenes, their runs and parameter studies.

    import simbody_reeving as sr
    case = sr.run_pendulum(axial_modes=1, t_end=5)          # one case of reeving-pendulum
    case["timeseries"]["axial_force_payload"]               # numpy arrays
    case["summary"]["max_energy_drift_J"]                   # summary.json's keys, unrounded

    scene = sr.PendulumScene(sr.PendulumParameters(M=2000), sr.SpanOptions(axial_modes=2))
    sim = scene.simulation(scene.make_initial_state(vx=1.0), integrator="rk-merson", accuracy=1e-6)
    for n in range(1, 101):
        sim.step_to(0.01 * n)                               # without the GIL
        force = scene.axial_force_at_payload(sim.state)

    rows = sr.run_study("studies/elevator-traction")       # reeving-study's results.csv as dicts

    system = sr.System(gravity=(0, -9.81, 0))              # one's own machine
    drum = system.add_pin(system.ground, sr.MassProperties(50, (0, 0, 0), 2.0))
    load = system.add_free(system.ground, sr.MassProperties(100, (0, 0, 0), 1.0))
    rope = system.add_rope(sr.RopeSpec(start=sr.WinchDrum(drum, radius=0.3, rope_on_drum=20),
                                       end=sr.RopeAnchor(load, (0, 0.5, 0)), ...))
    rope.node(0).rope_on_drum(state)                        # typed handles: WinchDrumHandle, ...

Errors: a bad parameter raises ValueError with the C++ message (StudyError, a ValueError, for a
bad study), other C++ failures RuntimeError; Ctrl-C ends a run or a study with KeyboardInterrupt.
See docs/python.md.
"""

import os as _os

from ._core import (  # noqa: F401
    AxialDynamics,
    Body,
    CraneCycle,
    CraneParameters,
    CraneScenario,
    CraneScene,
    ElevatorParameters,
    ElevatorScenario,
    ElevatorScene,
    DeviationSheave,
    MassProperties,
    PendulumParameters,
    PendulumScene,
    PinnedNodeHandle,
    ReevingSubsystem,
    RopeAnchor,
    RopeHandle,
    RopeNodeHandle,
    RopeProperties,
    RopeSpec,
    SheaveModel,
    Simulation,
    SpanOptions,
    State,
    StudyError,
    System,
    TractionMode,
    TractionSheave,
    TractionSheaveHandle,
    TractionSlip,
    Transform,
    TransverseDynamics,
    TurningSheave,
    TurningSheaveHandle,
    VelocityModel,
    WinchDrum,
    WinchDrumHandle,
    integrator_names,
    run_pendulum,
)
from . import _core

__all__ = [
    "AxialDynamics", "Body", "CraneCycle", "CraneParameters", "CraneScenario", "CraneScene",
    "DeviationSheave", "ElevatorParameters", "ElevatorScenario", "ElevatorScene", "MassProperties",
    "PendulumParameters", "PendulumScene", "PinnedNodeHandle", "ReevingSubsystem", "RopeAnchor",
    "RopeHandle", "RopeNodeHandle", "RopeProperties", "RopeSpec", "SheaveModel", "Simulation",
    "SpanOptions", "State", "StudyError", "System", "TractionMode", "TractionSheave",
    "TractionSheaveHandle", "TractionSlip", "Transform", "TransverseDynamics", "TurningSheave",
    "TurningSheaveHandle", "VelocityModel", "WinchDrum", "WinchDrumHandle", "demo_dir",
    "integrator_names", "results_array", "run_pendulum", "run_study",
]


def demo_dir():
    """The folder of the demo programs a study runs (reeving-pendulum, -crane, -elevator).

    $SIMBODY_REEVING_DEMO_DIR if set; else build/examples when this package is the build tree's
    (build/python/simbody_reeving); else the bin/ folder of the prefix it is installed under.
    """
    env = _os.environ.get("SIMBODY_REEVING_DEMO_DIR")
    if env:
        return env
    here = _os.path.dirname(_os.path.abspath(__file__))
    build = _os.path.normpath(_os.path.join(here, _os.pardir, _os.pardir, "examples"))
    if _os.path.isfile(_os.path.join(build, "reeving-pendulum")):
        return build
    return _os.path.normpath(_os.path.join(here, _core._installed_demo_dir))


def run_study(study, out=None, demo_dir=None, quiet=True, resume=False, as_array=False):
    """Runs a parameter study as reeving-study does (docs/studies.md), returns its results.csv.

    study: a study file (YAML), a folder holding study.yaml, or a dict with the study file's keys
        ({"scene": "elevator", "vary": {"friction": [0.1, 0.2]}, "metrics": [...]}).
    out: the output folder (results.csv, summary.json, figures/); None: a temporary one, removed.
    demo_dir: where the demo programs are (default: demo_dir()).
    quiet: no progress line and no summary printed.
    resume: continue the study in `out` (reeving-study --resume).
    as_array: a numpy structured array instead of a list of dicts.

    Returns one dict per case, in case order: "case", the varied and sampled parameters, the
    metrics, "wall_seconds", "status" ("ok", "failed", "timeout") and "message"; numbers as int or
    float (the double of the CSV's cell: bit for bit), an empty cell as None.
    Raises StudyError (a ValueError) for a bad study, with the runner's "FILE:LINE:COLUMN: message"
    (FILE "<study dict>" for a dict, its lines those of json.dumps(study, indent=2)); KeyboardInterrupt
    on Ctrl-C (the finished cases stay in out/results.csv.partial: resume=True continues).
    """
    if out is not None:
        out = _os.fspath(out)
    rows = _core._run_study(study, out, demo_dir or globals()["demo_dir"](), quiet, resume)
    return results_array(rows) if as_array else rows


def results_array(rows):
    """A study's rows (run_study's list of dicts) as a numpy structured array: a column of ints is
    int64, of numbers (None as NaN) float64, else a unicode string column."""
    import numpy as np

    if not rows:
        return np.zeros(0)
    names = list(rows[0].keys())
    fields = []
    for name in names:
        values = [r[name] for r in rows]
        present = [v for v in values if v is not None]
        if present and all(isinstance(v, int) and not isinstance(v, bool) for v in present) \
                and len(present) == len(values):
            fields.append((name, np.int64))
        elif present and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in present):
            fields.append((name, np.float64))
        else:
            width = max([len(str(v)) for v in present] + [1])
            fields.append((name, "U%d" % width))
    array = np.zeros(len(rows), dtype=fields)
    for name, kind in fields:
        if kind is np.float64:
            array[name] = [np.nan if r[name] is None else float(r[name]) for r in rows]
        elif kind is np.int64:
            array[name] = [r[name] for r in rows]
        else:
            array[name] = ["" if r[name] is None else str(r[name]) for r in rows]
    return array
