# SPDX-License-Identifier: MIT
"""Sweep loaders against `sadr sweep` output (layout: docs/sweeps.md): the
tidy table against the runs' own frames, the xarray fields against numpy on
the realizations, and the Dask runner against the local executor, byte for byte."""
import filecmp

import numpy as np
import pytest
import yaml
from dask.distributed import Client, LocalCluster

import sadr
import sadr.dask_runner
from conftest import EXAMPLES

RATE = "reactions[decay_A].rate"
R = 3


def write_sweep(tmp_path, keep="all"):
    (tmp_path / "scene.yaml").write_text((EXAMPLES / "static_reaction_diffusion.yaml").read_text())
    sweep = {"scene": "scene.yaml", "realizations": R, "seed": 11,
             "parameters": {"grid": {RATE: [0.5, 2.0]},
                            "zip": {"time.end": [0.5], "output.every": [0.25]}},
             "executor": {"type": "local", "workers": 2}, "keep": keep}
    path = tmp_path / "sweep.yaml"
    path.write_text(yaml.safe_dump(sweep, sort_keys=False))
    return path


@pytest.fixture(scope="module")
def local_sweep(tmp_path_factory, sadr_bin):
    root = tmp_path_factory.mktemp("sweep")
    sadr.run_cli(["sweep", write_sweep(root), "-o", root / "local", "-q"])
    return sadr.open(root / "local")


def test_manifest_and_points(local_sweep):
    sw = local_sweep
    assert isinstance(sw, sadr.Sweep)
    assert sw.parameters == [RATE, "time.end", "output.every"]
    assert sw.points[RATE].tolist() == [0.5, 2.0]
    assert (sw.points["state"] == "done").all()
    assert len(sw.runs) == 2 * R and (sw.runs["state"] == "ok").all()
    assert sw.run(1, 2).manifest["overrides"][0].startswith(RATE)


def test_table_against_the_runs(local_sweep):
    sw = local_sweep
    t = sw.table()
    assert list(t.columns[:7]) == ["point", RATE, "time.end", "output.every", "realization",
                                   "frame", "time"]
    assert len(t) == 2 * R * 3
    for (p, r), rows in t.groupby(["point", "realization"]):
        series = sw.run(p, r).series()
        assert rows["time"].tolist() == series.index.tolist()
        assert rows["A"].tolist() == series["A"].tolist()  # copy numbers: exact
        assert (rows[RATE] == sw.points.loc[p, RATE]).all()
    # a faster decay leaves fewer molecules: A(0.5) is Poisson with mean P/k (1 - exp(-k/2)),
    # P ~ 280/time (28 source particles): 124 vs 88; the difference of two means of 3 is
    # 4.2 standard deviations: false-failure rate ~1e-5
    end = t[t["frame"] == 2].groupby(RATE)["A"]
    assert end.mean()[0.5] > end.mean()[2.0]
    disk = sadr.Disk([0.5, 0.5], 0.15)
    td = sw.table(region=disk, stat="mean", species="A")
    want = [sadr.observe(f, "A", disk, "mean") for p in (0, 1) for r in range(R)
            for f in sw.run(p, r).frames()]
    assert td["A"].tolist() == want
    fig = sadr.plot_sweep(t, RATE, "A")
    np.testing.assert_allclose(fig.axes[0].lines[0].get_ydata(), end.mean().to_numpy())


def test_module_cli_plots_a_sweep(local_sweep, tmp_path):
    import subprocess
    import sys

    out = tmp_path / "summary.png"
    proc = subprocess.run([sys.executable, "-m", "sadr", "plot", str(local_sweep.path), "-o", str(out),
                           "--species", "A"], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_fields_against_numpy(local_sweep):
    sw = local_sweep
    for p in (0, 1):
        ds = sw.fields(p)
        assert ds.attrs[RATE] == sw.points.loc[p, RATE] and ds.attrs["realizations"] == R
        runs = [sw.run(p, r) for r in range(R)]
        assert ds["time"].values.tolist() == runs[0].times.tolist()
        for k in range(len(runs[0])):
            a = np.array([run.frame(k).species["A"] for run in runs])
            np.testing.assert_array_equal(ds["id"].values, runs[0].frame(k).ids)
            np.testing.assert_allclose(ds["A_mean"][k].values, a.mean(axis=0), rtol=1e-13, atol=1e-13)
            np.testing.assert_allclose(ds["A_var"][k].values, a.var(axis=0, ddof=1), rtol=1e-12,
                                       atol=1e-12)
            np.testing.assert_array_equal(ds["x"][k].values, runs[0].frame(k).positions[:, 0])
    allf = sw.all_fields()
    assert allf["A_mean"].dims == ("point", "time", "particle")
    assert allf[RATE].values.tolist() == [0.5, 2.0]


def test_dask_sweep_equals_local(tmp_path, local_sweep):
    path = write_sweep(tmp_path)
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        sw = sadr.dask_runner.run_sweep(path, tmp_path / "dask", client)
    assert (sw.points["state"] == "done").all()
    a, b = local_sweep.path, sw.path
    names = sorted(str(p.relative_to(a)) for p in a.glob("points/*/*.csv"))
    names += sorted(str(p.relative_to(a)) for p in a.glob("runs/*/frames/*"))
    names.append("observables.csv")
    assert len(names) > 2 * R * 3
    _, mismatch, errors = filecmp.cmpfiles(a, b, names, shallow=False)
    assert not mismatch and not errors, mismatch + errors
    assert sw.table().equals(local_sweep.table())


def test_dask_sweep_replays_one_flow(tmp_path):
    """A sweep over a stochastic diffusivity of a moving fluid, its runs Dask tasks:
    every run replays the one recorded flow (one tape in flows/, each run's
    result.json names the same fluid key, one run recorded it), and the frames,
    aggregates and observables equal, byte for byte, those of the local executor
    with every run stepping its own fluid (--no-flow-replay)."""
    scene = sadr.Scene.load(EXAMPLES / "poiseuille_tracer_2d.yaml")
    scene["time.end"] = 0.2
    scene["output.every"] = 0.1
    scene["output.formats"] = ["csv"]
    scene.write(tmp_path / "scene.yaml")
    sweep = {"scene": "scene.yaml", "realizations": 2, "seed": 5,
             "parameters": {"grid": {"species[T].diffusivity": [0.001, 0.004]}},
             "executor": {"type": "local", "workers": 2}, "keep": "all"}
    path = tmp_path / "sweep.yaml"
    path.write_text(yaml.safe_dump(sweep, sort_keys=False))
    own = tmp_path / "own"
    sadr.run_cli(["sweep", path, "-o", own, "-q", "--no-flow-replay"])
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        sw = sadr.dask_runner.run_sweep(path, tmp_path / "dask", client)
    assert (sw.points["state"] == "done").all()
    points = sw.manifest["points"]
    assert all(p["flow_replay"]["on"] for p in points), [p["flow_replay"] for p in points]
    assert len({p["flow_replay"]["fluid_key"] for p in points}) == 1
    tapes = sorted(sw.path.glob("flows/*.bin"))
    assert len(tapes) == 1, tapes
    results = [yaml.safe_load((sw.path / r["dir"] / "result.json").read_text())
               for r in sw.manifest["runs"]]
    assert len(results) == 4
    assert {r["fluid_key"] for r in results} == {points[0]["flow_replay"]["fluid_key"]}
    assert sum(bool(r["flow_recorded"]) for r in results) == 1
    names = sorted(str(p.relative_to(own)) for p in own.glob("points/*/*.csv"))
    names += sorted(str(p.relative_to(own)) for p in own.glob("runs/*/frames/*.csv"))
    assert len(names) >= 4 * 3
    _, mismatch, errors = filecmp.cmpfiles(own, sw.path, names, shallow=False)
    assert not mismatch and not errors, mismatch + errors
