#!/usr/bin/env python3
"""Plots of `fxraster plan` (docs/reports.md, "Planner"): the ratio to the target (log) against
the cost and against the measured model speed, every evaluated configuration grey, the Pareto
front (against cost) orange, the line ratio = 1 (the target). Exit 3 without matplotlib."""
import argparse
import csv
import sys

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit(3)

ap = argparse.ArgumentParser()
ap.add_argument("--csv", required=True)
ap.add_argument("--out", required=True)
ap.add_argument("--cost", required=True)
a = ap.parse_args()
rows = list(csv.DictReader(open(a.csv, newline="")))
floor = 1e-6
for x_key, x_label, name in (("cost", a.cost, "error_vs_cost.png"), ("mfrags_per_s", "model speed (M fragments/s)", "error_vs_speed.png")):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    xs = [float(r[x_key]) for r in rows]
    ys = [max(floor, float(r["ratio"])) for r in rows]
    ax.scatter(xs, ys, s=10, color="#999999", label="configurations")
    front = sorted((float(r[x_key]), max(floor, float(r["ratio"]))) for r in rows if r["pareto"] == "1")
    if front:
        ax.plot([p[0] for p in front], [p[1] for p in front], "o-", color="#dd8452", ms=4, label="Pareto front (cost)")
    ax.axhline(1.0, color="#c44e52", lw=1, ls="--", label="target")
    ax.set_yscale("log")
    ax.set_xlabel(x_label)
    ax.set_ylabel("worst error / target")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{a.out}/{name}", dpi=100)
    plt.close(fig)
