#!/bin/bash
# Round 10 (#14): is round 9's processes-mode coupled-step ratio (new/old 1.11 at the median of
# 7 pairs) real? old = 263b868 (before the redesign), new = a785c0f (main); release builds of
# sadr, fluid_service and ssa_service:
#   git worktree add --detach /work/old263 263b868 && cd /work/old263 && cmake --preset release \
#     && cmake --build --preset release -j2 --target sadr fluid_service ssa_service
# Usage: bash bench/results/round10_processes.sh > out.txt   (a loaded machine is fine for parts
# 1-2, which count; part 3 times interleaved A/B/B/A runs, so that A/A spreads sit beside A/B).
set -u
OLD=${OLD:-/work/old263/build/release}
NEW=${NEW:-/work/wt/procs/build/release}
ROUNDS=${ROUNDS:-20}
CPU_ROUNDS=${CPU_ROUNDS:-12}
PARTS=${PARTS:-1 2 3 4}  # e.g. PARTS=1 to redo the counts only
has() { [[ " $PARTS " == *" $1 "* ]]; }
S=$(cd "$(dirname "$0")/.." && pwd)
T=${T:-/tmp/r10}
PY=/usr/bin/python3
mkdir -p $T
load() { echo "# $1 $(date -u +%H:%M:%S) uptime: $(uptime | sed 's/.*load/load/')"; }
load start

has 1 && echo "## 1. per process per coupling step: instructions and simulated cache misses (callgrind --cache-sim=yes), runs of 4 and 12 steps"
has 1 && for b in old:$OLD new:$NEW; do
  nice -n 10 $PY $S/coupled/processes_probe.py --sadr ${b#*:}/bin/sadr --steps 4 12 --wrap callgrind-cache \
    --label ${b%%:*} --work $T/cg-${b%%:*}
  # sadr under valgrind: OMP_WAIT_POLICY set beforehand (as sadr sets it), so it does not re-exec itself
  nice -n 10 $PY $S/coupled/processes_probe.py --sadr ${b#*:}/bin/sadr --steps 4 12 --wrap callgrind-sadr \
    --env OMP_WAIT_POLICY=passive --label ${b%%:*} --work $T/cgs-${b%%:*}
done > $T/callgrind.json
has 2 && echo "## 2. per process per coupling step: system calls (strace -f -c), runs of 10 and 40 steps"
has 2 && for b in old:$OLD new:$NEW; do
  nice -n 10 $PY $S/coupled/processes_probe.py --sadr ${b#*:}/bin/sadr --steps 10 40 --wrap strace \
    --label ${b%%:*} --work $T/st-${b%%:*}
done > $T/strace.json
has 2 && load "after 1-2"
has 3 && echo "## 3. coupled_step.py --sizes 10000 --steps 40, $ROUNDS rounds of old new new old per variant"
# variants: the processes and embedded modes of round 9 (overlap on: auto with 2 cores), and the
# processes mode with --no-overlap (the SSA stage never runs beside the fluid stage)
has 3 && for r in $(seq $ROUNDS); do
  for v in processes embedded processes-no-overlap; do
    case $v in
      processes) args="--modes processes" ;;
      embedded) args="--modes embedded" ;;
      processes-no-overlap) args="--modes processes --extra=--no-overlap" ;;
    esac
    for b in old:$OLD new:$NEW new:$NEW old:$OLD; do
      nice -n 10 $PY $S/coupled/coupled_step.py --sadr ${b#*:}/bin/sadr --sizes 10000 --steps 40 \
        $args --out $T/cs 2>&1 | grep "^N=" | sed "s|^|${b%%:*} r$r $v |"
    done
  done
done > $T/coupled.txt
has 3 && load "after 3"
has 4 && echo "## 4. per process CPU per coupling step (wait4 rusage; runs of 10 and 40 steps), $CPU_ROUNDS rounds old new"
has 4 && for r in $(seq $CPU_ROUNDS); do
  for b in old:$OLD new:$NEW; do
    nice -n 10 $PY $S/coupled/processes_probe.py --sadr ${b#*:}/bin/sadr --steps 10 40 \
      --label ${b%%:*} --work $T/ru-${b%%:*}
  done
done > $T/rusage.json
load end
$PY $S/results/round10_processes_summary.py $T
