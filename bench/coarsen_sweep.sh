#!/bin/sh
# Coarsening sweep: `curvetet shell` (with coarsening, epsilon 1%) over every
# good mesh of ../shared/data without a features file (the unit tests run a
# subset). One line per model: exit code, wall seconds (build + coarsen +
# write), coarsening seconds, faces before -> after, reduction, max distance /
# epsilon. Optional: DEBUG=1 adds --debug-invariants (global check after every
# pass; slow), THREADS=n. Usage: bench/coarsen_sweep.sh [build dir]
set -u
build=${1:-build}
data=$(dirname "$0")/../../shared/data/good
out=$(mktemp -d)
extra=""
[ "${DEBUG:-0}" = 1 ] && extra="--debug-invariants"
printf '%-36s %4s %8s %8s %8s %8s %7s %8s\n' model exit wall_s coarsen_s before after ratio dist/eps
for mesh in "$data"/*.off; do
  name=$(basename "$mesh" .off)
  [ -e "$data/$name.features.json" ] && continue
  start=$(date +%s.%N)
  "$build"/app/curvetet -q --threads "${THREADS:-0}" shell "$mesh" -o "$out/$name" $extra
  code=$?
  end=$(date +%s.%N)
  if [ $code -eq 0 ]; then
    /usr/bin/python3 - "$out/$name/report.json" "$name" "$code" "$start" "$end" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))["coarsen"]
print("%-36s %4s %8.2f %8.2f %8d %8d %7.2f %8.3f" % (sys.argv[2], sys.argv[3], float(sys.argv[5]) - float(sys.argv[4]),
      c["seconds"], c["faces_before"], c["faces_after"], c["faces_before"] / max(1, c["faces_after"]),
      c["max_distance"] / c["epsilon"]))
PY
  else
    printf '%-36s %4s\n' "$name" "$code"
  fi
  rm -rf "$out/$name"
done
rm -rf "$out"
