# SPDX-License-Identifier: MIT
"""The Dask example: realizations as tasks on a dask.distributed LocalCluster,
each the Slurm worker command, give byte-identical frames and ensemble files
to the local executor (`sadr run -r R`)."""
import filecmp

from dask.distributed import Client, LocalCluster

import sadr
import sadr.dask_runner
from conftest import poiseuille

R = 3


def same_files(a, b, pattern):
    fa = sorted(p.relative_to(a) for p in a.glob(pattern))
    fb = sorted(p.relative_to(b) for p in b.glob(pattern))
    assert fa == fb and fa, f"{pattern}: {fa} vs {fb}"
    _, mismatch, errors = filecmp.cmpfiles(a, b, [str(p) for p in fa], shallow=False)
    assert not mismatch and not errors, mismatch + errors
    return len(fa)


def test_dask_equals_local_executor(tmp_path):
    scene = poiseuille(end=0.3, every=0.1, formats=("vtu", "csv"))
    scene["species[0].diffusivity"] = 0.01  # more jumps: realizations differ
    path = scene.write(tmp_path / "scene.yaml")
    local = scene.run(tmp_path / "local", realizations=R, jobs=2)
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        dask = sadr.dask_runner.run_ensemble(path, tmp_path / "dask", R, client)
    assert dask.realizations == local.realizations == [0, 1, 2]
    n = same_files(local.path, dask.path, "realization_*/frames/*")
    assert n == R * 4 * 2  # 4 frames, vtu + csv
    assert same_files(local.path, dask.path, "ensemble/*.csv") == 4
    # aggregates through the package agree too, and the realizations do differ
    region = sadr.Box([0.5, 0.0], [1.0, 1.0])
    a, b = local.values("T", region), dask.values("T", region)
    assert (a == b).all() and len({tuple(row) for row in a}) == R


def test_failed_task_raises(tmp_path):
    scene = poiseuille(end=0.1, every=0.1)
    scene["time.end"] = -1
    path = scene.write(tmp_path / "bad.yaml")
    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=None,
                      processes=False) as cluster, Client(cluster) as client:
        try:
            sadr.dask_runner.run_ensemble(path, tmp_path / "out", 1, client)
        except sadr.InvalidInput as e:
            assert "realization 0" in e.message and "time.end" in e.message
        else:
            raise AssertionError("a failing task did not raise")
