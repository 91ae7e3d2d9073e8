#!/bin/sh
# Feature-preserving coarsening sweep (issue 9): `curvetet shell` at epsilon
# 1% on every mesh of ../shared/data/good with a NAME.features.json, once with
# the features and once without. One line per run: chains, corners, faces
# before -> after, coarsening seconds, max distance / epsilon, max distance
# along features / epsilon and the feature check verdict (every corner a
# shell vertex at its input position, every chain covered end to end by
# coarse shell edges). The command itself exits 3 if the check fails.
# Usage: bench/features_sweep.sh [build dir] [extra shell args]; RUN_TIMEOUT=s per run (default 900, exit 124)
set -u
build=${1:-build}
extra=${2:-}
data=$(dirname "$0")/../../shared/data/good
out=$(mktemp -d)
printf '%-28s %-8s %6s %7s %8s %8s %9s %8s %8s %5s %4s\n' model features chains corners before after coarsen_s dist/eps feat/eps ok exit
for json in "$data"/*.features.json; do
  name=$(basename "$json" .features.json)
  mesh="$data/$name.off"
  for mode in with without; do
    args=""
    [ "$mode" = with ] && args="--features $json"
    timeout "${RUN_TIMEOUT:-900}" "$build"/app/curvetet -q shell "$mesh" $args -o "$out/$name" $extra
    code=$?
    if [ -e "$out/$name/report.json" ]; then
      /usr/bin/python3 - "$out/$name/report.json" "$name" "$mode" "$code" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
c = r["coarsen"]
f = r.get("features", {})
chk = f.get("check", {})
print("%-28s %-8s %6s %7s %8d %8d %9.2f %8.3f %8s %5s %4s" % (sys.argv[2], sys.argv[3],
      f.get("chains", "-") if sys.argv[3] == "with" else "-", f.get("corners", "-") if sys.argv[3] == "with" else "-",
      c["faces_before"], c["faces_after"], c["seconds"], c["max_distance"] / c["epsilon"],
      "%.3f" % (chk["max_distance"] / c["epsilon"]) if chk else "-", chk.get("ok", "-"), sys.argv[4]))
PY
    else
      printf '%-28s %-8s %56s %4s\n' "$name" "$mode" "(no report)" "$code"
    fi
    rm -rf "$out/$name"
  done
done
rm -rf "$out"
