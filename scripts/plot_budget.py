#!/usr/bin/env python3
"""Plots of `fxraster budget` (docs/reports.md, "Error budget").

Reads budget_fragments.csv (one row per sampled fragment and output: error, the share of every
rounding point, the residual) and writes into --out:
  hist_<output>.png           histogram of the error (every point active), log count
  heat_<output>_<point>.png   the share of <point> over the image, for each point that is the
                              dominant one on at least 1 % of that output's sampled fragments
Prints the names of the files written, one a line. Exit 3 when matplotlib is missing.
"""
import argparse
import csv
import sys

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit(3)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--csv", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--width", type=int, required=True)
    ap.add_argument("--height", type=int, required=True)
    a = ap.parse_args()
    rows = {}
    with open(a.csv, newline="") as f:
        r = csv.DictReader(f)
        points = [c[len("share_"):] for c in r.fieldnames if c.startswith("share_")]
        for row in r:
            rows.setdefault((row["output"], row["unit"]), []).append(row)
    written = []
    for (out, unit), rs in sorted(rows.items()):
        err = [float(x["error"]) for x in rs]
        fig, ax = plt.subplots(figsize=(6, 3.5))
        ax.hist(err, bins=60, color="#4c72b0")
        ax.set_yscale("log")
        ax.set_xlabel(f"{out} error ({unit}), every rounding point active")
        ax.set_ylabel("fragments")
        ax.set_title(f"{out}: {len(err)} sampled fragments")
        fig.tight_layout()
        name = f"hist_{out}.png"
        fig.savefig(f"{a.out}/{name}", dpi=100)
        plt.close(fig)
        written.append(name)
        # Dominant point per fragment (largest share; the residual competes too).
        counts = {p: 0 for p in points}
        for x in rs:
            best, bp = 0.0, None
            for p in points:
                s = float(x["share_" + p])
                if s > best:
                    best, bp = s, p
            if bp is not None and float(x["residual"]) <= best:
                counts[bp] += 1
        for p in points:
            if counts[p] < max(1, 0.01 * len(rs)):
                continue
            xs = [int(x["x"]) + 0.5 for x in rs]
            ys = [int(x["y"]) + 0.5 for x in rs]
            cs = [float(x["share_" + p]) for x in rs]
            fig, ax = plt.subplots(figsize=(6, 6 * a.height / max(1, a.width) + 0.6))
            sc = ax.scatter(xs, ys, c=cs, s=4, cmap="inferno", marker="s")
            ax.set_xlim(0, a.width)
            ax.set_ylim(0, a.height)
            ax.set_aspect("equal")
            ax.set_title(f"{out}: share of {p} ({unit}); dominant on {counts[p]} of {len(rs)}")
            fig.colorbar(sc, ax=ax, shrink=0.8)
            fig.tight_layout()
            name = f"heat_{out}_{p}.png"
            fig.savefig(f"{a.out}/{name}", dpi=100)
            plt.close(fig)
            written.append(name)
    for w in written:
        print(w)


if __name__ == "__main__":
    main()
