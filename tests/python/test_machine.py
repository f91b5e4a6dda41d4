"""One's own machine from Python (sr.System, docs/python.md): (a) the paper's pendulum built body by
body and rope node by rope node equals the bundled PendulumScene's run; (b) a winch drum and a
traction sheave: the typed handles' queries against closed forms, a wrong-kind query absent; (c)
bad specs raise ValueError with the C++ message; the handles keep their System alive."""

import gc
import math
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import support  # noqa: E402

import numpy as np  # noqa: E402

import simbody_reeving as sr  # noqa: E402


def raises(kind, f, *args, **kwargs):
    """The exception f raises, which must be a `kind` (pytest.raises without pytest)."""
    try:
        f(*args, **kwargs)
    except kind as e:
        return e
    raise AssertionError("%s did not raise %s" % (getattr(f, "__name__", f), kind.__name__))


# ---- (a) the pendulum --------------------------------------------------------------------------

def build_pendulum(p, spans, vx):
    """PendulumScene's machine (plugin/scenes/src/PendulumScene.cpp) and makeInitialState(vx, 0)."""
    system = sr.System(gravity=(0, -p.g, 0))
    payload = system.add_free(system.ground, sr.MassProperties(p.M, (0, 0, 0), p.J))
    spec = sr.RopeSpec(
        name="pendulum rope",
        start=sr.RopeAnchor(system.ground, (0, 0, 0)),
        sheaves=[sr.DeviationSheave(system.ground, centre=(p.a, 0, 0), radius=p.r, wrap_sense=-1)],
        end=sr.RopeAnchor(payload, (0, p.d, 0)),
        properties=sr.RopeProperties(p.rhoA, p.EA, p.EI, p.tension_only),
        unstretched_length=p.a + p.L,
        span_defaults=spans,
        plane_normal=(0, 0, 1),
        sheave_model=p.sheave_model)
    rope = system.add_rope(spec)
    state = system.default_state()
    P = (p.M + p.rhoA * p.L) * p.g
    stretch = math.sqrt(1.0 + 2.0 * P / p.EA)
    x = p.a + p.r if p.sheave_model == sr.SheaveModel.Wrapped else p.a
    payload.set_q_to_fit_translation(state, (x, -p.L * stretch - p.d, 0))
    system.find_static_equilibrium(state, 1e-9)
    payload.set_u_to_fit_linear_velocity(state, (vx, 0, 0))
    return system, payload, rope, state


def test_pendulum_built_in_python_equals_the_scene():
    # Same bodies, rope, subsystem order, initial state, integrator and report times as the scene:
    # the runs are the same computation. Measured: every difference 0 (bit for bit) for rk-merson
    # with the point sheave and rk3 with the wrapped one, steps and rhs evaluations equal. The
    # bound, 1e-12 of each column's scale, admits round-off should an operation's order ever differ
    # (the Python-side initial guess is the same IEEE arithmetic as the C++ one).
    bound = 1e-12
    for integrator, model in (("rk-merson", sr.SheaveModel.Point), ("rk3", sr.SheaveModel.Wrapped)):
        p = sr.PendulumParameters(sheave_model=model)
        spans = sr.SpanOptions(axial_modes=2)
        scene = sr.PendulumScene(p, spans)
        ref_sim = scene.simulation(scene.make_initial_state(vx=1.0), integrator=integrator, accuracy=1e-6)
        ref = ref_sim.run(t_end=2.0, report_interval=0.01)

        system, payload, rope, state = build_pendulum(p, spans, 1.0)
        assert np.array_equal(state.q, scene.make_initial_state(vx=1.0).q)
        sim = system.simulation(state, integrator=integrator, accuracy=1e-6)
        mine = sim.run(t_end=2.0, report_interval=0.01)

        pairs = {"t": "t", "x": "q4", "y": "q5", "energy": "energy",
                 "axial_force_payload": "rope0.span1.axial_force_end",
                 "axial_force_sheave": "rope0.span1.axial_force_start",
                 "s_sheave": "rope0.node1.material_coordinate"}
        if model == sr.SheaveModel.Wrapped:
            pairs["wrap_angle"] = "rope0.node1.wrap_angle"
        assert len(mine["t"]) == len(ref["t"]) == 201
        worst = 0.0
        for a, b in pairs.items():
            scale = max(np.max(np.abs(ref[a])), 1.0)
            d = np.max(np.abs(mine[b] - ref[a])) / scale
            worst = max(worst, d)
            assert d <= bound, (integrator, a, d)
        qd = np.max(np.abs(sim.state.q - ref_sim.state.q))
        ud = np.max(np.abs(sim.state.u - ref_sim.state.u))
        print("pendulum %s %s: largest relative column difference %.3g, |q - q_scene| %.3g, |u - u_scene| %.3g, "
              "steps %d / %d" % (integrator, model.name, worst, qd, ud, sim.steps, ref_sim.steps))
        assert qd <= bound and ud <= bound
        assert sim.steps == ref_sim.steps and sim.rhs_evaluations == ref_sim.rhs_evaluations
        # The body and rope queries on the report state are the scene's.
        st = sim.state
        assert np.max(np.abs(payload.position(st) - scene.payload_position(ref_sim.state))) <= bound
        s, P = rope.axial_force_along(st, 1, 11)
        s_ref, P_ref = scene.reeving.axial_force_along(ref_sim.state, 0, 1, 11)
        assert np.max(np.abs(P - P_ref)) <= bound * np.max(np.abs(P_ref))
        assert abs(system.reeving.mechanical_energy(st) - mine["energy"][-1]) == 0


# ---- (b) a winch drum and a traction sheave ---------------------------------------------------

R_DRUM, STORED, R_SHEAVE, MU = 0.3, 20.0, 0.25, 0.2
A, L, M, RHOA, EA, G = 4.0, 9.0, 100.0, 1.5, 1e7, 9.81


def build_hoist(drum_speed, theta0):
    """A drum (Pin at the origin) pays rope out horizontally to a traction sheave (Pin at (A, 0)),
    down which it hangs to a payload on a vertical slider. The drum's speed is prescribed
    (Motion::Steady), the sheave turns freely. Straight spans (no modes): the horizontal span's
    weight goes to its end nodes, its pull is the vertical span's. At the sheave's pin angle 0 the rope's material coordinate
    there is A - R theta0 (the horizontal chord's length from the drum's s_0 = -R theta0)."""
    system = sr.System(gravity=(0, -G, 0))
    drum = system.add_pin(system.ground, sr.MassProperties(50.0, (0, 0, 0), 2.0))
    drum.prescribe_steady_speed(drum_speed)
    sheave = system.add_pin(system.ground, sr.MassProperties(20.0, (0, 0, 0), 0.7), in_parent=(A, 0, 0))
    # A slider moves along x of its frames: turned so that x points down, below the sheave.
    down = sr.Transform.about_axis(-math.pi / 2, "z", p=(A, 0, 0))
    payload = system.add_slider(system.ground, sr.MassProperties(M, (0, 0, 0), 1.0), in_parent=down)
    rope = system.add_rope(sr.RopeSpec(
        name="hoist rope",
        start=sr.WinchDrum(drum, radius=R_DRUM, rope_on_drum=STORED, payout_sense=1),
        sheaves=[sr.TractionSheave(sheave, radius=R_SHEAVE, friction_coefficient=MU,
                                   material_coordinate_at_zero_angle=A - R_DRUM * theta0)],
        end=sr.RopeAnchor(payload),
        properties=sr.RopeProperties(mass_per_length=RHOA, axial_stiffness=EA),
        unstretched_length=L,
        span_defaults=sr.SpanOptions(axial_modes=0, transverse_modes=0),  # straight spans
        plane_normal=(0, 0, 1)))
    state = system.default_state()
    drum.set_q(state, theta0)
    payload.set_q(state, L + R_DRUM * theta0 - A)  # the vertical span's length, unstretched
    system.find_static_equilibrium(state, 1e-10)
    return system, drum, sheave, payload, rope, state


def test_winch_drum_and_traction_sheave_against_closed_forms():
    theta = 2.0
    system, drum, sheave, payload, rope, state = build_hoist(0.0, theta)
    d, t, end = rope.nodes
    assert isinstance(d, sr.WinchDrumHandle) and isinstance(t, sr.TractionSheaveHandle)
    assert type(end) is sr.RopeNodeHandle and end.kind == "RopeAnchor"
    assert isinstance(d, sr.PinnedNodeHandle) and isinstance(t, sr.PinnedNodeHandle)

    # The drum held at theta: the stored rope is rope_on_drum - sense R theta, s_0 = -sense R theta.
    # Measured: both differences 0 (the bound, 1e-14 of the stored rope, is round-off's).
    assert drum.q(state)[0] == theta
    stored_err = abs(d.rope_on_drum(state) - (STORED - R_DRUM * theta))
    s0_err = abs(d.material_coordinate(state) - (-R_DRUM * theta))
    print("drum: rope_on_drum error %.3g m, s_0 error %.3g m" % (stored_err, s0_err))
    assert stored_err <= 1e-14 * STORED and s0_err <= 1e-14 * STORED

    # At rest the free sheave carries no torque; the payload's rope force is its weight; the limit
    # is e^(mu alpha) with alpha the chords' turn at the point sheave, pi/2; in stick, no slip.
    W = M * G
    F = rope.node_forces(state)
    assert np.array_equal(F[2], end.node_force(state)) and np.array_equal(F[0], d.node_force(state))
    torque = abs(t.torque(state))
    weight_err = np.max(np.abs(F[2] - np.array([0.0, W, 0.0]))) / W
    alpha = t.wrap_angle(state)
    alpha_err = abs(alpha - math.pi / 2)
    limit_err = abs(t.traction_limit(state) - math.exp(MU * math.pi / 2))
    P = rope.span_end_forces(state)
    ratio_err = abs(t.traction_ratio(state) - P[0, 1] / P[1, 0])
    print("traction sheave: |torque| %.3g N m, |F_payload - M g| / M g %.3g, |alpha - pi/2| %.3g rad, "
          "|limit - e^(mu pi/2)| %.3g, |ratio - P_a / P_b| %.3g (ratio %.6f)"
          % (torque, weight_err, alpha_err, limit_err, ratio_err, t.traction_ratio(state)))
    # Measured (find_static_equilibrium to 1e-10): |torque| 4.4e-9 N m (of R P = 266 N m), weight
    # 3.4e-12, alpha, limit and ratio 0 (the chords are exactly horizontal and vertical). Bounds: 1e-7
    # N m and 1e-10 (23x and 29x), round-off for the last three.
    assert torque <= 1e-7 and weight_err <= 1e-10
    assert alpha_err <= 1e-14 and limit_err <= 1e-14 and ratio_err <= 1e-14
    assert t.traction_mode(state) == sr.TractionMode.Stick and t.traction_ratio(state) < t.traction_limit(state)
    assert t.slip_rate(state) == 0.0 and t.slip_distance(state) == 0.0 and t.friction_work(state) == 0.0
    assert rope.wrap_angles(state)[0] == alpha and system.reeving.wrap_angle(state, rope, 1) == alpha

    # The rope's forces on its nodes balance its weight: the rope in the spans, L + sense R theta,
    # and the ring stored on the drum, rope_on_drum - sense R theta (RopeModel::setStoredRope).
    rope_weight = RHOA * (L + STORED) * G
    balance_err = np.max(np.abs(F.sum(axis=0) - np.array([0.0, -rope_weight, 0.0]))) / rope_weight
    # The drum's pull: the horizontal span's is the vertical span's force at the top, M g + rhoA g l
    # (l its unstretched length); its torque sense R times that, to O(eps) (the rope's generalized
    # force on the drum's material coordinate carries the strain energy leaving the span).
    s1, s2 = system.reeving.span_material_range(state, rope, 1)
    pull = W + RHOA * G * (s2 - s1)
    pull_err = abs(F[0, 0] - pull) / pull
    drum_torque_err = abs(d.torque(state) - R_DRUM * pull) / (R_DRUM * pull)
    print("rope: |sum F_k - rope weight| / weight %.3g, |F_drum,x - (M g + rhoA g l)| / pull %.3g, "
          "|torque - R pull| / (R pull) %.3g (eps = P / EA %.3g)" % (balance_err, pull_err, drum_torque_err, pull / EA))
    # Measured: 1.5e-11, 8.0e-8 and 5.3e-5 (eps 1.06e-4); bounds 1e-9, 1e-6 and 1e-3 (67x, 12x, 19x).
    assert balance_err <= 1e-9 and pull_err <= 1e-6
    assert drum_torque_err <= 1e-3

    # Wrong kinds: the queries of another kind do not exist on a handle; asking the rope for a node
    # as another kind is the C++ handle's ValueError.
    raises(AttributeError, lambda: d.slip_rate(state))
    raises(AttributeError, lambda: d.traction_limit(state))
    raises(AttributeError, lambda: t.rope_on_drum(state))
    raises(AttributeError, lambda: end.torque(state))
    e = raises(ValueError, rope.traction_sheave, 0)
    assert "TractionSheave" in str(e), str(e)
    e = raises(ValueError, rope.winch_drum, 1)
    assert "WinchDrum" in str(e), str(e)
    assert isinstance(rope.winch_drum(0), sr.WinchDrumHandle) and isinstance(rope.traction_sheave(1), sr.TractionSheaveHandle)


def test_hauling_drum_time_series():
    # The drum hauls in at a prescribed speed: its angle is theta0 + omega t, so the reports' stored
    # rope is rope_on_drum - R (theta0 + omega t) at every report; the payload rises by about R omega t.
    # Slowly (R omega = 15 mm/s): the start's jerk rings the payload on the rope (134 rad/s) with
    # m v omega_n = 200 N, below its weight, so the rope stays taut and the sheave in stick.
    omega, theta0 = -0.05, 1.0
    system, drum, sheave, payload, rope, state = build_hoist(omega, theta0)
    sim = system.simulation(state, integrator="rk-merson", accuracy=1e-7)
    r = sim.run(t_end=1.0, report_interval=0.05)
    assert sim.limit_reached == "" and len(r["t"]) == 21
    expected = STORED - R_DRUM * (theta0 + omega * r["t"])
    err = np.max(np.abs(r["rope0.node0.rope_on_drum"] - expected))
    rise = payload.q(sim.state)[0] - payload.q(state)[0]
    print("hauling: |rope_on_drum - (stored - R (theta0 + omega t))| %.3g m, payload moved %.6f m (R omega t %.6f)"
          % (err, rise, R_DRUM * omega))
    # Measured: 0 m (q of a constant u, integrated to round-off; bound 1e-12 m), and the payload 2.8e-5 m
    # off R omega t (the ringing, amplitude R omega / omega_n = 1.1e-4 m, and the stretch; bound 3e-4 m, 11x).
    assert err <= 1e-12
    assert abs(rise - R_DRUM * omega) <= 3e-4
    for column in ("rope0.span0.axial_force_end", "rope0.node1.traction_ratio", "rope0.node1.slip_rate", "energy"):
        assert isinstance(r[column], np.ndarray) and r[column].shape == (21,), column
    print("hauling: span 1 force at the sheave min %.6g max %.6g N, ratio max %.6g, slip rate max %.3g"
          % (r["rope0.span1.axial_force_start"].min(), r["rope0.span1.axial_force_start"].max(),
             r["rope0.node1.traction_ratio"].max(), np.abs(r["rope0.node1.slip_rate"]).max()))
    assert np.all(r["rope0.span1.axial_force_start"] > 0)


# ---- (c) bad input ----------------------------------------------------------------------------

def hoist_spec(system, **changes):
    drum = system.add_pin(system.ground, sr.MassProperties(50.0, (0, 0, 0), 2.0))
    sheave = system.add_pin(system.ground, sr.MassProperties(20.0, (0, 0, 0), 0.7), in_parent=(A, 0, 0))
    payload = system.add_slider(system.ground, sr.MassProperties(M), in_parent=sr.Transform.about_axis(-math.pi / 2, "z", p=(A, 0, 0)))
    spec = sr.RopeSpec(name="bad", start=sr.WinchDrum(drum, radius=R_DRUM, rope_on_drum=STORED),
                       sheaves=[sr.TractionSheave(sheave, radius=R_SHEAVE, friction_coefficient=MU,
                                                  material_coordinate_at_zero_angle=A)],
                       end=sr.RopeAnchor(payload), properties=sr.RopeProperties(RHOA, EA), unstretched_length=L,
                       plane_normal=(0, 0, 1))
    for k, v in changes.items():
        if k == "drum_on_payload":
            spec.start = sr.WinchDrum(payload, radius=R_DRUM, rope_on_drum=STORED)
        elif k == "sheave":
            spec.sheaves = [sr.TractionSheave(sheave, **v)]
        elif k == "end_body":
            spec.end = sr.RopeAnchor(v)
        else:
            setattr(spec, k, v)
    return spec


def test_bad_specs_raise_value_error_with_the_cpp_message():
    other = sr.System()
    stranger = other.add_pin(other.ground, sr.MassProperties(1.0, (0, 0, 0), 1.0))
    cases = [
        (dict(unstretched_length=-1.0), "ReevingSubsystem: rope 'bad': unstretchedLength [m] = -1 must be finite and > 0"),
        (dict(drum_on_payload=True),
         "ReevingSubsystem: rope 'bad': start node (WinchDrum, node 0): its body must be a MobilizedBody::Pin (the rope turns it about the pin axis)"),
        (dict(sheave=dict(radius=0.0, friction_coefficient=MU)),
         "ReevingSubsystem: rope 'bad': sheave 0 (TractionSheave, node 1) radius [m] = 0 must be finite and > 0"),
        (dict(sheave=dict(radius=R_SHEAVE, sense=2)), "ReevingSubsystem: rope 'bad': sheave 0 (TractionSheave, node 1) sense = 2 must be +1 or -1"),
        (dict(end_body=None), "ReevingSubsystem: rope 'bad': end node (Anchor, node 2) has no body"),
        (dict(end_body=stranger), "ReevingSubsystem: rope 'bad': end node (Anchor, node 2) is on a body of another system's matter subsystem"),
        (dict(properties=sr.RopeProperties(RHOA, -5.0)), None),
    ]
    for changes, message in cases:
        system = sr.System()
        e = raises(ValueError, system.add_rope, hoist_spec(system, **changes))
        print("ValueError: %s" % e)
        if message is not None:
            assert str(e) == message, (str(e), message)
        else:
            assert str(e).startswith("ReevingSubsystem: rope 'bad': ") and "-5" in str(e), str(e)
        assert system.num_ropes == 0
    # A node of the wrong place is a TypeError at assignment (in C++ it does not compile).
    system = sr.System()
    spec = hoist_spec(system)
    raises(TypeError, setattr, spec, "start", sr.DeviationSheave(system.ground, radius=1.0))
    raises(TypeError, setattr, spec, "sheaves", [sr.RopeAnchor(system.ground)])
    # Bindings' own checks: a bad rotation, building after the topology, a state of another System.
    raises(ValueError, sr.Transform, [[1, 0, 0], [0, 2, 0], [0, 0, 1]])
    raises(ValueError, sr.MassProperties, -1.0)
    raises(ValueError, sr.MassProperties, 1.0, (0, 0, 0), (1.0, 1.0, 5.0))  # not a triangle
    good = system.add_rope(spec)
    state = system.default_state()
    raises(ValueError, system.add_pin, system.ground, sr.MassProperties(1.0))
    raises(ValueError, system.add_rope, hoist_spec(sr.System()))
    raises(ValueError, good.node(0).rope_on_drum, other.default_state())
    raises(IndexError, good.node, 3)
    # A state of another system anywhere is a ValueError (Simbody itself would abort), before the
    # topology too.
    scene = sr.PendulumScene()
    scene_state = scene.make_initial_state()
    raises(ValueError, system.reeving.axial_force, scene_state, 0, 0, 1.0)
    raises(ValueError, scene.reeving.axial_force, state, 0, 0, 1.0)
    raises(ValueError, scene.payload_position, state)
    raises(ValueError, scene.simulation, state)
    raises(ValueError, system.simulation, scene_state)
    raises(ValueError, sr.System().reeving.mechanical_energy, scene_state)
    # An evaluation failure is a RuntimeError: the default state has the payload at the sheave.
    e = raises(RuntimeError, good.node(0).rope_on_drum, state)
    assert "ChordFrame: chord e = r2 - r1 = (0 0) is zero" in str(e), str(e)
    system.body(3).set_q(state, L - A)
    assert good.node(0).rope_on_drum(state) == STORED  # the interpreter and the System go on


def test_handles_keep_their_system_alive():
    def make():
        system, drum, sheave, payload, rope, state = build_hoist(0.0, 0.5)
        return rope.node(0), payload, state
    handle, payload, state = make()
    gc.collect()
    assert handle.rope_on_drum(state) == STORED - R_DRUM * 0.5
    assert abs(payload.position(state)[0] - A) <= 1e-15 * A
    del handle
    gc.collect()
    assert payload.kind == "Slider"


# ---- examples/python/own_machine.py: a TurningSheave, a Weld, a Planar and a mobility force --------

def test_own_machine_example():
    import importlib.util
    path = os.path.join(support.PY_EXAMPLES, "own_machine.py")
    spec = importlib.util.spec_from_file_location("own_machine", path)
    om = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(om)
    side, speed = 300.0, 0.05
    system, bodies, rope, state = om.build(speed, side)
    assert [n.kind for n in rope.nodes] == ["WinchDrum", "TurningSheave", "RopeAnchor"]
    assert isinstance(rope.node(1), sr.TurningSheaveHandle) and not hasattr(rope.node(1), "slip_rate")
    assert [bodies[k].kind for k in ("drum", "jib", "sheave", "hook")] == ["Pin", "Weld", "Pin", "Planar"]
    e = om.equilibrium(system, bodies, rope, state, side)
    W = om.HOOK_M * om.G
    force_err = np.max(np.abs(e["hook_force"] - e["hook_force_closed_form"])) / W
    lean_err = abs(e["lean"] - e["lean_closed_form"])
    # The wrap angle at the point sheave: the turn between the chords to the drum and to the hitch.
    hitch = bodies["hook"].station_position(state, (0, om.HITCH, 0))
    a, b = -om.HEAD, hitch - om.HEAD
    alpha = math.pi - math.acos(np.dot(a, b) / np.linalg.norm(a) / np.linalg.norm(b))
    alpha_err = abs(e["wrap_angle"] - alpha)
    print("own machine: |F_hook - (-F, M g)| / M g %.3g, |lean - atan(F / (M g + rhoA g l / 2))| %.3g rad, "
          "|alpha - closed form| %.3g rad" % (force_err, lean_err, alpha_err))
    # Measured: 4.9e-8 (equilibrium to 1e-10 of the largest generalized force), 1.9e-6 rad (the
    # chord of a weighted span, to first order in rhoA g l / M g = 0.02) and 4.4e-16 rad; bounds
    # 1e-6, 2e-5 rad and 1e-14 rad (20x, 10x, 22x).
    assert force_err <= 1e-6 and lean_err <= 2e-5 and alpha_err <= 1e-14
    # Hauling: the stored rope grows by v t, exactly (a prescribed drum speed).
    sim = system.simulation(state, integrator="rk-merson", accuracy=1e-7)
    r = sim.run(t_end=0.5, report_interval=0.05)
    drum_err = np.max(np.abs(r["rope0.node0.rope_on_drum"] - (om.STORED + speed * r["t"])))
    print("own machine: |rope_on_drum - (stored + v t)| %.3g m" % drum_err)
    assert drum_err <= 1e-12  # measured 0 m (round-off bound)
    assert np.all(r["rope0.span1.axial_force_end"] > 0) and sim.limit_reached == ""
    # The script runs and prints its table.
    printed = support.python(path, "--t-end", "0.5").stdout
    assert printed.startswith("equilibrium: lean 0.06048") and "limit: none" in printed, printed


if __name__ == "__main__":
    sys.exit(support.main(globals()))
