#!/bin/sh
# Curved vs flat middle (issue 7): `curvetet shell --order 4` (middle of
# degree 3 fitted and certified in every operation) against `--order 2` (flat
# middle), epsilon 1%, over every good mesh of ../shared/data without a
# features file. One line per model: faces after coarsening (flat, curved),
# curved/flat, curved coarsening seconds (sum of passes), CPU share of that
# time spent in the least-squares fit and in slab certificates, max distance
# / epsilon on the curved surface, exit codes. DEBUG=1 runs the curved shell
# with --debug-invariants (global invariants + certified slabs + map after
# every pass; slower, pass times exclude the checks). THREADS=n. MODELS="a b"
# restricts the run to those models (file names without .off).
# Usage: bench/curved_shell_sweep.sh [build dir]
set -u
build=${1:-build}
data=$(dirname "$0")/../../shared/data/good
out=$(mktemp -d)
extra=""
[ "${DEBUG:-0}" = 1 ] && extra="--debug-invariants"
echo '| model | input faces | flat | curved | curved/flat | coarsen s | fit % | certificate % | dist/eps | exit flat/curved |'
echo '|---|---|---|---|---|---|---|---|---|---|'
for mesh in "$data"/*.off; do
  name=$(basename "$mesh" .off)
  [ -e "$data/$name.features.json" ] && continue
  if [ -n "${MODELS:-}" ]; then
    case " $MODELS " in *" $name "*) ;; *) continue ;; esac
  fi
  "$build"/app/curvetet -q --threads "${THREADS:-0}" shell "$mesh" -o "$out/$name.flat" --order 2
  cf=$?
  "$build"/app/curvetet -q --threads "${THREADS:-0}" shell "$mesh" -o "$out/$name.curved" --order 4 $extra
  cc=$?
  /usr/bin/python3 - "$out/$name" "$name" "$cf" "$cc" <<'PY'
import json, os, sys
base, name, cf, cc = sys.argv[1:5]
def load(tag):
    p = base + "." + tag + "/report.json"
    return json.load(open(p))["coarsen"] if os.path.exists(p) else None
f, c = load("flat"), load("curved")
if not (f and c):
    print("| %-34s | %6s | %6s | %6s | %9s | %6s | %6s | %6s | %8s | %s/%s |" % (name, "", "", "", "", "", "", "", "", cf, cc))
    sys.exit(0)
secs = sum(p["seconds"] for p in c["passes"])
cm = c.get("curved_middle", {})
fit = cm.get("fit_cpu_seconds", 0); cert = cm.get("certificate_cpu_seconds", 0)
# CPU shares are relative to the summed pass wall time x threads used (1 or 2).
cpu = secs * max(1, int(os.environ.get("THREADS", "0") or 0) or os.cpu_count())
print("| %-34s | %6d | %6d | %6d | %9.2f | %8.1f | %5.0f%% | %5.0f%% | %8.3f | %s/%s |" % (
    name, c["faces_before"], f["faces_after"], c["faces_after"], c["faces_after"] / max(1, f["faces_after"]),
    secs, 100 * fit / cpu, 100 * cert / cpu, c["max_distance"] / c["epsilon"], cf, cc))
PY
  rm -rf "$out/$name.flat" "$out/$name.curved"
done
rm -rf "$out"
