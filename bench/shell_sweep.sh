#!/bin/sh
# Full sweep of `curvetet shell --debug-invariants` over every good mesh of
# ../shared/data (the unit test runs a subset). Prints one line per model:
# name, exit code, wall seconds, faces, singular vertices, min thickness /
# bbox diagonal, vertices at target. Usage: bench/shell_sweep.sh [build dir]
set -u
build=${1:-build}
data=$(dirname "$0")/../../shared/data/good
out=$(mktemp -d)
printf '%-36s %4s %8s %7s %5s %12s %s\n' model exit seconds faces sing min_thick/diag at_target
for mesh in "$data"/*.off; do
  name=$(basename "$mesh" .off)
  start=$(date +%s.%N)
  "$build"/app/curvetet -q shell "$mesh" -o "$out/$name" --debug-invariants
  code=$?
  end=$(date +%s.%N)
  if [ $code -eq 0 ]; then
    /usr/bin/python3 - "$out/$name/report.json" "$name" "$code" "$start" "$end" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); s = r["shell"]; d = r["input"]["bbox_diagonal"]
print("%-36s %4s %8.2f %7d %5d %12.3g %d/%d" % (sys.argv[2], sys.argv[3], float(sys.argv[5]) - float(sys.argv[4]),
      s["input_faces"], s["singular_vertices"], s["thickness"]["min"] / d, s["vertices_at_target"], s["input_vertices"]))
PY
  else
    printf '%-36s %4s\n' "$name" "$code"
  fi
done
rm -rf "$out"
