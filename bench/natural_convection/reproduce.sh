#!/bin/bash
# Regenerates docs/natural-convection.md's tables and docs/images/natural_convection_*.png from the
# current scenes (Morris walls; c0 = 3 at Ra = 1e4, 4 at 1e5 and 1e6):
#   * the deterministic scenes at 81^2 (Ra = 1e4, 1e5 to t = 50; 1e6 to t = 80 with frames every
#     0.5, so that the steady-state test's 20-unit slope resolves 1e-3 under its frame scatter),
#   * the stochastic Ra = 1e4 scene at N = 10 and N = 100 molecules per particle (t = 50), and
#     the stochastic Ra = 1e5 scene at N = 10 (t = 60) and Ra = 1e6 at N = 10 (t = 80),
#   * the convergence runs at Ra = 1e4: 41^2 (the reduced test scene) and 121^2 to t = 40,
#   * an ensemble of 4 realizations at N = 10 restarted from the N = 10 run's t = 30 frame
#     (8 time units each; restart_scene.py), to check that frames and realizations count alike,
#   * with FINE=1 also 121^2 at Ra = 1e5 (t = 50) and 1e6 (t = 80, frames every 0.5): about 45 and
#     60 CPU minutes more,
# then analyse.py (steady-state criterion, window averages, noise), table.py, convergence.py and
# plots.py. Runs go one thread each, two at a time; each run's CPU time is in OUT/NAME.time
# (/usr/bin/time -v). The runs already present in OUT are reused (delete a run's folder to redo it).
# About 90 CPU minutes in all without FINE (one core each; docs/natural-convection.md, "Cost").
#
#   [FINE=1] bench/natural_convection/reproduce.sh BIN_DIR OUT
set -euo pipefail
BIN=${1:?usage: reproduce.sh BIN_DIR OUT}
OUT=${2:?usage: reproduce.sh BIN_DIR OUT}
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
PY=/usr/bin/python3
mkdir -p "$OUT"
V=$($PY -c 'print(repr((1 / 81) ** 2))')

run() {  # name stop scene [args...]: sadr run to t = stop unless OUT/name exists
  local name=$1 stop=$2 scene=$3
  shift 3
  [ -d "$OUT/$name/frames" ] || [ -d "$OUT/$name/realization_0000" ] && return 0
  /usr/bin/time -v -o "$OUT/$name.time" \
    "$BIN/sadr" run "$scene" --fluid-threads 1 -q --stop-at "$stop" -o "$OUT/$name" "$@"
}
stochastic() {  # N: the --set arguments for N molecules per particle at theta = 1
  $PY -c "import sys; n = float(sys.argv[1]); v = $V
print('--set species[theta].boundaries[0].count=%d --set fluid.boussinesq.coefficient=%.16g --set fluid.boussinesq.reference=%.16g' % (round(n), v / n, 0.24 * n / v))" "$1"
}
EX=$ROOT/examples
run ra1e4 50 "$EX/natural_convection_ra1e4.yaml" & p1=$!
run st4_n10 50 "$EX/natural_convection_ra1e4_stochastic.yaml" & p2=$!
wait $p1 && wait $p2
run ra1e4_121 40 "$HERE/natural_convection_ra1e4_121.yaml" & p1=$!
run ra1e4_41 40 "$ROOT/tests/data/scenes/natural_convection_ra1e4_coarse.yaml" & p2=$!
wait $p1 && wait $p2
# the ensemble: 4 realizations restarted from the N = 10 run's frame at t = 30, t = 0-8
$PY "$HERE/restart_scene.py" "$OUT/st4_n10/frames/frame_000030.csv" "$EX/natural_convection_ra1e4_stochastic.yaml" \
  "$OUT/st4_n10_restart30" --end 8 --every 1
run st4_n10_ens 8 "$OUT/st4_n10_restart30/scene.yaml" -r 4 -j 1
run ra1e5 50 "$EX/natural_convection_ra1e5.yaml" & p1=$!
run ra1e6 80 "$EX/natural_convection_ra1e6.yaml" --set output.every=0.5 & p2=$!
wait $p1 && wait $p2
# shellcheck disable=SC2046
run st4_n100 50 "$EX/natural_convection_ra1e4_stochastic.yaml" $(stochastic 100) & p1=$!
run st5_n10 60 "$EX/natural_convection_ra1e5_stochastic.yaml" & p2=$!
wait $p1 && wait $p2
run st6_n10 80 "$EX/natural_convection_ra1e6_stochastic.yaml"
if [ "${FINE:-0}" = 1 ]; then
  run ra1e5_121 50 "$HERE/natural_convection_ra1e5_121.yaml" & p1=$!
  run ra1e6_121 80 "$HERE/natural_convection_ra1e6_121.yaml" --set output.every=0.5 & p2=$!
  wait $p1 && wait $p2
fi

A="$PY $HERE/analyse.py"
$A "$OUT/ra1e4" --ra 1e4 --json "$OUT/a4.json" > "$OUT/a4.txt" || true
$A "$OUT/ra1e5" --ra 1e5 --json "$OUT/a5.json" > "$OUT/a5.txt" || true
# Ra = 1e6: frames every 0.5 and a 20-unit slope window (the frame scatter of Nu needs them; docs);
# if it is not steady by t = 80 after all, averaged from t = 54 and the row says so
$A "$OUT/ra1e6" --ra 1e6 --rate-window 20 --json "$OUT/a6.json" > "$OUT/a6.txt" ||
  $A "$OUT/ra1e6" --ra 1e6 --rate-window 20 --from 54 --json "$OUT/a6.json" > "$OUT/a6.txt" || true
start() { $PY -c 'import json, sys; print(json.load(open(sys.argv[1]))["window"][0])' "$1"; }
# stochastic: the criterion cannot see through the per-frame noise; the deterministic run's t = 26 (docs)
$A "$OUT/st4_n10" --ra 1e4 --molecules 10 --from 26 --against "$OUT/ra1e4" --json "$OUT/s10.json" > "$OUT/s10.txt" || true
$A "$OUT/st4_n100" --ra 1e4 --molecules 100 --from 26 --against "$OUT/ra1e4" --json "$OUT/s100.json" > "$OUT/s100.txt" || true
$A "$OUT/st5_n10" --ra 1e5 --molecules 10 --from 32 --against "$OUT/ra1e5" --json "$OUT/s5_10.json" > "$OUT/s5_10.txt" || true
$A "$OUT/st6_n10" --ra 1e6 --molecules 10 --from "$(start "$OUT/a6.json")" --against "$OUT/ra1e6" --json "$OUT/s6_10.json" > "$OUT/s6_10.txt" || true
# the ensemble: frames 1-8 after the restart (t = 31-38 of the run it starts from)
$A "$OUT/st4_n10_ens" --ra 1e4 --molecules 10 --from 1 --json "$OUT/s10_ens.json" > "$OUT/s10_ens.txt" || true
# one realization over the same 8 time units, for comparison
$A "$OUT/st4_n10" --ra 1e4 --molecules 10 --from 31 --window 7 --json "$OUT/s10_31.json" > "$OUT/s10_31.txt" || true
# errors and noise against realizations (the ensemble's first 1, 2, 4) and frames (the long run's
# first 5, 10, 25 from t = 26)
E=$OUT/st4_n10_ens
$A "$E/realization_0000" --ra 1e4 --molecules 10 --from 1 --json "$OUT/s10_R1.json" > /dev/null || true
$A "$E/realization_0000" "$E/realization_0001" --ra 1e4 --molecules 10 --from 1 --json "$OUT/s10_R2.json" > /dev/null || true
for w in 4 9; do
  $A "$OUT/st4_n10" --ra 1e4 --molecules 10 --from 26 --window $w --json "$OUT/s10_F$((w + 1)).json" > /dev/null || true
done
# convergence at Ra = 1e4: the three resolutions over the same window t = 26-40
$A "$OUT/ra1e4_41" --ra 1e4 --h "$($PY -c 'print(3/41)')" --dx "$($PY -c 'print(1/41)')" --from 26 --window 14 \
  --json "$OUT/c41.json" > "$OUT/c41.txt" || true
$A "$OUT/ra1e4" --ra 1e4 --from 26 --window 14 --json "$OUT/c81.json" > "$OUT/c81.txt" || true
$A "$OUT/ra1e4_121" --ra 1e4 --h "$($PY -c 'print(3/121)')" --dx "$($PY -c 'print(1/121)')" --from 26 --window 14 \
  --json "$OUT/c121.json" > "$OUT/c121.txt" || true

$PY "$HERE/table.py" "$OUT"/a4.json "$OUT"/s10.json "$OUT"/s100.json \
  "$OUT"/s10_ens.json="8 frames each, restarted from the N = 10 run at t = 30" "$OUT"/a5.json "$OUT"/s5_10.json \
  "$OUT"/a6.json "$OUT"/s6_10.json | tee "$OUT/table.md"
$PY "$HERE/stochastic_table.py" "$OUT"/a4.json="deterministic" "$OUT"/s10_F5.json="N = 10, 5 frames" \
  "$OUT"/s10_F10.json="N = 10, 10 frames" "$OUT"/s10.json="N = 10, 25 frames" "$OUT"/s100.json="N = 100, 25 frames" \
  "$OUT"/s10_R1.json="N = 10, restarted at t = 30, R = 1" "$OUT"/s10_R2.json="N = 10, restarted, R = 2" \
  "$OUT"/s10_ens.json="N = 10, restarted, R = 4" "$OUT"/s10_31.json="N = 10, the long run over t = 31-38" \
  "$OUT"/a5.json="Ra = 1e5 deterministic" "$OUT"/s5_10.json="Ra = 1e5, N = 10" \
  "$OUT"/a6.json="Ra = 1e6 deterministic" "$OUT"/s6_10.json="Ra = 1e6, N = 10" | tee "$OUT/stochastic.md"
names="ra1e4 st4_n10 st4_n100 st4_n10_ens ra1e5 st5_n10 ra1e6 st6_n10 ra1e4_41 ra1e4_121"
[ "${FINE:-0}" = 1 ] && names="$names ra1e5_121 ra1e6_121"
# shellcheck disable=SC2086
$PY "$HERE/cost_table.py" "$OUT" $names --relative-to ra1e4 | tee "$OUT/cost.md"
$PY "$HERE/convergence.py" "$OUT"/c41.json=41 "$OUT"/c81.json=81 "$OUT"/c121.json=121 | tee "$OUT/convergence.md"
if [ "${FINE:-0}" = 1 ]; then  # 81^2 against 121^2 over the 81^2 runs' windows
  H121=$($PY -c 'print(3/121)') DX121=$($PY -c 'print(1/121)')
  $A "$OUT/ra1e5_121" --ra 1e5 --h "$H121" --dx "$DX121" --from "$(start "$OUT/a5.json")" \
    --json "$OUT/c5_121.json" > "$OUT/c5_121.txt" || true
  $A "$OUT/ra1e6_121" --ra 1e6 --h "$H121" --dx "$DX121" --rate-window 20 --from "$(start "$OUT/a6.json")" \
    --json "$OUT/c6_121.json" > "$OUT/c6_121.txt" || true
  $PY "$HERE/convergence.py" "$OUT"/a5.json=81 "$OUT"/c5_121.json=121 | tee "$OUT/convergence_ra1e5.md"
  $PY "$HERE/convergence.py" "$OUT"/a6.json=81 "$OUT"/c6_121.json=121 | tee "$OUT/convergence_ra1e6.md"
fi
last() { ls "$OUT/$1"/frames/frame_*.csv | tail -1; }
$PY "$HERE/plots.py" --analysis "$OUT"/a4.json "$OUT"/a5.json "$OUT"/a6.json \
  --frames "$(last ra1e4)" "$(last ra1e5)" "$(last ra1e6)" --out "$ROOT/docs/images"
