# SPDX-License-Identifier: MIT
"""Ensembles and time series against numpy on the realizations' own frames,
and against the per-particle statistics the product writes in ensemble/."""
import numpy as np
import pytest
from scipy import stats

import sadr


def raw(run, k):
    """Frame k of a run read without the package (numpy on the CSV text)."""
    path = run.files[k]["csv"]
    header = path.read_text().splitlines()[0].split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1)
    return {name: data[:, i] for i, name in enumerate(header)}


def test_layout(static_ensemble):
    ens = static_ensemble
    assert isinstance(ens, sadr.Ensemble) and isinstance(sadr.open(ens.path), sadr.Ensemble)
    assert ens.realizations == [0, 1, 2, 3]
    assert ens.times.tolist() == [0.0, 0.25, 0.5]
    assert ens.species == ["A", "B"]
    seeds = {r.manifest["seed"] for r in ens.runs}
    assert len(seeds) == 4  # independent realizations


REGIONS = {
    "all": (None, lambda d: np.ones(len(d["x"]), bool)),
    "disk": (sadr.Disk([0.5, 0.5], 0.15),
             lambda d: (d["x"] - 0.5) ** 2 + (d["y"] - 0.5) ** 2 <= 0.15**2),
    "box": (sadr.Box([0.0, 0.0], [0.5, 1.0]), lambda d: (d["x"] <= 0.5)),
    "fluid&box": (sadr.Kinds("fluid") & sadr.Box([0.0, 0.0], [0.5, 1.0]),
                  lambda d: (d["kind"] == 0) & (d["x"] <= 0.5)),
}


@pytest.mark.parametrize("name", REGIONS)
@pytest.mark.parametrize("stat", ["total", "mean", "concentration"])
def test_values_against_numpy(static_ensemble, name, stat):
    region, select = REGIONS[name]
    ens = static_ensemble
    got = ens.values("A", region, stat)
    want = np.empty_like(got)
    for r, run in enumerate(ens.runs):
        for k in range(len(ens.times)):
            d = raw(run, k)
            m = select(d)
            assert m.any()
            a = d["A"][m]
            want[r, k] = {"total": a.sum(), "mean": a.mean(),
                          "concentration": a.sum() / (d["mass"][m] / d["density"][m]).sum()}[stat]
    np.testing.assert_allclose(got, want, rtol=1e-14, atol=0)
    assert np.unique(got[:, -1]).size > 1  # stochastic A: the realizations differ


def test_band_against_numpy(static_ensemble):
    ens = static_ensemble
    disk = sadr.Disk([0.5, 0.5], 0.15)
    values = ens.values("A", disk)
    b = ens.band("A", disk, confidence=0.9)
    assert b.index.tolist() == ens.times.tolist()
    np.testing.assert_array_equal(b["mean"], values.mean(axis=0))
    np.testing.assert_allclose(b["std"], values.std(axis=0, ddof=1), rtol=1e-15)
    half = stats.t.ppf(0.95, 3) * values.std(axis=0, ddof=1) / 2.0
    np.testing.assert_allclose(b["upper"] - b["mean"], half, rtol=1e-12)
    np.testing.assert_allclose(b["mean"] - b["lower"], half, rtol=1e-12)
    assert (b["n"] == 4).all()
    # the deterministic B is the same in every realization: a zero-width band
    bb = ens.band("B", disk)
    assert (bb["std"] == 0).all() and (bb["upper"] == bb["lower"]).all()


def test_mean_frame_is_numpy_mean(static_ensemble):
    """ensemble/frame_NNNNNN.csv (written by sadr) against numpy over the realizations."""
    ens = static_ensemble
    for k in range(len(ens.times)):
        m = ens.mean_frame(k)
        a = np.array([run.frame(k).species["A"] for run in ens.runs])
        assert m["time"] == ens.times[k]
        assert (m["realizations"] == 4).all()
        f0 = ens.runs[0].frame(k)
        assert np.array_equal(m["ids"], f0.ids)
        assert m["positions"].shape == (len(f0), 3) and m["kinds"].dtype == np.uint8
        np.testing.assert_array_equal(m["positions"], f0.positions)  # realization 0's, by id
        np.testing.assert_array_equal(m["kinds"], f0.kinds)
        np.testing.assert_allclose(m["A"][0], a.mean(axis=0), rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(m["A"][1], a.var(axis=0, ddof=1), rtol=1e-12, atol=1e-12)


def test_series_tables(static_ensemble):
    ens = static_ensemble
    s = ens.series("A", "fluid")
    assert list(s.columns) == [0, 1, 2, 3] and s.index.name == "time"
    np.testing.assert_array_equal(s.to_numpy().T, ens.values("A", "fluid"))
    run = ens[0]
    t = run.series()
    assert list(t.columns) == ["A", "B"]
    assert t["A"].iloc[0] == 0 and t["A"].iloc[-1] > 0  # production started from zero


def test_empty_region_is_nan_not_zero(static_ensemble):
    f = static_ensemble[0].frame(-1)
    nowhere = sadr.Box([2.0, 2.0], [3.0, 3.0])
    assert sadr.observe(f, "A", nowhere, "total") == 0.0
    assert np.isnan(sadr.observe(f, "A", nowhere, "mean"))
    with pytest.raises(ValueError, match="stat 'median'"):
        sadr.observe(f, "A", None, "median")
    with pytest.raises(KeyError, match="no field 'C'"):
        sadr.observe(f, "C")
