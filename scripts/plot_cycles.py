#!/usr/bin/python3
"""Timeline of stage occupancy from `fxraster cycles` (app/cmd_cycles.cpp).

    plot_cycles.py --csv OUT/timeline.csv --out OUT/timeline.png [--title T]

The CSV has a column `clock` (the bin's first clock, from the frame's start) and one column per
stage with the fraction of the bin's clocks the stage was busy. One lane per stage.
Exit status: 0 done, 2 bad input (message names the file and column), 3 matplotlib missing.
"""
import argparse
import csv
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--csv", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--title", default="stage occupancy")
    a = ap.parse_args()
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("plot_cycles.py: matplotlib is not installed", file=sys.stderr)
        return 3
    try:
        with open(a.csv, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        print("plot_cycles.py: %s: %s" % (a.csv, e), file=sys.stderr)
        return 2
    if not rows or "clock" not in rows[0]:
        print("plot_cycles.py: %s: no rows or no column 'clock'" % a.csv, file=sys.stderr)
        return 2
    stages = [c for c in rows[0].keys() if c != "clock"]
    try:
        x = [int(r["clock"]) for r in rows]
        ys = {s: [float(r[s]) for r in rows] for s in stages}
    except (ValueError, KeyError) as e:
        print("plot_cycles.py: %s: bad value: %s" % (a.csv, e), file=sys.stderr)
        return 2
    width = (x[1] - x[0]) if len(x) > 1 else 1
    fig, ax = plt.subplots(figsize=(10, 0.6 * len(stages) + 1.5))
    for i, s in enumerate(stages):
        ax.bar(x, [0.85 * v for v in ys[s]], width=width, bottom=i, align="edge", color="C%d" % (i % 10))
    ax.set_yticks([i + 0.4 for i in range(len(stages))])
    ax.set_yticklabels(stages)
    ax.set_xlabel("clock (bin width %d)" % width)
    ax.set_title(a.title + " (bar height: busy fraction of the bin)")
    ax.set_xlim(x[0], x[-1] + width)
    fig.tight_layout()
    fig.savefig(a.out, dpi=100)
    return 0


if __name__ == "__main__":
    sys.exit(main())
