#!/bin/bash
# Round 8 interleaved runs (issue #14 step 4: SdpdBackend split into units, one SlabScheduler in
# the fluid core shared by the SDPD bulk path and tDPD): old = session start 6ab505a (release
# build in /work/baseline), new = main (release build in /work/main:
#   cmake --preset release && cmake --build --preset release -j2 --target fluid_bench fluid_tdpd_bench).
# Run with nothing else on the machine: bash bench/results/sdpd_slab_split_interleaved.sh > out.txt
# Ratios to state: new/old particle-steps per CPU-s (1 thread) and per wall-s (2 threads).
set -u
OLD=/work/baseline/build/release
NEW=/work/main/build/release
mkdir -p /tmp/r8
echo "# start $(date -u +%H:%M:%S) load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "## fluid_bench --case D N threads steps (SDPD bulk path: half pairs on the SlabScheduler)"
for r in 1 2 3; do
  for c in "2 10000 1 400" "3 10000 1 60" "2 10000 2 400" "3 10000 2 60"; do
    echo "old $c: $($OLD/bench/fluid/fluid_bench --case $c 2>&1 | tail -1)"
    echo "new $c: $($NEW/bench/fluid/fluid_bench --case $c 2>&1 | tail -1)"
  done
done
echo "## fluid_tdpd_bench --small (1e4; 1, 4, 25 species), 1 and 2 threads (tDPD on the SlabScheduler)"
for r in 1 2 3; do
  for t in 1 2; do
    echo "old T=$t: $(OMP_NUM_THREADS=$t $OLD/bench/fluid_tdpd/fluid_tdpd_bench --small /tmp/r8/tdpd-old-$t-$r.json 2>&1 | tr '\n' ' ')"
    echo "new T=$t: $(OMP_NUM_THREADS=$t $NEW/bench/fluid_tdpd/fluid_tdpd_bench --small /tmp/r8/tdpd-new-$t-$r.json 2>&1 | tr '\n' ' ')"
  done
done
echo "## fluid_tdpd_bench --large (1e5), 2 threads"
for r in 1 2; do
  echo "old: $(OMP_NUM_THREADS=2 $OLD/bench/fluid_tdpd/fluid_tdpd_bench --large /tmp/r8/tdpdL-old-$r.json 2>&1 | tr '\n' ' ')"
  echo "new: $(OMP_NUM_THREADS=2 $NEW/bench/fluid_tdpd/fluid_tdpd_bench --large /tmp/r8/tdpdL-new-$r.json 2>&1 | tr '\n' ' ')"
done
echo "# end $(date -u +%H:%M:%S) load: $(cut -d' ' -f1-3 /proc/loadavg)"
