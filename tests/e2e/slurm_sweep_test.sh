#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Opt-in (ctest -L slurm): a real single-node Slurm (slurm-local.sh from
# $SADR_SLURM_LOCAL or ../shared/tools/, Debian's slurm-wlm + munge) runs a
# 2-point x 3-realization sweep through the slurm executor (job array +
# dependent aggregation job); its aggregates must equal, byte for byte, those of
# the local executor. Then a cancelled array task: the sweep reports it and
# `sadr sweep --resume` completes it without recomputing the finished runs.
# Without the script or a scheduler that starts, the test is SKIPPED (exit 77)
# with the reason printed, never passed.
set -euo pipefail
src=${1:?source dir}; bin=${2:?bin dir}
slurm_local=${SADR_SLURM_LOCAL:-$src/../shared/tools/slurm-local.sh}
skip() { echo "SKIPPED (not passed): $*" >&2; exit 77; }
[ -f "$slurm_local" ] || skip "slurm-local.sh not found at $slurm_local (set SADR_SLURM_LOCAL)"
work=$(mktemp -d /tmp/sadr-slurm-sweep-XXXXXX)
export SLURM_LOCAL_DIR=$work/slurm
# Stop the daemons (by the PIDs slurm-local.sh recorded under $work) before
# removing $work: removed first, the PID files would be gone and the daemons left.
cleanup() { bash "$slurm_local" down >/dev/null 2>&1 || true; rm -rf "$work"; }
trap cleanup EXIT
bash "$slurm_local" install || skip "slurm-wlm/munge could not be installed"
bash "$slurm_local" config || skip "slurm.conf could not be written"
bash "$slurm_local" up || skip "the Slurm daemons did not start"
export SLURM_CONF=$SLURM_LOCAL_DIR/etc/slurm.conf
for _ in $(seq 1 60); do sinfo -h -o %T 2>/dev/null | grep -qE "idle|mix|alloc" && break; sleep 1; done
sinfo -h -o %T | grep -qE "idle|mix|alloc" || skip "the Slurm node never became idle: $(sinfo 2>&1)"

cat > "$work/scene.yaml" <<'YAML'
name: slurm_bd
dimension: 1
box: {lower: [0.0], upper: [1.0], periodic: [true]}
particles: {spacing: 0.125, density: 1.0}
fluid: {backend: static, h_over_dx: 1.5}
species: [{name: A, diffusivity: 0.0}]
reactions:
  - {name: birth, equation: "0 -> A", rate: 4000}
  - {name: death, equation: "A -> 0", rate: 1}
time: {coupling_step: 0.5, end: 2.0}
output: {times: [1.0, 2.0], formats: [csv, vtu], checkpoint_every: 0.5}
seed: 5
YAML
cat > "$work/sweep.yaml" <<'YAML'
scene: scene.yaml
realizations: 3
seed: 21
keep: all
retries: 0
parameters:
  grid:
    reactions[birth].rate: [1e6, 2e6]
executor: {type: slurm, cpus_per_task: 1, poll_seconds: 0.5}
YAML
"$bin/sadr" sweep "$work/sweep.yaml" -o "$work/local" --executor local -q
"$bin/sadr" sweep "$work/sweep.yaml" -o "$work/cluster"
n=0
for f in $(cd "$work/local" && ls points/*/frame_* points/*/aggregate.pvd observables.csv); do
  cmp "$work/local/$f" "$work/cluster/$f"
  n=$((n + 1))
done
[ "$n" -ge 13 ] || { echo "only $n aggregate files compared"; exit 1; }
grep -q '"state": "done"' "$work/cluster/sweep.json"
echo "slurm sweep aggregates == local executor's ($n files, byte for byte)"

# Flow replay on Slurm: a moving fluid (the Poiseuille tracer example, shortened)
# swept over a stochastic diffusivity. The array tasks record the one fluid once
# (flows/<key>.bin) and replay it; frames and aggregates equal, byte for byte, the
# local executor's with every run stepping its own fluid.
sed -e 's/^  end: .*/  end: 0.2/' -e 's/^  every: .*/  every: 0.1/' \
  "$src/examples/poiseuille_tracer_2d.yaml" > "$work/flow.yaml"
grep -q '^  end: 0.2$' "$work/flow.yaml" && grep -q '^  every: 0.1$' "$work/flow.yaml" ||
  { echo "could not shorten the example's time.end/output.every"; exit 1; }
cat > "$work/flow_sweep.yaml" <<'YAML'
scene: flow.yaml
realizations: 2
seed: 9
keep: all
retries: 0
parameters:
  grid:
    species[T].diffusivity: [0.001, 0.004]
executor: {type: slurm, cpus_per_task: 1, poll_seconds: 0.5}
YAML
"$bin/sadr" sweep "$work/flow_sweep.yaml" -o "$work/flow_own" --executor local -q --no-flow-replay
"$bin/sadr" sweep "$work/flow_sweep.yaml" -o "$work/flow_cluster"
tapes=$(ls "$work/flow_cluster/flows/"*.bin | wc -l)
[ "$tapes" -eq 1 ] || { echo "expected 1 recorded flow, found $tapes"; exit 1; }
recorded=$(grep -l '"flow_recorded": true' "$work"/flow_cluster/runs/*/result.json | wc -l)
[ "$recorded" -eq 1 ] || { echo "expected 1 run to record the flow, found $recorded"; exit 1; }
n=0
for f in $(cd "$work/flow_own" && ls points/*/frame_*.csv runs/*/frames/frame_*.csv); do
  cmp "$work/flow_own/$f" "$work/flow_cluster/$f"
  n=$((n + 1))
done
[ "$n" -ge 12 ] || { echo "only $n replayed files compared"; exit 1; }
echo "slurm sweep replayed one flow to 4 runs; $n files == the local executor's without replay"

# A cancelled array task: the sweep reports it; --resume runs only that one.
"$bin/sadr" sweep "$work/sweep.yaml" -o "$work/cancel" > "$work/cancel.log" 2>&1 &
driver=$!
job=""
for _ in $(seq 1 200); do
  job=$(squeue -h -n sadr-sweep -o %F 2>/dev/null | head -1)
  [ -n "$job" ] && break
  sleep 0.1
done
[ -n "$job" ] || { echo "no array job appeared"; cat "$work/cancel.log"; exit 1; }
scancel "${job}_4"
set +e
wait "$driver"
rc=$?
set -e
cat "$work/cancel.log"
[ "$rc" -eq 3 ] || { echo "expected exit 3 (a run not finished), got $rc"; exit 1; }
grep -q "runs not finished" "$work/cancel.log"
"$bin/sadr" sweep --resume "$work/cancel" > "$work/resume.log" 2>&1 || { cat "$work/resume.log"; exit 1; }
cat "$work/resume.log"
grep -q "executed 1 runs, skipped 5 finished" "$work/resume.log"
for f in $(cd "$work/local" && ls points/*/frame_*.csv observables.csv); do
  cmp "$work/local/$f" "$work/cancel/$f"
done
echo "cancelled task reported, resumed alone, aggregates == local's"
