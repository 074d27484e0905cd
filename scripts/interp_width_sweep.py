#!/usr/bin/env python3
"""Measured error of narrower interpolator plane sums (docs/rtl.md, "fxr_interp": plane width).

The 1/w and v/w plane sums of stage 7 are interp_plane_bits = plane_edge_bits + interp_block_bits
+ 3 wide (125 at the default: 2·attr_coord_bits + 2 = 82 edge bits, 40 block bits). This renders
scenes with `fxraster render` at narrower raster.interp_block_bits (and attr_coord_bits) and
reports, per configuration, the varyings' error against the double reference and the exact
(GMP) spot checks, and how many output varyings differ from the default configuration's.

    scripts/interp_width_sweep.py --fxraster build/app/fxraster --out DIR [--scene S.json ...]

Writes DIR/interp_width.md (a Markdown table) and prints it.
"""
import argparse
import csv
import json
import os
import subprocess

CONFIGS = [  # (interp_block_bits, attr_coord_bits)
    (40, 40), (36, 40), (32, 40), (30, 40), (28, 40), (26, 40), (24, 40), (40, 36), (32, 36), (28, 36)]


def plane_bits(ibb, acb):
    return 2 * acb + 2 + ibb + 3


def render(fx, scene, cfg, out, size):
    os.makedirs(out, exist_ok=True)
    conf = os.path.join(out, "config.json")
    json.dump({"version": 1, "raster": {"interp_block_bits": cfg[0], "attr_coord_bits": cfg[1]}}, open(conf, "w"))
    cmd = [fx, "render", "--out", os.path.join(out, "r"), "--config", conf, "--no-affine-image", "--quiet"]
    cmd += ["--default"] if scene == "default" else [scene]
    if size:
        cmd += ["--width", str(size[0]), "--height", str(size[1])]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        return None, (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1]
    return os.path.join(out, "r"), ""


def varyings(path):
    rows = []
    with open(os.path.join(path, "fragments.csv")) as f:
        lines = [l for l in f if not l.startswith("#")]
    for r in csv.DictReader(lines):
        rows.append(tuple(v for k, v in r.items() if k.startswith("v")))
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--fxraster", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--scene", action="append", default=None)
    ap.add_argument("--size", default=None, help="WxH viewport override")
    a = ap.parse_args()
    size = tuple(int(v) for v in a.size.split("x")) if a.size else None
    scenes = a.scene or ["default"]
    lines = ["| scene | interp_block_bits | attr_coord_bits | interp_plane_bits | u max ulp | u p99.9 ulp | v max ulp | "
             "v p99.9 ulp | exact spot max ulp (u, v) | varyings != default | texel max |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for scene in scenes:
        base = None
        for cfg in CONFIGS:
            tag = "%s_%d_%d" % (os.path.basename(scene).replace(".json", ""), cfg[0], cfg[1])
            path, err = render(a.fxraster, scene, cfg, os.path.join(a.out, tag), size)
            name = os.path.basename(scene)
            if path is None:
                lines.append("| %s | %d | %d | %d | refused: %s |||||||" % (name, cfg[0], cfg[1], plane_bits(*cfg), err[:80]))
                continue
            j = json.load(open(os.path.join(path, "report.json")))
            vs = j["errors_vs_double_reference"]["varyings"]
            frag = varyings(path)
            if base is None:
                base = frag
            diff = sum(1 for x, y in zip(frag, base) for u, w in zip(x, y) if u != w) if len(frag) == len(base) else -1
            texel = max(v["texels"]["max"] for v in vs) if vs else 0
            spot = ", ".join("%.3g" % v["exact_spot_ulp"]["max"] for v in vs)
            u, v = vs[0]["ulp"], vs[1]["ulp"] if len(vs) > 1 else vs[0]["ulp"]
            lines.append("| %s | %d | %d | %d | %.3g | %.3g | %.3g | %.3g | %s | %s of %d | %.3g |" % (
                name, cfg[0], cfg[1], plane_bits(*cfg), u["max"], u["p999"], v["max"], v["p999"], spot,
                diff if diff >= 0 else "(other count)", len(frag) * len(vs), texel))
    text = "\n".join(lines) + "\n"
    open(os.path.join(a.out, "interp_width.md"), "w").write(text)
    print(text)


if __name__ == "__main__":
    main()
