"""The module's surface: a Python loop over Simulation.step_to gives run_pendulum's numbers bit for
bit; the elevator's reports equal the reeving-elevator demo's time series; the crane runs with its
energy balance; the GIL is free during a run (another Python thread keeps running); the rope
queries; the parameter structs."""

import csv
import os
import pickle
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.dirname(__file__))
import support  # noqa: E402

import numpy as np  # noqa: E402

import simbody_reeving as sr  # noqa: E402


def test_python_loop_equals_run_pendulum():
    case = sr.run_pendulum(axial_modes=2, t_end=2.0)
    scene = sr.PendulumScene(spans=sr.SpanOptions(axial_modes=2))
    sim = scene.simulation(scene.make_initial_state(vx=1.0), integrator="rk-merson", accuracy=1e-6)
    rows = [sim.observe_row()]
    for n in range(1, 201):
        sim.step_to(n * 0.01)
        rows.append(sim.observe_row())
    for c, column in enumerate(sim.columns):
        assert np.array_equal(np.array([r[c] for r in rows]), case["timeseries"][column]), column
    assert sim.steps == case["summary"]["steps"] and sim.rhs_evaluations == case["summary"]["rhs_evaluations"]
    # The scene's queries on the report state are the observer's numbers.
    state = sim.state
    assert state.time == 2.0
    assert scene.axial_force_at_payload(state) == rows[-1][4]
    s1, s2 = scene.reeving.span_material_range(state, 0, 1)
    assert scene.reeving.axial_force(state, 0, 1, s2) == rows[-1][4]
    assert scene.reeving.mechanical_energy(state) == rows[-1][7]
    s, p = scene.reeving.axial_force_along(state, 0, 1, 11)
    assert s[0] == s1 and s[-1] == s2 and np.array_equal(p, scene.reeving.axial_force(state, 0, 1, s))
    assert scene.reeving.sample_span(state, 0, 1, 5).shape == (5, 3)
    assert scene.reeving.num_ropes == 1 and scene.reeving.num_spans(0) == 2 and scene.reeving.is_planar(0)


def test_elevator_reports_equal_the_demo():
    params = sr.ElevatorParameters(scenario=sr.ElevatorScenario.EmergencyStop, friction=0.1)
    scene = sr.ElevatorScene(params, sr.SpanOptions(axial_modes=1, transverse_modes=1))
    sim = scene.simulation(scene.make_initial_state())
    reports = sim.run(t_end=1.0)
    with tempfile.TemporaryDirectory() as tmp:
        support.run([os.path.join(support.EXAMPLES, "reeving-elevator"), "--scenario", "emergency-stop", "--friction",
                     "0.1", "--t-end", "1", "--out", tmp, "--no-plots", "--quiet"])
        with open(os.path.join(tmp, "timeseries_emergency-stop.csv")) as f:
            rows = list(csv.reader(f))
    pairs = {"t_s": "t", "car_y_m": "car_y", "car_v_mps": "car_v", "car_a_mps2": "car_a",
             "counterweight_y_m": "counterweight_y", "rope_travel_m": "rope_travel",
             "car_side_force_N": "car_side_force", "counterweight_side_force_N": "counterweight_side_force",
             "force_ratio": "force_ratio", "friction_work_J": "friction_work", "machine_work_J": "machine_work",
             "energy_residual_J": "energy_residual", "wrap_angle_rad": "wrap_angle"}
    assert len(rows) - 1 == len(reports["t"]) == 101
    for i, row in enumerate(rows[1:]):
        for demo_column, column in pairs.items():
            cell = row[rows[0].index(demo_column)]
            assert "%.10g" % reports[column][i] == cell, (i, column, cell)  # the demo's precision(10)
    assert sim.steps > 0 and sim.limit_reached == ""


def test_crane_runs_with_its_energy_balance():
    scene = sr.CraneScene(sr.CraneParameters(falls=2), spans=sr.SpanOptions(axial_modes=0))
    sim = scene.simulation(scene.make_initial_state(), accuracy=1e-6)
    reports = sim.run(t_end=2.0, report_interval=0.05)
    assert len(reports["t"]) == 41 and "fall_top_force_1" in reports and "wrap_angle_1" in reports
    assert np.all(reports["fall_top_force_0"] > 0)
    lifted = scene.parameters.payload_mass + scene.parameters.hook_mass
    assert abs(reports["fall_top_force_0"][0] * 2 / (lifted * 9.81) - 1) < 0.05
    assert np.max(np.abs(reports["energy_residual"])) < 1.0  # [J], against the lift's kJ


def test_the_gil_is_free_during_a_run():
    done = threading.Event()
    result = {}

    def run():
        result["case"] = sr.run_pendulum(axial_modes=3, axial_dynamics="dynamic", t_end=0.3)
        done.set()

    thread = threading.Thread(target=run)
    start = time.monotonic()
    thread.start()
    ticks = 0
    while not done.is_set():  # pure Python: runs only while the other thread does not hold the GIL
        ticks += 1
    thread.join()
    took = time.monotonic() - start
    assert result["case"]["summary"]["termination"] == "completed"
    assert took > 0.05 and ticks > 10000, (took, ticks)


def test_parameters():
    p = sr.PendulumParameters(M=2000, EA=1e7)
    assert p.M == 2000 and p.EA == 1e7 and p.a == 3.0
    assert "M=2000.0" in repr(p) and p.to_dict()["EA"] == 1e7
    q = pickle.loads(pickle.dumps(p))
    assert q.to_dict() == p.to_dict()
    e = sr.ElevatorParameters(car_load=0.5)
    assert e.car_load == 0.5 and e.car_position is None and e.counterweight() == 1315.0
    assert sr.integrator_names()[0] == "rk-merson"


if __name__ == "__main__":
    sys.exit(support.main(globals()))
