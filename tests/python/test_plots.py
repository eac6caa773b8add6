# SPDX-License-Identifier: MIT
"""Plot one-liners: each returns a Figure that saves as PNG and draws what it says."""
import matplotlib
import numpy as np
import pandas as pd

import sadr


def png(fig, path):
    fig.savefig(path, dpi=60)
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 2000
    return data


def _backend_after_import(tmp_path, env_backend=None, pyplot_first=False):
    """matplotlib's backend after `import sadr.plots` in a fresh interpreter whose
    matplotlibrc asks for the svg backend (ctest sets MPLBACKEND: removed here)."""
    import os
    import subprocess
    import sys

    (tmp_path / "matplotlibrc").write_text("backend: svg\n")
    env = {k: v for k, v in os.environ.items() if k != "MPLBACKEND"}
    env["MPLCONFIGDIR"] = str(tmp_path)
    if env_backend:
        env["MPLBACKEND"] = env_backend
    code = ("import matplotlib\n" + ("import matplotlib.pyplot\n" if pyplot_first else "")
            + "import sadr.plots\nprint(matplotlib.get_backend().lower())")
    proc = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    return proc.stdout.strip()


def test_backend_is_agg_unless_chosen(tmp_path):
    """sadr.plots selects Agg (no display needed) over a configured backend,
    but not over MPLBACKEND nor a pyplot already imported."""
    assert _backend_after_import(tmp_path) == "agg"
    assert _backend_after_import(tmp_path, env_backend="pdf") == "pdf"
    assert _backend_after_import(tmp_path, pyplot_first=True) == "svg"


def test_particles_coloured(tmp_path, poiseuille_runs):
    f = poiseuille_runs["binary"].frame(-1)
    for color in ("T", "speed"):
        fig = sadr.plot_particles(f, color=color, arrows=color == "speed")
        assert isinstance(fig, matplotlib.figure.Figure)
        coloured = fig.axes[0].collections[1]
        assert len(coloured.get_array()) == np.count_nonzero(f.kinds != 1)  # walls drawn grey
        np.testing.assert_array_equal(coloured.get_array(), f.field(color)[f.kinds != 1])
        png(fig, tmp_path / f"{color}.png")


def test_profile_of_a_known_field(tmp_path, poiseuille_runs):
    """The profile of y across the channel is y itself at the bin centres
    (to within the particle positions in a bin: spacing 0.05, 10 bins of 0.1)."""
    f = poiseuille_runs["binary"].frame(0)
    s, mean, count = sadr.profile(f, "y", [0.5, 0.0], [0.5, 1.0], width=0.5, bins=10)
    assert count.sum() == 400 and (count == 40).all()  # 20 fluid rows x 20 columns
    np.testing.assert_allclose(mean, s, atol=1e-12)
    png(sadr.plot_profile(f, "vx", [0.5, 0.0], [0.5, 1.0], width=0.5, bins=10,
                          reference=lambda y: 0.0), tmp_path / "profile.png")


def test_series_and_bands(tmp_path, static_ensemble):
    b = static_ensemble.band("A", sadr.Disk([0.5, 0.5], 0.15))
    fig = sadr.plot_series(b)
    ax = fig.axes[0]
    np.testing.assert_array_equal(ax.lines[0].get_ydata(), b["mean"])
    assert len(ax.collections) == 1  # the shaded band
    png(fig, tmp_path / "band.png")
    fig = sadr.plot_series(static_ensemble.series("A"))
    assert len(fig.axes[0].lines) == 4
    png(fig, tmp_path / "series.png")


def test_sweep_plot(tmp_path):
    rng = np.random.default_rng(3)
    rows = [{"k": k, "realization": r, "time": 1.0, "A": k * 10 + rng.normal()}
            for k in (1.0, 2.0, 4.0) for r in range(5)]
    table = pd.DataFrame(rows)
    fig = sadr.plot_sweep(table, "k", "A")
    line = fig.axes[0].lines[0]
    np.testing.assert_array_equal(line.get_xdata(), [1.0, 2.0, 4.0])
    np.testing.assert_allclose(line.get_ydata(), table.groupby("k")["A"].mean().to_numpy())
    png(fig, tmp_path / "sweep.png")
    # the table it plots (printed by `python3 -m sadr plot SWEEP`): 95 % t interval, n = 5
    from scipy import stats

    s = sadr.sweep_summary(table, "k", "A")
    assert s["realizations"].tolist() == [5, 5, 5]
    a = table[table["k"] == 2.0]["A"].to_numpy()
    half = stats.t.ppf(0.975, 4) * a.std(ddof=1) / np.sqrt(5)
    np.testing.assert_allclose(s.loc[1, ["A_mean", "ci_lo", "ci_hi"]].to_numpy(dtype=float),
                               [a.mean(), a.mean() - half, a.mean() + half], rtol=1e-14)


def test_overview_and_module_cli(tmp_path, poiseuille_runs):
    """`python3 -m sadr plot RUN` (Quick start command (1)) writes the overview PNG."""
    import subprocess
    import sys

    run = poiseuille_runs["binary"]
    fig = sadr.plots.overview(run)
    assert len([a for a in fig.axes if a.get_label() != "<colorbar>"]) == 4
    out = tmp_path / "overview.png"
    proc = subprocess.run([sys.executable, "-m", "sadr", "plot", str(run.path), "-o", str(out)],
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    bad = subprocess.run([sys.executable, "-m", "sadr", "plot", str(tmp_path)],
                         capture_output=True, text=True)
    assert bad.returncode == 1 and "neither a run" in bad.stderr


def test_overview_1d(tmp_path):
    from conftest import EXAMPLES

    s = sadr.Scene.load(EXAMPLES / "annihilation_1d_stochastic.yaml")
    s["time.end"] = 0.02
    s["output.times"] = [0.0, 0.02]
    run = s.run(tmp_path / "ann")
    fig = sadr.plots.overview(run)
    lines = fig.axes[0].lines
    assert len(lines) == 2
    np.testing.assert_array_equal(np.sort(lines[1].get_xdata()), np.sort(run.frame(-1).positions[:, 0]))
