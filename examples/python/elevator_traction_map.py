#!/usr/bin/env python3
"""A small EN 81-50 traction study of the bundled elevator, run from Python.

The study of studies/elevator-traction, smaller: the loading and emergency-stop cases over the
groove friction, the car's position in the shaft and its load. simbody_reeving.run_study runs it
with reeving-study's own code (each case the reeving-elevator demo, checked with --check first),
so its table is the runner's results.csv: run the study file --write-study writes with
`build/examples/reeving-study FILE` and the two tables agree bit for bit (wall times aside).

    PYTHONPATH=build/python python3 examples/python/elevator_traction_map.py [--small] [--out DIR]
        [--write-study FILE.json] [--plot FILE.png] [--no-plots]

--small: 8 cases (car at 20 m, empty or at 125 %) instead of 36; --out keeps the runner's outputs
(results.csv, summary.json); --plot draws the margins (matplotlib, if present).
"""

import argparse
import json
import sys

import simbody_reeving as sr

METRICS = [
    "traction_table.0.traction",                  # held or slipped
    "traction_table.0.traction_margin",           # e^(mu alpha) / the largest force ratio [-]
    "traction_table.0.slip_distance_m",           # rope slip over the sheave [m]
    "traction_table.0.largest_force_ratio",       # [-]
    "traction_table.0.traction_limit",            # e^(mu alpha) [-]
    "traction_table.0.max_car_acceleration_mps2",
    "traction_table.0.steps",
    "wall_seconds",
]


def study(small=False):
    """The study as a dict: the keys of a study file (docs/studies.md)."""
    if small:
        position = [20]
        load = [0, 1.25]
    else:
        position = {"linear": {"from": 2, "to": 38, "count": 3}}   # 2, 20, 38 m above the bottom landing
        load = {"linear": {"from": 0, "to": 1.25, "count": 3}}      # 0, 62.5, 125 % of the rated load
    return {
        "description": "EN 81-50 traction of the bundled elevator (a small map, from Python)",
        "scene": "elevator",
        "fixed": {"axial-modes": 1, "transverse-modes": 1},
        "vary": {
            "scenario": ["loading", "emergency-stop"],
            "friction": [0.1, 0.2],
            "car-position": position,
            "car-load": load,
        },
        "metrics": METRICS,
        "limits": {"wall_seconds": 120},
    }


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--small", action="store_true", help="8 cases instead of 36")
    parser.add_argument("--out", metavar="DIR", help="keep the runner's outputs in DIR")
    parser.add_argument("--write-study", metavar="FILE", help="write the study (JSON, a YAML study file) to FILE")
    parser.add_argument("--plot", metavar="PNG", default="elevator_traction_map.png")
    parser.add_argument("--no-plots", action="store_true", help="no figure")
    args = parser.parse_args(argv)

    s = study(args.small)
    if args.write_study:
        with open(args.write_study, "w") as f:
            json.dump(s, f, indent=2)
    rows = sr.run_study(s, out=args.out)
    print("%-15s %5s %6s %6s  %-8s %8s %9s" % ("scenario", "mu", "z [m]", "load", "traction", "margin", "slip [m]"))
    for r in rows:
        print("%-15s %5g %6g %6g  %-8s %8.4f %9.4f" % (
            r["scenario"], r["friction"], r["car-position"], r["car-load"], r["traction_table.0.traction"],
            r["traction_table.0.traction_margin"], r["traction_table.0.slip_distance_m"]))
    failed = [r for r in rows if r["status"] != "ok"]
    held = sum(r["traction_table.0.traction"] == "held" for r in rows)
    print("%d cases: %d held, %d slipped, %d failed" % (len(rows), held, len(rows) - held - len(failed), len(failed)))

    if not args.no_plots:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            print("elevator_traction_map.py: matplotlib not found, no figure (apt-get install python3-matplotlib)",
                  file=sys.stderr)
            return 1 if failed else 0
        table = sr.results_array(rows)
        fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
        for ax, scenario in zip(axes, ["loading", "emergency-stop"]):
            for mu in sorted(set(table["friction"])):
                for z in sorted(set(table["car-position"])):
                    sel = (table["scenario"] == scenario) & (table["friction"] == mu) & (table["car-position"] == z)
                    ax.plot(table["car-load"][sel], table["traction_table.0.traction_margin"][sel], "o-",
                            label="mu %g, z %g m" % (mu, z))
            ax.axhline(1.0, color="k", lw=0.8)
            ax.set_title(scenario)
            ax.set_xlabel("car load [of the rated load]")
            ax.grid(True)
        axes[0].set_ylabel("traction margin [-]")
        axes[1].legend(fontsize=7)
        fig.savefig(args.plot, dpi=100)
        print("elevator_traction_map.py: figure in %s" % args.plot)
    return 1 if failed else 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except ValueError as e:  # a bad study: the runner's message
        print("elevator_traction_map.py: %s" % e, file=sys.stderr)
        sys.exit(2)
