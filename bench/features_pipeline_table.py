#!/usr/bin/python3
"""Markdown table of a bench/features_pipeline_sweep.sh output directory.

Usage: /usr/bin/python3 bench/features_pipeline_table.py OUT_DIR
One row per run (NAME_with / NAME_without): chains, corners, coarse feature
edges, tets, boundary triangles, wall seconds (/usr/bin/time), of which the
curved optimization, max AMIPS and min scaled Jacobian after the curved
optimization, Gmsh's verdict (tests/pipeline/gmsh_pipeline_check.py) and the
feature check through the map (tests/pipeline/feature_map_check.py).
"""
import glob
import json
import os
import re
import sys


def read(path):
    return open(path).read() if os.path.exists(path) else ""


def main():
    out = sys.argv[1]
    print("| model | features | chains | corners | coarse feature edges | tets | boundary faces | time s "
          "(optimization) | max AMIPS | min SJ | Gmsh | corners ok (map) | feature vertices off the curves (map) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|")
    for rep in sorted(glob.glob(os.path.join(out, "*.report.json"))):
        base = rep[: -len(".report.json")]
        name, mode = os.path.basename(base).rsplit("_", 1)
        r = json.load(open(rep))
        f = r.get("features", {})
        opt = r.get("curved_optimization", {})
        wall = read(base + ".time").split()
        gm = read(base + ".gmsh")
        fc = read(base + ".features")
        m = re.search(r"corners: (\d+ of \d+) ok; feature vertices off the output curves: (\d+ of \d+)", fc)
        print(f"| {name} | {mode} | {f.get('chains', '-')} | {f.get('corners', '-')} | {f.get('coarse_edges', '-')} | "
              f"{r['verification'].get('tets', '-')} | {r['assembly']['boundary_triangles']} | "
              f"{wall[0] if wall else '-'} ({r['timings_s'].get('curved optimization', 0):.0f}) | "
              f"{opt.get('max_amips_after', float('nan')):.4g} | {opt.get('min_scaled_jacobian_after', float('nan')):.3g} | "
              f"{'ok' if 'exit 0' in gm else ('FAIL' if gm else '-')} | {m.group(1) if m else '-'} | "
              f"{m.group(2) if m else '-'} |")


if __name__ == "__main__":
    main()
