#!/usr/bin/env python3
"""The paper's pendulum study from Python: the four cases n_a = 0..3 of reeving-pendulum.

Each case is simbody_reeving.run_pendulum, the demo's own case (examples/pendulum/main.cpp
runCase: the same scene, integrator, stepper and report times), so the numbers are the demo's:
the maximum energy drift, the steps and the axial force at the payload end at every report.

    PYTHONPATH=build/python python3 examples/python/pendulum.py [--t-end 20] [--axial-modes 0,1,2,3]
        [--integrator rk-merson] [--accuracy 1e-6] [--json FILE] [--plot FILE.png] [--no-plots]

--json FILE writes every case's summary, time series and static axial force (numbers with every
digit) for tests/python; --plot draws the payload-end force of every case (matplotlib, if present).
"""

import argparse
import json
import sys

import simbody_reeving as sr


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--axial-modes", default="0,1,2,3", help="comma list of n_a (default 0,1,2,3)")
    parser.add_argument("--t-end", type=float, default=20.0, help="end time [s] (default 20)")
    parser.add_argument("--vx0", type=float, default=1.0, help="the payload's push [m/s] (default 1)")
    parser.add_argument("--integrator", default="rk-merson", choices=sr.integrator_names())
    parser.add_argument("--accuracy", type=float, default=1e-6)
    parser.add_argument("--report-interval", type=float, default=0.01, help="[s] (default 0.01)")
    parser.add_argument("--json", metavar="FILE", help="write the cases' numbers to FILE")
    parser.add_argument("--plot", metavar="PNG", default="pendulum_payload_end_force.png",
                        help="the figure (default pendulum_payload_end_force.png)")
    parser.add_argument("--no-plots", action="store_true", help="no figure")
    args = parser.parse_args(argv)
    modes = [int(m) for m in args.axial_modes.split(",")]

    cases = {}
    print("n_a  steps  max energy drift [J]  payload-end axial force [N]: static      min           max")
    for na in modes:
        case = sr.run_pendulum(axial_modes=na, t_end=args.t_end, vx0=args.vx0, integrator=args.integrator,
                               accuracy=args.accuracy, report_interval=args.report_interval)
        s, force = case["summary"], case["timeseries"]["axial_force_payload"]
        cases[na] = case
        # %.12g: the digits reeving-pendulum writes to summary.json and timeseries.csv
        print("%3d %6d  %-20.12g  %26.12g %13.12g %13.12g" % (na, s["steps"], s["max_energy_drift_J"], force[0],
                                                              force.min(), force.max()))
    drift = max(c["summary"]["max_energy_drift_J"] for c in cases.values())
    print("max energy drift over the cases: %.3e J (reeving-pendulum prints the same)" % drift)

    if args.json:
        def arrays(d):
            return {k: [float(x) for x in v] for k, v in d.items()}
        with open(args.json, "w") as f:
            json.dump({str(na): {"summary": c["summary"], "timeseries": arrays(c["timeseries"]),
                                 "static_axial_force": arrays(c["static_axial_force"])}
                       for na, c in cases.items()}, f)
    if not args.no_plots:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            print("pendulum.py: matplotlib not found, no figure (apt-get install python3-matplotlib)",
                  file=sys.stderr)
            return 0
        fig, ax = plt.subplots(figsize=(9, 5))
        for na, c in cases.items():
            ax.plot(c["timeseries"]["t"], c["timeseries"]["axial_force_payload"], label="n_a = %d" % na)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("P [N]")
        ax.set_title("Axial force at the payload end")
        ax.grid(True)
        ax.legend()
        fig.savefig(args.plot, dpi=100)
        print("pendulum.py: figure in %s" % args.plot)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except ValueError as e:  # a bad option: the C++ message
        print("pendulum.py: %s" % e, file=sys.stderr)
        sys.exit(2)
