#!/bin/sh
# Full pipeline on the CAD models with features (issue 9 acceptance):
#   curvetet MESH -o OUT.msh --features MESH.features.json --order 4 --epsilon 0.01 --report R.json --map OUT.map
# and, with MODE=both, the same without --features. Per run it keeps the report, the
# time output and the verdicts of tests/pipeline/feature_map_check.py (through the map)
# and tests/pipeline/gmsh_pipeline_check.py (Gmsh Jacobians + distance) in OUT_DIR.
# Summarize with bench/features_pipeline_table.py OUT_DIR.
# Usage: bench/features_pipeline_sweep.sh CURVETET_BINARY OUT_DIR [models...]
#   MODE=with|without|both (default with); RUN_TIMEOUT seconds per run (default 1800)
set -u
bin=$1
out=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
data=$here/../../shared/data/good
[ -d "$data" ] || data=/work/shared/data/good
mkdir -p "$out"
models=${*:-"cad_boolean cad_fillet3 cad_freecad_MSOP_10 cad_t20_component8 abc_00000050_part2 cad_t16_spherical_cavities cad_thicksolid_thin"}
modes=${MODE:-with}
[ "$modes" = both ] && modes="with without"
for name in $models; do
  for mode in $modes; do
    base=$out/${name}_$mode
    args=""
    [ "$mode" = with ] && args="--features $data/$name.features.json"
    uptime > "$base.load"
    /usr/bin/time -f "%e %M" -o "$base.time" timeout "${RUN_TIMEOUT:-1800}" "$bin" -q "$data/$name.off" \
      -o "$base.msh" --order 4 --epsilon 0.01 --report "$base.report.json" --map "$base.map" $args > "$base.log" 2>&1
    echo $? > "$base.exit"
    uptime >> "$base.load"
    if [ -e "$base.msh" ]; then
      /usr/bin/python3 "$here/../tests/pipeline/gmsh_pipeline_check.py" "$base.msh" "$data/$name.off" 0.01 > "$base.gmsh" 2>&1
      echo "exit $?" >> "$base.gmsh"
      if [ "$mode" = with ]; then
        /usr/bin/python3 "$here/../tests/pipeline/feature_map_check.py" "$base.msh" "$base.map" \
          "$data/$name.features.json" > "$base.features" 2>&1
        echo "exit $?" >> "$base.features"
      fi
    fi
    echo "$name $mode exit $(cat "$base.exit") $(cat "$base.time" | tail -1)"
  done
done
