# SPDX-License-Identifier: MIT
"""Ensembles on a Dask cluster (``python3-distributed``): each realization one
task, running exactly the worker command of the Slurm executor
(``deploy/slurm/realization.sbatch``):

    OMP_NUM_THREADS=1 JOB_COMPLETION_INDEX=i \\
        sadr run SCENE --realization env --output OUT --quiet --restart-on-failure 2

then ``sadr ensemble OUT`` combines the CSV frames. The result is
byte-identical to ``sadr run SCENE -r R -o OUT`` (tests/python/test_dask.py).

    from dask.distributed import Client, LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        ens = sadr.dask_runner.run_ensemble("scene.yaml", "runs/ens", 8, client)

The tasks are plain ``subprocess.run`` calls: workers need the `sadr`
executables (same path, or ``sadr_bin=``) and a shared output folder, not this
package.
"""
from __future__ import annotations

import os
import subprocess
from pathlib import Path
from typing import TYPE_CHECKING

from .cli import error_for, find_sadr, run_cli
from .runs import Ensemble

if TYPE_CHECKING:
    from .sweeps import Sweep


def realization_command(scene, output, sadr_bin=None) -> list:
    """The Slurm array task's command line (the index comes from the environment)."""
    sadr_bin = sadr_bin or find_sadr()
    return [str(sadr_bin), "run", str(scene), "--realization", "env", "--output", str(output),
            "--quiet", "--restart-on-failure", "2"]


def realization_env(index: int, threads: int = 1) -> dict:
    """A task's environment: this one plus the array index (as a Kubernetes
    Indexed Job's, which `--realization env` and `sweep-task` read) and its threads."""
    env = dict(os.environ)
    env.pop("SLURM_ARRAY_TASK_ID", None)  # --realization env reads it before JOB_COMPLETION_INDEX
    env["JOB_COMPLETION_INDEX"] = str(index)
    env["OMP_NUM_THREADS"] = str(threads)
    return env


def run_ensemble(scene: str | os.PathLike, output: str | os.PathLike, realizations: int, client, *,
                 sadr_bin=None, threads: int = 1, combine: bool = True) -> Ensemble:
    """Runs realizations 0..R-1 of ``scene`` into ``output`` as Dask tasks on
    ``client``, then (``combine``) ``sadr ensemble output``. A failed task raises
    the SadrError of its exit code naming the realization."""
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    cmd = realization_command(Path(scene).resolve(), output.resolve(), sadr_bin)
    futures = [client.submit(subprocess.run, cmd, env=realization_env(i, threads),
                             capture_output=True, text=True, key=f"sadr-realization-{i}-{output.name}",
                             pure=False)
               for i in range(realizations)]
    for i, proc in enumerate(client.gather(futures)):
        if proc.returncode != 0:
            raise error_for(proc.returncode, proc.stderr, cmd, f"realization {i}: sadr")
    if combine:
        run_cli(["ensemble", output])
    return Ensemble(output)


def run_sweep(sweep_file: str | os.PathLike, output: str | os.PathLike, client, *, sadr_bin=None,
              threads: int = 1, flow_replay: bool = True) -> Sweep:
    """A `sadr sweep` whose runs are Dask tasks: prepares ``output`` (``sadr
    sweep FILE -o OUT --aggregate-only`` writes sweep.json with every run
    pending), runs each unfinished run as ``sadr sweep-task OUT -q`` with its
    index in ``JOB_COMPLETION_INDEX`` (the Slurm array task's command), then
    aggregates with ``sadr sweep --resume OUT --aggregate-only``. Runs whose
    fluid is the same share one recorded flow (``OUT/flows``, docs/sweeps.md);
    ``flow_replay=False`` passes ``--no-flow-replay``. Returns the sadr.Sweep;
    a failed run raises the SadrError of its exit code."""
    from .sweeps import Sweep

    output = Path(output).resolve()
    sadr_bin = str(sadr_bin or find_sadr())
    if not (output / "sweep.json").is_file():
        args = ["sweep", Path(sweep_file).resolve(), "-o", output, "--aggregate-only", "-q"]
        proc = run_cli(args + ([] if flow_replay else ["--no-flow-replay"]), check=False)
        if proc.returncode not in (0, 3) or not (output / "sweep.json").is_file():
            raise error_for(proc.returncode, proc.stderr, proc.args, "sadr sweep")
    pending = [r["index"] for r in Sweep(output).manifest["runs"] if r["state"] != "ok"]
    cmd = [sadr_bin, "sweep-task", str(output), "-q"]
    futures = [client.submit(subprocess.run, cmd, env=realization_env(i, threads),
                             capture_output=True, text=True, key=f"sadr-sweep-task-{i}-{output.name}",
                             pure=False)
               for i in pending]
    failed = [(i, p) for i, p in zip(pending, client.gather(futures)) if p.returncode != 0]
    run_cli(["sweep", "--resume", output, "--aggregate-only", "-q"], check=not failed)
    if failed:
        i, proc = failed[0]
        raise error_for(proc.returncode, proc.stderr, cmd,
                        f"{len(failed)} sweep run(s) failed; run {i}: sadr")
    return Sweep(output)
