#!/usr/bin/python3
"""Tools test of `fxraster sweep` (ctest label tools), end to end:
    check_sweep_report.py FXRASTER WORKDIR UNIT [extra sweep args...]
runs the sweep into WORKDIR/UNIT, checks that sweep.csv, report.md and the plots exist, that
the CSV parses with the expected columns (every parameter of the unit, the cost and error
metrics, the Pareto flags), that exactly the default row is marked, that each Pareto front is
non-empty and not dominated, and that bad arguments give a clear message and a non-zero exit.
"""
import csv
import os
import shutil
import subprocess
import sys

COMMON = ["latency", "ii", "table_bits", "multipliers", "max_err_ulp", "mean_err_ulp",
          "rms_err_ulp", "correctly_rounded_share", "count", "multiplier_widths",
          "pareto_latency", "pareto_table_bits"]
PARAMS = {
    "recip": ["in_sig_bits", "out_sig_bits", "seed_index_bits", "seed_frac_bits", "nr_steps",
              "nr_frac_bits", "correction", "max_err_ulp_before_round", "faithful"],
    "div": ["algorithm", "num_bits", "den_bits", "quot_bits", "seed_index_bits", "seed_bits",
            "nr_steps", "nr_frac_bits", "bits_per_stage", "schedule", "correctly_rounded"],
}
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL " + what)


def main():
    fxr, work, unit = sys.argv[1], sys.argv[2], sys.argv[3]
    extra = sys.argv[4:]
    out = os.path.join(work, unit)
    shutil.rmtree(out, ignore_errors=True)
    p = subprocess.run([fxr, "sweep", unit, "--out", out, "--no-timing"] + extra,
                       capture_output=True, text=True)
    print(p.stdout + p.stderr)
    check(p.returncode == 0, "sweep exit status %d" % p.returncode)
    csv_path = os.path.join(out, "sweep.csv")
    for f in ("sweep.csv", "report.md", "error_vs_latency.png", "error_vs_table_bits.png"):
        path = os.path.join(out, f)
        check(os.path.isfile(path) and os.path.getsize(path) > 0, "%s exists and is not empty" % f)
    if os.path.isfile(csv_path):
        with open(csv_path, newline="") as f:
            rows = list(csv.DictReader(f))
        check(len(rows) >= 2, "CSV has rows (%d)" % len(rows))
        cols = rows[0].keys() if rows else []
        for c in ["id", "label", "is_default"] + COMMON + PARAMS[unit]:
            check(c in cols, "CSV column '%s'" % c)
        check(sum(r["is_default"] == "1" for r in rows) == 1, "exactly one default row")
        check(len({r["id"] for r in rows}) == len(rows), "configuration ids are unique")
        for r in rows:
            for c in ("latency", "table_bits", "max_err_ulp", "correctly_rounded_share"):
                try:
                    float(r[c])
                except (ValueError, KeyError):
                    check(False, "row %s: column %s is a number (%r)" % (r.get("label"), c, r.get(c)))
        for cost in ("latency", "table_bits"):
            front = [r for r in rows if r.get("pareto_" + cost) == "1"]
            check(len(front) >= 1, "Pareto front against %s is not empty" % cost)
            for a in front:  # independent re-check: nothing dominates a front row
                ca, ea = float(a[cost]), float(a["max_err_ulp"])
                for b in rows:
                    cb, eb = float(b[cost]), float(b["max_err_ulp"])
                    check(not (cb <= ca and eb <= ea and (cb < ca or eb < ea)),
                          "front row %s (%s) is dominated by %s" % (a["label"], cost, b["label"]))
    md = open(os.path.join(out, "report.md")).read() if os.path.isfile(os.path.join(out, "report.md")) else ""
    check("## Pareto front" in md and "(default)" in md and "error_vs_latency.png" in md,
          "report.md has the default row, the Pareto fronts and the plots")

    # The registry lists the unit (the main job iterates over `sweep --list`).
    p = subprocess.run([fxr, "sweep", "--list"], capture_output=True, text=True)
    check(p.returncode == 0 and unit in p.stdout.split(), "sweep --list names %s: %r" % (unit, p.stdout))

    # Bad arguments: clear message, non-zero exit, nothing written.
    for args, needle in ((["sweep", "nosuchunit"], "nosuchunit"),
                         (["sweep"], "unit"),
                         (["sweep", unit, "--count", "0"], "count"),
                         (["sweep", unit, "--out", "/proc/fxraster-cannot-write-here"], "/proc/fxraster-cannot-write-here")):
        p = subprocess.run([fxr] + args, capture_output=True, text=True)
        check(p.returncode != 0, "%s exits non-zero (got %d)" % (" ".join(args), p.returncode))
        check(needle in (p.stdout + p.stderr), "%s: message names '%s': %r" % (" ".join(args), needle,
                                                                             (p.stdout + p.stderr)[-300:]))
    print("sweep %s report: %s" % (unit, "FAILED (%d)" % len(failures) if failures else "PASSED"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
