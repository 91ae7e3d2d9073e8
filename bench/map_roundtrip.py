#!/usr/bin/python3
"""Round trip input -> output boundary -> input of a smooth field through the
map (`curvetet transfer`), against epsilon, on one model; prints a Markdown
table (boundary triangles, map build time, max / mean round-trip error in
units of |grad f| * epsilon, labels changed). Usage:
  bench/map_roundtrip.py [MODEL] [EPS ...]   (default examples/spot.off 0.02 0.01 0.005)
Needs build/app/curvetet (scripts/build.sh curvetet_cli)."""
import json
import os
import subprocess
import sys
import time

import numpy as np

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
exe = os.path.join(root, "build", "app", "curvetet")
model = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "examples", "spot.off")
epsilons = [float(e) for e in sys.argv[2:]] or [0.02, 0.01, 0.005]
work = os.path.join(root, "out", "map_roundtrip")
os.makedirs(work, exist_ok=True)

print(f"model {os.path.basename(model)}\n")
print("| eps | boundary tris | pipeline s | map s | max err / (abs(grad f) eps) | mean err / (abs(grad f) eps) | labels changed |")
print("|---:|---:|---:|---:|---:|---:|---:|")
for eps in epsilons:
    base = os.path.join(work, f"eps{eps}")
    start = time.time()
    subprocess.run([exe, "-q", model, "-o", base + ".msh", "--map", base + ".map", "--epsilon", str(eps),
                    "--report", base + ".json"], check=True)
    seconds = time.time() - start
    report = json.load(open(base + ".json"))
    # The field on the model's own vertices (OFF, as the map's input order).
    with open(model) as f:
        tokens = f.read().split()
    nv = int(tokens[1])
    verts = np.array(tokens[4:4 + 3 * nv], float).reshape(nv, 3)
    lo, hi = verts.min(axis=0), verts.max(axis=0)
    diag = np.linalg.norm(hi - lo)
    k = 2 * np.pi / diag  # one wavelength across the model
    x = verts - lo
    field = np.sin(k * x[:, 0]) * np.cos(k * x[:, 1]) + 0.5 * np.sin(k * x[:, 2])
    grad = 1.5 * k
    label = (x[:, 0] > 0.5 * (hi - lo)[0]).astype(int)
    with open(base + ".in.csv", "w") as f:
        f.write("f,label\n")
        for v, l in zip(field, label):
            f.write(f"{v!r},{l}\n")
    subprocess.run([exe, "-q", "transfer", base + ".map", base + ".in.csv", "-o", base + ".nodes.csv", "--to",
                    "boundary"], check=True)
    subprocess.run([exe, "-q", "transfer", base + ".map", base + ".nodes.csv", "-o", base + ".back.csv", "--to",
                    "input"], check=True)
    back = np.loadtxt(base + ".back.csv", delimiter=",", skiprows=1)
    err = np.abs(back[:, 3] - field)  # columns x, y, z, f, label
    scale = grad * eps * diag
    changed = int((back[:, 4] != label).sum())
    print(f"| {eps} | {report['assembly']['boundary_triangles']} | {seconds:.1f} | "
          f"{report['timings_s'].get('map', float('nan')):.2f} | {err.max() / scale:.3f} | {err.mean() / scale:.4f} | "
          f"{changed} / {nv} |")
