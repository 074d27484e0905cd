#!/usr/bin/python3
"""Plots of a sweep report: error against each cost, Pareto front marked.

Called by `fxraster sweep` (app/cmd_sweep.cpp) with the CSV it wrote:
    plot_sweep.py --csv OUT/sweep.csv --out OUT --unit recip --error max_err_ulp \
                  --cost latency --cost table_bits [--cost fmax_mhz:max]
Writes OUT/error_vs_<cost>.png per cost. The Pareto flags come from the CSV's
pareto_<cost> columns (computed once, in the C++ report writer); this script only draws.
Exit status: 0 done, 2 bad input (message names the file and column), 3 matplotlib missing.
"""
import argparse
import csv
import math
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--csv", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--unit", required=True)
    ap.add_argument("--error", required=True, help="error column (y axis, log scale)")
    ap.add_argument("--cost", action="append", required=True,
                    help="cost column (x axis); NAME:max when higher is better")
    a = ap.parse_args()
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("plot_sweep.py: matplotlib is not available for %s: plots skipped "
              "(apt-get install python3-matplotlib)" % sys.executable, file=sys.stderr)
        return 3

    with open(a.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        print("plot_sweep.py: %s: no rows" % a.csv, file=sys.stderr)
        return 2
    for spec in a.cost:
        cost, _, sense = spec.partition(":")
        for col in (cost, a.error, "pareto_" + cost, "label", "is_default"):
            if col not in rows[0]:
                print("plot_sweep.py: %s: no column '%s'" % (a.csv, col), file=sys.stderr)
                return 2
        pts = []
        for r in rows:
            if r[cost] == "" or r[a.error] == "":
                continue  # not measured (e.g. does not fit: no Fmax)
            pts.append((float(r[cost]), float(r[a.error]), r["label"],
                        r["pareto_" + cost] == "1", r["is_default"] == "1"))
        fig, ax = plt.subplots(figsize=(8, 5.5), dpi=110)
        # Zero error cannot sit on a log axis: draw it at a floor below the smallest nonzero.
        nonzero = [p[1] for p in pts if p[1] > 0]
        floor = min(nonzero) / 4 if nonzero else 1e-3
        def y(v):
            return v if v > 0 else floor
        other = [p for p in pts if not p[3]]
        front = sorted([p for p in pts if p[3]], key=lambda p: p[0])
        ax.scatter([p[0] for p in other], [y(p[1]) for p in other], s=22, c="#9aa4b1",
                   label="configuration")
        if front:
            ax.plot([p[0] for p in front], [y(p[1]) for p in front], "-o", c="#c2410c", ms=6,
                    drawstyle="steps-post", label="Pareto front")
            # One label per point: configurations tied in cost and error share it.
            tied = {}
            for p in front:
                tied.setdefault((p[0], p[1]), []).append(p[2])
            for (cx, ey), names in tied.items():
                text = names[0] + (" (+%d tied)" % (len(names) - 1) if len(names) > 1 else "")
                ax.annotate(text, (cx, y(ey)), textcoords="offset points", xytext=(4, 4),
                            fontsize=7, color="#7c2d12")
        for p in pts:
            if p[4]:
                ax.scatter([p[0]], [y(p[1])], s=140, facecolors="none", edgecolors="#1d4ed8",
                           linewidths=1.8, label="default (%s)" % p[2], zorder=5)
        yaxis = ax.get_yaxis_transform()  # x in axes fraction, y in data
        ax.axhline(0.5, ls=":", c="#15803d", lw=1)
        ax.text(0.99, 0.5, "0.5 ulp: correctly rounded", transform=yaxis, va="bottom", ha="right", fontsize=7,
                color="#15803d")
        ax.axhline(1.0, ls=":", c="#b45309", lw=1)
        ax.text(0.99, 1.0, "1 ulp: faithful", transform=yaxis, va="bottom", ha="right", fontsize=7, color="#b45309")
        ax.set_yscale("log")
        if cost in ("table_bits", "lut4", "mult_bits", "mult_cells", "area_proxy") and \
                all(p[0] > 0 for p in pts) and pts and max(p[0] for p in pts) > 20 * min(p[0] for p in pts):
            ax.set_xscale("log")
        ax.set_xlabel(cost + (" (higher is better)" if sense == "max" else ""))
        ax.set_ylabel(a.error + " (log)")
        ax.set_title("%s: %s against %s (%d configurations)" % (a.unit, a.error, cost, len(pts)))
        ax.grid(True, which="both", alpha=0.25)
        ax.legend(fontsize=8, loc="upper right")
        path = "%s/error_vs_%s.png" % (a.out, cost)
        fig.savefig(path, bbox_inches="tight")
        plt.close(fig)
    return 0


if __name__ == "__main__":
    sys.exit(main())
