#!/bin/bash
# Round 9 interleaved runs, issue #14 closing measurement: old = 263b868 (the commit the issue's
# file:line references are "as of", before any of the redesign; release build in /work/old263:
#   git worktree add --detach /work/old263 263b868 && cmake --preset release && cmake --build --preset release -j2),
# new = main (release build in /work/main: cmake --preset release && cmake --build --preset release -j2).
# Run with nothing else on the machine: bash bench/results/round9_interleaved.sh > out.txt
# Ratios to state: new/old per pair (fluid: particle-steps per CPU-s with 1 thread, per wall-s
# with 2; tdpd: particle-steps per CPU-s; ssa: ns per event; coupled: ms per coupling step).
set -u
OLD=${OLD:-/work/old263/build/release}
NEW=${NEW:-/work/main/build/release}
S=$(cd "$(dirname "$0")/.." && pwd)
T=/tmp/r9
mkdir -p $T
echo "# start $(date -u +%H:%M:%S) load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "## fluid_bench --case D N threads steps"
for r in 1 2 3; do
  for c in "2 10000 1 400" "3 10000 1 60" "2 10000 2 400" "3 10000 2 60"; do
    echo "old $c: $($OLD/bench/fluid/fluid_bench --case $c 2>&1 | tail -1)"
    echo "new $c: $($NEW/bench/fluid/fluid_bench --case $c 2>&1 | tail -1)"
  done
done
echo "## fluid_tdpd_bench --small (1e4; 1, 4, 25 species), OMP_NUM_THREADS=1"
for r in 1 2; do
  echo "old: $(OMP_NUM_THREADS=1 $OLD/bench/fluid_tdpd/fluid_tdpd_bench --small $T/tdpd-old-$r.json 2>&1 | tr "\n" " ")"
  echo "new: $(OMP_NUM_THREADS=1 $NEW/bench/fluid_tdpd/fluid_tdpd_bench --small $T/tdpd-new-$r.json 2>&1 | tr "\n" " ")"
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
  /usr/bin/python3 $S/coupled/coupled_step.py --sadr $OLD/bin/sadr --sizes 10000 --steps 40 --out $T/c-old-$r 2>&1 | grep "^N=" | sed "s|^|old |"
  /usr/bin/python3 $S/coupled/coupled_step.py --sadr $NEW/bin/sadr --sizes 10000 --steps 40 --out $T/c-new-$r 2>&1 | grep "^N=" | sed "s|^|new |"
done
echo "# end $(date -u +%H:%M:%S) load: $(cut -d' ' -f1-3 /proc/loadavg)"
