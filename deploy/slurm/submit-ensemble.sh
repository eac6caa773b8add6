#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Submits R realizations as a Slurm array, then a dependent job that combines
# them into OUTPUT_DIR/ensemble/ (per-frame mean and variance).
#   deploy/slurm/submit-ensemble.sh SCENE OUTPUT_DIR R [SADR_BIN_DIR]
# Prints the two job ids. Needs csv in the scene's output.formats.
set -euo pipefail
scene=$(realpath "${1:?usage: submit-ensemble.sh SCENE OUTPUT_DIR R [SADR_BIN_DIR]}")
out=$(realpath -m "${2:?missing OUTPUT_DIR}")
count=${3:?missing R}
bin=$(realpath "${4:-build/release/bin}")
here=$(dirname "$(realpath "$0")")
mkdir -p "$out"
array=$(sbatch --parsable --array=0-$((count - 1)) --chdir="$out" \
  "$here/realization.sbatch" "$scene" "$out" "$bin")
combine=$(sbatch --parsable --dependency=afterok:"$array" --chdir="$out" \
  --job-name=sadr-ensemble --output=sadr-ensemble-%j.log --wrap "'$bin/sadr' ensemble '$out'")
echo "array job $array, combine job $combine"
