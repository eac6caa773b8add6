#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Opt-in (ctest -L slurm): a real single-node Slurm (../shared/tools/slurm-local.sh,
# Debian's slurm-wlm + munge) runs a 4-task array of realizations through
# deploy/slurm/submit-ensemble.sh; the combined ensemble must equal, byte for
# byte, what `sadr run -r 4` computes locally. Installs packages and starts
# daemons (stopped again by PID at exit), hence not in the default suite.
set -euo pipefail
src=${1:?source dir}; bin=${2:?bin dir}
slurm_local=${SADR_SLURM_LOCAL:-$src/../shared/tools/slurm-local.sh}
[ -x "$slurm_local" ] || { echo "slurm-local.sh not found at $slurm_local"; exit 1; }
work=$(mktemp -d /tmp/sadr-slurm-XXXXXX)
export SLURM_LOCAL_DIR=$work/slurm
# Stop the daemons before removing $work (it holds the PID files `down` reads).
cleanup() { bash "$slurm_local" down >/dev/null 2>&1 || true; rm -rf "$work"; }
trap cleanup EXIT
bash "$slurm_local" install
bash "$slurm_local" config
bash "$slurm_local" up
export SLURM_CONF=$SLURM_LOCAL_DIR/etc/slurm.conf

cat > "$work/scene.yaml" <<'YAML'
name: slurm_ann
dimension: 1
box: {lower: [0.0], upper: [1.0], periodic: [false]}
regions:
  - {name: left_wall, shape: box, lower: [0.0], upper: [0.0]}
  - {name: right_wall, shape: box, lower: [1.0], upper: [1.0]}
particles:
  spacing: 0.0625
  density: 1.0
  fill: [{region: left_wall, kind: wall}, {region: right_wall, kind: wall}, {kind: fluid}]
fluid: {backend: static, h_over_dx: 1.8}
species:
  - name: A
    diffusivity: 0.1
    boundaries: [{region: left_wall, condition: dirichlet, count: 100}, {region: right_wall, condition: dirichlet, count: 0}]
  - name: B
    diffusivity: 0.1
    boundaries: [{region: left_wall, condition: dirichlet, count: 0}, {region: right_wall, condition: dirichlet, count: 100}]
reactions: [{name: annihilation, equation: "A + B -> 0", rate: 0.1}]
time: {coupling_step: 0.01, end: 0.4}
output: {times: [0.2, 0.4], formats: [csv]}
seed: 11
YAML
"$bin/sadr" run "$work/scene.yaml" -q -r 4 -o "$work/local"
ids=$(bash "$src/deploy/slurm/submit-ensemble.sh" "$work/scene.yaml" "$work/cluster" 4 "$bin")
echo "$ids"
combine=$(echo "$ids" | awk '{print $NF}')
for _ in $(seq 1 240); do
  squeue -h -j "$combine" 2>/dev/null | grep -q . || break
  sleep 0.5
done
for f in "$work/local/ensemble/"*.csv; do
  cmp "$f" "$work/cluster/ensemble/$(basename "$f")"
done
echo "slurm ensemble == local ensemble ($(ls "$work/local/ensemble" | wc -l) frames)"
