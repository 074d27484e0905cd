#!/usr/bin/python3
"""Synthesis cost of unit configurations: LUT4s, logic depth, Fmax.

For each configuration in --configs (JSON list of {"id", "label", "params": {CamelName: int}},
written by `fxraster sweep UNIT --synth`), synthesises rtl/fxr_<unit>.sv (read with every other
rtl/fxr_*.sv file: units share modules such as fxr_seed_rom, fxr_nr_step, fxr_round; synthesis
keeps what the top instantiates) with the parameters set by `chparam`:

  generic:  yosys  read_verilog -sv PKG RTL...; chparam ...; synth -flatten -top T; abc -lut 4;
                   opt_clean; stat; ltp -noff          -> LUT4 count, depth (LUT levels)
  ice40:    yosys  ... synth_ice40 -top T -json x.json   (flattens by default)
            nextpnr-ice40 --hx8k --package ct256 --json x.json --freq 100
                                                        -> logic cells, Fmax (MHz) or "does not fit"

Depth comes from the generic netlist: after synth_ice40, ltp does not treat SB_DFF cells as
flip-flops (docs/references.md#toolchain-yosys). Results are cached per configuration in
--cache/<key>.json, where the key hashes the unit, the parameters, the RTL and package text and
this flow, so a rerun only synthesises what changed. Writes --out CSV:
id,label,lut4,depth,ice40_lc,fmax_mhz,fit.
"""
import argparse
import glob
import hashlib
import json
import os
import re
import subprocess
import sys
import tempfile
import time

FLOW_VERSION = "3"  # bump when the flow below changes (invalidates the cache)
HX8K_LCS = 7680
TOOL_TIMEOUT_S = 1800


def rtl_files(rtl_dir, unit):
    top = os.path.join(rtl_dir, "fxr_%s.sv" % unit)
    if not os.path.exists(top):
        raise SystemExit("synth_cost.py: %s: not found (the unit's RTL has not landed?)" % top)
    # Modules with record ports (fxr_rec_pkg, docs/rtl.md) are not read for a unit that does not
    # use them: their package is generated beside fxr_config_pkg only when needed (see main()).
    others = sorted(f for f in glob.glob(os.path.join(rtl_dir, "fxr_*.sv"))
                    if f != top and "fxr_rec_pkg" not in open(f).read())
    return [top] + others


def declared_params(top_file):
    text = open(top_file).read()
    return set(re.findall(r"parameter\s+(?:int\s+(?:unsigned\s+)?|integer\s+)?(\w+)\s*=", text))


def run(cmd, cwd, log):
    t0 = time.time()
    with open(log, "w") as f:
        try:
            p = subprocess.run(cmd, cwd=cwd, stdout=f, stderr=subprocess.STDOUT, timeout=TOOL_TIMEOUT_S)
            rc = p.returncode
        except subprocess.TimeoutExpired:
            rc = -1
    return rc, time.time() - t0, open(log, errors="replace").read()


def yosys_script(pkg, files, top, params, tail):
    read = "read_verilog -sv %s %s" % (pkg, " ".join(files))
    ch = "".join("chparam -set %s %d %s; " % (k, v, top) for k, v in sorted(params.items()))
    return "%s; %s%s" % (read, ch, tail)


def synth_one(unit, cfg, pkg, files, no_pnr, workdir):
    top = "fxr_%s" % unit
    known = declared_params(files[0])
    params = {k: v for k, v in cfg["params"].items() if k in known}
    res = {"id": cfg["id"], "label": cfg["label"], "lut4": "", "depth": "", "ice40_lc": "",
           "fmax_mhz": "", "fit": ""}
    # generic: LUT4s and depth
    script = yosys_script(pkg, files, top, params, "synth -flatten -top %s; abc -lut 4; opt_clean; stat; ltp -noff" % top)
    rc, secs, log = run(["yosys", "-p", script], workdir, os.path.join(workdir, "generic.log"))
    if rc != 0:
        err = [l for l in log.splitlines() if "ERROR" in l]
        res["fit"] = "yosys error: " + (err[-1] if err else "exit %d" % rc).replace(",", ";")[:200]
        return res
    luts = re.findall(r"^\s+\$lut\s+(\d+)", log, re.M)
    depth = re.findall(r"Longest topological path in \S+ \(length=(\d+)\)", log)
    res["lut4"] = luts[-1] if luts else "0"
    res["depth"] = depth[-1] if depth else ""
    res["generic_s"] = round(secs, 1)
    if no_pnr:
        res["fit"] = "not run"
        return res
    # iCE40: logic cells and Fmax
    script = yosys_script(pkg, files, top, params, "synth_ice40 -top %s -json x.json" % top)
    rc, secs, log = run(["yosys", "-q", "-p", script], workdir, os.path.join(workdir, "ice40.log"))
    if rc != 0:
        res["fit"] = "synth_ice40 error"
        return res
    rc, secs2, log = run(["nextpnr-ice40", "--hx8k", "--package", "ct256", "--json", "x.json",
                          "--freq", "100"], workdir, os.path.join(workdir, "nextpnr.log"))
    lc = re.findall(r"ICESTORM_LC:\s+(\d+)/\s*(\d+)", log)
    if lc:
        res["ice40_lc"] = lc[-1][0]
    fmax = re.findall(r"Max frequency for clock '[^']*': ([\d.]+) MHz", log)
    if fmax:  # placed and routed; nextpnr exits non-zero when --freq is not met: still a result
        res["fmax_mhz"] = fmax[-1]
        res["fit"] = "fits"
    elif lc and int(lc[-1][0]) > int(lc[-1][1]) or "Unable to place" in log or "failed to place" in log.lower():
        res["fit"] = "does not fit"
    else:
        err = [l for l in log.splitlines() if "ERROR" in l]
        res["fit"] = ("nextpnr error: " + (err[-1] if err else "exit %d" % rc)).replace(",", ";")[:200]
    res["pnr_s"] = round(secs + secs2, 1)
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--unit", required=True)
    ap.add_argument("--configs", required=True)
    ap.add_argument("--pkg", required=True, help="generated fxr_config_pkg.sv")
    ap.add_argument("--rtl-dir", required=True)
    ap.add_argument("--cache", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--no-pnr", action="store_true", help="generic LUT4 / depth only (no nextpnr)")
    ap.add_argument("--only", action="append", default=[], help="synthesise only these ids (others: cache or empty)")
    a = ap.parse_args()

    files = [os.path.abspath(f) for f in rtl_files(a.rtl_dir, a.unit)]
    pkg = os.path.abspath(a.pkg)
    if "fxr_rec_pkg" in open(files[0]).read():  # record ports: the generated fxr_rec_pkg.sv beside PKG
        pkg += " " + os.path.join(os.path.dirname(pkg), "fxr_rec_pkg.sv")
    configs = json.load(open(a.configs))
    os.makedirs(a.cache, exist_ok=True)
    tools = subprocess.run(["yosys", "-V"], capture_output=True, text=True).stdout.strip()
    src_hash = hashlib.sha256()
    for f in pkg.split() + files:
        src_hash.update(open(f, "rb").read())
    rows = []
    for i, cfg in enumerate(configs):
        key = hashlib.sha256(json.dumps([FLOW_VERSION, tools, a.unit, cfg["params"], a.no_pnr,
                                         src_hash.hexdigest()], sort_keys=True).encode()).hexdigest()[:20]
        cached = os.path.join(a.cache, "%s-%s.json" % (cfg["id"], key))
        if os.path.exists(cached):
            res = json.load(open(cached))
            how = "cached"
        elif a.only and cfg["id"] not in a.only:
            res = {"id": cfg["id"], "label": cfg["label"], "lut4": "", "depth": "", "ice40_lc": "",
                   "fmax_mhz": "", "fit": "not run"}
            how = "skipped"
        else:
            with tempfile.TemporaryDirectory(prefix="synth-", dir=a.cache) as wd:
                res = synth_one(a.unit, cfg, pkg, files, a.no_pnr, wd)
            json.dump(res, open(cached, "w"), indent=1)
            how = "synthesised"
        rows.append(res)
        print("[synth %s] %d/%d %s: %s LUT4, depth %s, Fmax %s (%s) [%s]" % (
            a.unit, i + 1, len(configs), cfg["label"], res["lut4"], res["depth"],
            res["fmax_mhz"] or "-", res["fit"], how), file=sys.stderr, flush=True)
    cols = ["id", "label", "lut4", "depth", "ice40_lc", "fmax_mhz", "fit"]
    with open(a.out, "w") as f:
        f.write(",".join(cols) + "\n")
        for r in rows:
            f.write(",".join(str(r.get(c, "")).replace(",", ";") for c in cols) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
