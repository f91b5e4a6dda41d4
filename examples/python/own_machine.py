#!/usr/bin/env python3
"""One's own machine from Python: a winch hauls a hook over a jib head sheave.

The machine, body by body (simbody_reeving.System): a winch drum on a Pin at the origin, a jib
welded to the ground with its head sheave (a TurningSheave: an idler with inertia the rope turns
without slip) on a Pin at (6, 4) m, and a hook on a Planar mobilizer, hanging 5 m below the sheave
and pulled sideways by a constant force. One planar rope: the drum, the sheave, an anchor on the
hook. The drum turns at a prescribed speed (hauling in); static equilibrium first, then a run.

    PYTHONPATH=build/python python3 examples/python/own_machine.py [--t-end 2] [--haul-speed 0.05]
        [--side-force 300] [--integrator rk-merson] [--accuracy 1e-7]

Prints the equilibrium (the hook's rope force and its span's lean against the closed forms: the
rope balances weight and side force, (-F, M g); the chord leans by atan(F / (M g + rhoA g l / 2)),
the tension at the span's middle, l its length), then per report the hook's height, the rope
on the drum, the forces at both ends of the hook's span and the torques on drum and sheave.
"""

import argparse
import math
import sys

import numpy as np

import simbody_reeving as sr

G = 9.81
DRUM_R, STORED = 0.4, 30.0           # drum radius, rope on it at angle 0 [m]
HEAD = np.array([6.0, 4.0, 0.0])      # the jib head sheave's centre [m]
SHEAVE_R, DROP = 0.3, 5.0             # its radius, the hook's initial drop below it [m]
HOOK_M, HOOK_J, HITCH = 500.0, 20.0, 0.3  # hook mass [kg], inertia [kg m^2], rope hitch above its centre [m]
RHOA, EA = 2.0, 5e7                   # rope [kg/m], [N]


def build(haul_speed, side_force, spans=None):
    """The machine at static equilibrium with the drum at rest; the drum's speed then prescribed.
    Returns (system, bodies, rope, state): bodies a dict drum, jib, sheave, hook."""
    system = sr.System(gravity=(0, -G, 0))
    drum = system.add_pin(system.ground, sr.MassProperties(80.0, (0, 0, 0), 3.0))
    # Motion::Steady: the drum turns at -haul_speed / R (payout sense +1: a negative angle hauls in).
    drum.prescribe_steady_speed(-haul_speed / DRUM_R)
    jib = system.add_weld(system.ground, sr.MassProperties(200.0, (0, 0, 0), (50.0, 50.0, 80.0)), in_parent=HEAD)
    sheave = system.add_pin(jib, sr.MassProperties(10.0, (0, 0, 0), 0.3))
    hook = system.add_planar(system.ground, sr.MassProperties(HOOK_M, (0, 0, 0), HOOK_J))
    # Planar: u0 the rotation about z, u1, u2 the translations along x, y.
    system.add_mobility_force(hook, side_force, u_index=1)
    chord = float(np.linalg.norm(HEAD))
    rope = system.add_rope(sr.RopeSpec(
        name="hoist rope",
        start=sr.WinchDrum(drum, radius=DRUM_R, rope_on_drum=STORED),
        sheaves=[sr.TurningSheave(sheave, radius=SHEAVE_R, material_coordinate_at_zero_angle=chord)],
        end=sr.RopeAnchor(hook, (0, HITCH, 0)),
        properties=sr.RopeProperties(mass_per_length=RHOA, axial_stiffness=EA),
        unstretched_length=chord + DROP,
        span_defaults=spans or sr.SpanOptions(axial_modes=1, transverse_modes=1),
        plane_normal=(0, 0, 1)))
    state = system.default_state()
    # The guess: the hook on its rope's line, leaning by atan(F / M g) (Newton's steps from hanging
    # straight down do not find the leaning equilibrium).
    lean = math.atan2(side_force, HOOK_M * G)
    reach = DROP + HITCH
    hook.set_q(state, (lean, HEAD[0] + reach * math.sin(lean), HEAD[1] - reach * math.cos(lean)))
    system.find_static_equilibrium(state, 1e-10)
    return system, dict(drum=drum, jib=jib, sheave=sheave, hook=hook), rope, state


def equilibrium(system, bodies, rope, state, side_force):
    """The equilibrium's numbers and their closed forms."""
    hook = bodies["hook"]
    hitch = hook.station_position(state, (0, HITCH, 0))
    chord = HEAD - hitch
    lean = math.atan2(-chord[0], chord[1])  # the hook span's chord from the vertical, + towards the jib
    F = rope.node(2).node_force(state)
    s1, s2 = system.reeving.span_material_range(state, rope, 1)
    return dict(lean=lean, lean_closed_form=math.atan2(side_force, HOOK_M * G + RHOA * G * (s2 - s1) / 2),
                hook_force=F, hook_force_closed_form=np.array([-side_force, HOOK_M * G, 0.0]),
                rope_on_drum=rope.node(0).rope_on_drum(state), wrap_angle=rope.node(1).wrap_angle(state))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--t-end", type=float, default=2.0, help="[s] (default 2)")
    # The start's jerk rings the hook on the rope (about 90 rad/s) with m v omega_n: 2.3 kN at
    # 0.05 m/s, under its weight (faster, the rope goes slack for a moment).
    parser.add_argument("--haul-speed", type=float, default=0.05, help="rope speed onto the drum [m/s] (default 0.05)")
    parser.add_argument("--side-force", type=float, default=300.0, help="on the hook along +x [N] (default 300)")
    parser.add_argument("--integrator", default="rk-merson", choices=sr.integrator_names())
    parser.add_argument("--accuracy", type=float, default=1e-7)
    parser.add_argument("--report-interval", type=float, default=0.25, help="[s] (default 0.25)")
    args = parser.parse_args(argv)

    system, bodies, rope, state = build(args.haul_speed, args.side_force)
    e = equilibrium(system, bodies, rope, state, args.side_force)
    print("equilibrium: lean %.9f rad (closed form %.9f), hook force (%.6f, %.6f) N (closed form (%.6f, %.6f)), "
          "rope on drum %.6f m, wrap angle %.6f rad"
          % (e["lean"], e["lean_closed_form"], e["hook_force"][0], e["hook_force"][1],
             e["hook_force_closed_form"][0], e["hook_force_closed_form"][1], e["rope_on_drum"], e["wrap_angle"]))

    sim = system.simulation(state, integrator=args.integrator, accuracy=args.accuracy)
    r = sim.run(t_end=args.t_end, report_interval=args.report_interval)
    # The hook's y: Planar q = (angle, x, y), from the hook's first q in the state's.
    y = "q%d" % (bodies["hook"].q_index(state) + 2)
    print("%6s %10s %12s %12s %12s %12s %12s" % ("t [s]", "hook y [m]", "on drum [m]", "P top [N]", "P hook [N]",
                                               "drum [N m]", "sheave [N m]"))
    for i in range(len(r["t"])):
        print("%6.2f %10.5f %12.6f %12.3f %12.3f %12.3f %12.4f"
              % (r["t"][i], r[y][i], r["rope0.node0.rope_on_drum"][i], r["rope0.span1.axial_force_start"][i],
                 r["rope0.span1.axial_force_end"][i], r["rope0.node0.torque"][i], r["rope0.node1.torque"][i]))
    print("steps %d, limit: %s" % (sim.steps, sim.limit_reached or "none"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
