#!/bin/bash
# Round 7 interleaved runs (issue #14 behaviour-preserving redesign): old = session start
# 263b868 (release build in /work/baseline), new = main (release build in /work/main).
# Run with nothing else on the machine: bash bench/results/round7_interleaved.sh > out.txt
set -u
OLD=/work/baseline/build/release
NEW=/work/main/build/release
S=/work/main/bench
echo "# start $(date -u +%H:%M:%S) load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "## fluid_bench --case D N threads steps (particle-steps per wall-s / per CPU-s)"
for r in 1 2 3; do
  for c in "2 10000 1 400" "3 10000 1 60" "2 10000 2 400"; do
    echo "old $c: $($OLD/bench/fluid/fluid_bench --case $c 2>&1 | tail -1)"
    echo "new $c: $($NEW/bench/fluid/fluid_bench --case $c 2>&1 | tail -1)"
  done
done
echo "## fluid_tdpd_bench (OMP_NUM_THREADS=1)"
for r in 1 2; do
  echo "old: $(OMP_NUM_THREADS=1 $OLD/bench/fluid_tdpd/fluid_tdpd_bench /tmp/r7/tdpd-old-$r.json 2>&1 | tail -1)"
  echo "new: $(OMP_NUM_THREADS=1 $NEW/bench/fluid_tdpd/fluid_tdpd_bench /tmp/r7/tdpd-new-$r.json 2>&1 | tail -1)"
done
echo "## ssa_bench a / b / d"
for r in 1 2; do
  for s in a b d; do
    echo "old $s: $(OMP_WAIT_POLICY=passive $OLD/bench/ssa/ssa_bench $s 2>&1 | tail -1)"
    echo "new $s: $(OMP_WAIT_POLICY=passive $NEW/bench/ssa/ssa_bench $s 2>&1 | tail -1)"
  done
done
echo "## coupled step 1e4 (ms per coupling step)"
for r in 1 2 3; do
  /usr/bin/python3 $S/coupled/coupled_step.py --sadr $OLD/bin/sadr --sizes 10000 --steps 40 --out /tmp/r7/c-old-$r 2>&1 | grep "^N=" | sed "s|^|old |"
  /usr/bin/python3 $S/coupled/coupled_step.py --sadr $NEW/bin/sadr --sizes 10000 --steps 40 --out /tmp/r7/c-new-$r 2>&1 | grep "^N=" | sed "s|^|new |"
done
echo "# end $(date -u +%H:%M:%S) load: $(cut -d' ' -f1-3 /proc/loadavg)"
