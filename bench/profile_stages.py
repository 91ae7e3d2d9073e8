#!/usr/bin/env python3
"""Where the main job's time goes: per stage, and inside the coarsening per
invariant (issue 28, docs/performance.md).

usage: /usr/bin/python3 bench/profile_stages.py [--bin BIN] [--epsilon E ...]
           [--json OUT.json] [--timeout S] MESH...

Runs `curvetet MESH --epsilon E --report R.json` once per model and epsilon
(default epsilon 0.01 and 0.001) under /usr/bin/time, and prints two
Markdown tables: wall and CPU time with the report's stage times
(`timings_s`), and the coarsening's check CPU seconds per invariant
(`coarsen.check_cpu_seconds`, summed over both threads, so they add up to
more than the stage's wall time). Wall times on a shared machine carry
noise; compare shares, or runs made one after the other.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

STAGES = ["shell", "coarsen", "assemble", "curved optimization", "verify"]
CHECKS = ["proposals", "slab_quality", "prism_positivity", "coverage", "section", "curved_fit", "distance",
          "surface_distance", "curved_quality", "caps_intersection"]


def run(binary, mesh, eps, timeout, workdir):
    base = os.path.join(workdir, f"{os.path.basename(mesh)}.{eps}")
    cmd = ["/usr/bin/time", "-f", "%e %U %S %M", "-o", base + ".time", binary, mesh, "-o", base + ".msh",
           "--epsilon", str(eps), "--report", base + ".json"]
    try:
        rc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=timeout).returncode
    except subprocess.TimeoutExpired:
        return {"model": os.path.basename(mesh), "epsilon": eps, "exit": "timeout"}
    out = {"model": os.path.basename(mesh), "epsilon": eps, "exit": rc}
    if rc != 0:
        return out
    wall, user, sys_, rss = open(base + ".time").read().split()[-4:]
    report = json.load(open(base + ".json"))
    out.update(wall=float(wall), cpu=float(user) + float(sys_), peak_mib=int(rss) / 1024,
               stages=report["timings_s"], checks=report["coarsen"].get("check_cpu_seconds", {}),
               tets=report["verification"]["tets"], boundary=report["verification"]["boundary_triangles"])
    return out


def tables(rows):
    ok = [r for r in rows if r.get("exit") == 0]
    lines = ["| model | ε | tets | wall s | CPU s | " + " | ".join(STAGES) + " |",
             "|---|---:|---:|---:|---:|" + "---:|" * len(STAGES)]
    for r in ok:
        lines.append(f"| {r['model']} | {r['epsilon']:g} | {r['tets']} | {r['wall']:.1f} | {r['cpu']:.1f} | " +
                     " | ".join(f"{r['stages'].get(s, 0):.1f}" for s in STAGES) + " |")
    lines += ["", "| model | ε | " + " | ".join(c.replace("_", " ") for c in CHECKS) + " |",
              "|---|---:|" + "---:|" * len(CHECKS)]
    for r in ok:
        lines.append(f"| {r['model']} | {r['epsilon']:g} | " +
                     " | ".join(f"{r['checks'].get(c, 0):.1f}" for c in CHECKS) + " |")
    for r in rows:
        if r.get("exit") != 0:
            lines.append(f"\n{r['model']} at ε = {r['epsilon']:g}: exit {r['exit']}")
    return "\n".join(lines)


def main():
    a = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    a.add_argument("--bin", default="build/app/curvetet")
    a.add_argument("--epsilon", type=float, action="append")
    a.add_argument("--json")
    a.add_argument("--timeout", type=float, default=3600)
    a.add_argument("meshes", nargs="+")
    args = a.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as workdir:
        for mesh in args.meshes:
            for eps in args.epsilon or [0.01, 0.001]:
                rows.append(run(args.bin, mesh, eps, args.timeout, workdir))
                print(f"{rows[-1]['model']} {eps}: exit {rows[-1]['exit']}", file=sys.stderr, flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    print(tables(rows))


if __name__ == "__main__":
    main()
