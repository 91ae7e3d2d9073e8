#!/bin/sh
# Poisson L2 error against epsilon (issue 10, paper §6.4): regenerates the two
# tables of the README's "Example 1, Poisson". Writes a dense ellipsoid
# (radii 1, 0.7, 0.5; an octahedron subdivided LEVELS times, 8 * 4^LEVELS
# faces) with bench/make_ellipsoid.py, runs the main command on it at each
# epsilon (P = 4, --no-optimize), first with the flat middle (--flat-middle),
# then with the default curved middle, then `curvetet poisson` (P2 unknowns,
# Franke solution), and prints one markdown row per run: epsilon, the
# coarsening's max distance (what epsilon bounds, x bbox diagonal), tets,
# boundary triangles, the mean boundary edge and the volume-weighted mean
# longest tet edge (straight corner edges, via meshio), dofs, L2 error,
# relative L2 error, seconds of the meshing run. A run whose verification
# fails (exit 5) prints its exit code and the verified distances instead.
#
# Usage: bench/poisson_epsilon.sh [build dir]
# Environment: LEVELS (default 6: 32768 faces), MIDDLES (default
# "flat curved"), FLAT_EPSILONS (default "0.02 0.01 0.005 0.0025"),
# CURVED_EPSILONS (default "0.01 0.002 0.001 0.0005 0.00025"), THREADS
# (default 0 = all cores), KEEP=DIR keeps the meshes in DIR.
set -u
build=${1:-build}
here=$(dirname "$0")
levels=${LEVELS:-6}
out=${KEEP:-$(mktemp -d)}
mkdir -p "$out"
input="$out/ellipsoid$levels.off"
/usr/bin/python3 "$here/make_ellipsoid.py" "$levels" "$input" || exit 1
for middle in ${MIDDLES:-flat curved}; do
if [ "$middle" = flat ]; then
  extra="--flat-middle"
  epsilons=${FLAT_EPSILONS:-"0.02 0.01 0.005 0.0025"}
else
  extra=""
  epsilons=${CURVED_EPSILONS:-"0.01 0.002 0.001 0.0005 0.00025"}
fi
echo
echo "input: $input ($((8 * (1 << (2 * levels)))) faces), middle: $middle, threads: ${THREADS:-0}"
echo
echo "| ε | coarsening distance | tets | boundary triangles | boundary edge | tet size | dofs | L2 error | relative L2 error | mesh s |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for eps in $epsilons; do
  base="$out/${middle}_e$eps"
  start=$(date +%s.%N)
  "$build"/app/curvetet -q --threads "${THREADS:-0}" "$input" -o "$base.msh" --epsilon "$eps" --no-optimize \
    --report "$base.report.json" $extra 2> "$base.log"
  code=$?
  end=$(date +%s.%N)
  if [ $code -eq 0 ]; then
    "$build"/app/curvetet -q poisson "$base.msh" --json > "$base.poisson.json" || code=$?
  fi
  /usr/bin/python3 - "$base" "$eps" "$code" "$start" "$end" <<'PY'
import json, sys
base, eps, code, start, end = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
pct = f"{100 * eps:g} %"
try:
    r = json.load(open(base + ".report.json"))
except (OSError, ValueError):
    print(f"| {pct} | exit {code} (no report) | | | | | | | | |")
    sys.exit()
dist = r["coarsen"]["max_distance_relative"]
if code != 0:
    d = r["verification"]["distance"]
    print(f"| {pct} | {dist:.2g}; exit {code}: verified input->boundary {d['input_to_boundary_max']:.3g}, "
          f"boundary->input {d['boundary_to_input_max']:.3g} (x diagonal) | | | | | | | | |")
    sys.exit()
p = json.load(open(base + ".poisson.json"))["poisson"]
import contextlib, io, meshio, numpy as np
with contextlib.redirect_stdout(io.StringIO()):  # meshio prints notes on stdout
    m = meshio.read(base + ".msh")
x = m.points
tets = next(c.data for c in m.cells if c.type.startswith("tetra"))[:, :4]
tris = next(c.data for c in m.cells if c.type.startswith("triangle"))[:, :3]
longest = np.max([np.linalg.norm(x[tets[:, i]] - x[tets[:, j]], axis=1) for i in range(4) for j in range(i + 1, 4)], 0)
a, b, c = (x[tets[:, k]] - x[tets[:, 0]] for k in (1, 2, 3))
volume = np.abs(np.einsum("ij,ij->i", a, np.cross(b, c)))
edge = np.mean([np.linalg.norm(x[tris[:, i]] - x[tris[:, (i + 1) % 3]], axis=1) for i in range(3)])
print(f"| {pct} | {dist:.2g} | {p['tets']} | {r['assembly']['boundary_triangles']} | {edge:.3f} | "
      f"{np.average(longest, weights=volume):.3f} | {p['dofs']} | {p['l2_error']:.3g} | {p['l2_relative_error']:.3g} | "
      f"{end - start:.0f} |")
PY
done
done
[ -n "${KEEP:-}" ] || rm -rf "$out"
