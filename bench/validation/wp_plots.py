# SPDX-License-Identifier: MIT
"""Work-precision diagrams (error against CPU cost, log-log, Pareto front marked)
for report.py. Uses matplotlib's Agg backend (Debian python3-matplotlib)."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def pareto(points):
    """The non-dominated (cost, error) points, by increasing cost."""
    front, best = [], float("inf")
    for c, e in sorted(points):
        if e < best:
            front.append((c, e))
            best = e
    return front


def mark_front(ax, front, label):
    """Circles the Pareto-optimal points and joins them."""
    if front:
        ax.loglog(*zip(*front), "o-", mfc="none", mec="r", color="r", ms=11, lw=0.8, alpha=0.8,
                  label=label)


def finish(fig, axes, path, legend_size=7):
    """Grid and legend on every axes, tight layout, saved to `path` (PNG), closed."""
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=legend_size)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def det_points(d, np_):
    return [(r["cpu_s"], r["error"]) for r in d["sweep"]["rows"]
            if r["case"].startswith("annihilation") and r["res"] == np_ and r["cpu_s"] > 0]


def ssa_points(d, np_):
    """{(N_b, t_end): [(cost of r realizations, error of their mean), ...]}"""
    out = {}
    for c in d["ssa"]:
        if c["Np"] != np_:
            continue
        per = c["cpu_s"] / c["realizations"]
        out[(c["N_b"], c["end"])] = [(per * r, e) for r, e in sorted(c["errors"].items())]
    return out


def cheapest_at(points, target, noise=None):
    """Least cost whose error (and, for an ensemble, whose noise level, the expected
    error from R realizations: one lucky draw does not count) is <= target."""
    ok = [c for k, (c, e) in enumerate(points)
          if e <= target and (noise is None or noise[k] <= target)]
    return min(ok) if ok else None


def ssa_noise(d, np_):
    """{(N_b, t_end): [noise level of the mean of r, ...]} in the order of ssa_points()."""
    return {(c["N_b"], c["end"]): [v for _, v in sorted(c["noise"].items())]
            for c in d["ssa"] if c["Np"] == np_}


def make_all(d, figs, paper_sdpd, paper_ssa, paper_ssa_one, paper_cost_one):
    plots = {}
    nps = [n for n in (17, 33, 65) if det_points(d, n) or ssa_points(d, n)]
    fig, axes = plt.subplots(1, len(nps), figsize=(5 * len(nps), 4.2), squeeze=False)
    for ax, np_ in zip(axes[0], nps):
        det = det_points(d, np_)
        if det:
            ax.loglog(*zip(*det), "o", color="C0", label="ours, deterministic (N_b=1e3, t=1)")
        allpts = list(det)
        for k, ((nb, end), pts) in enumerate(sorted(ssa_points(d, np_).items())):
            big_r = next(c["realizations"] for c in d["ssa"]
                         if c["Np"] == np_ and c["N_b"] == nb and c["end"] == end)
            ax.loglog(*zip(*pts), "s-", color=f"C{k + 1}", ms=4,
                      label=f"ours, SSA N_b={nb:g}, t={end:g} (mean of r = 1..{big_r})")
            allpts += pts
        c1 = paper_cost_one[np_]
        ax.loglog([c1], [paper_sdpd[np_]], "*", ms=14, color="k", label="paper SDPD (N_b=1e4)")
        ax.loglog([100 * c1], [paper_ssa[np_]], "P", ms=11, color="k",
                  label="paper SSA, R=100 (N_b=1e4)")
        ax.loglog([c1], [paper_ssa_one[np_]], "X", ms=11, color="grey", label="paper SSA, R=1")
        mark_front(ax, pareto(allpts), "Pareto front (ours)")
        ax.set_title(f"drawert2019 Table 1, N = {np_}")
        ax.set_xlabel("CPU time [s]")
        ax.set_ylabel("||u - u_ref||_2 / (N - 1)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6)
    fig.text(0.5, 0.005, "CPU time: ours sadr + services (os.wait4); paper: its code on this "
             "machine type (issue #20)", ha="center", fontsize=7)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    p = figs / "table1_work_precision.png"
    fig.savefig(p, dpi=110)
    plt.close(fig)
    plots["table1"] = p

    pois = [r for r in d["sweep"]["rows"] if r["case"].startswith("poiseuille")]
    if pois:
        fig, ax = plt.subplots(figsize=(5.5, 4.2))
        for k, res in enumerate(sorted({r["res"] for r in pois})):
            pts = [(r["cpu_s"], r["error"]) for r in pois if r["res"] == res and r["cpu_s"] > 0]
            if pts:
                ax.loglog(*zip(*pts), "o", color=f"C{k}", label=f"H/dx = {res} (dt = 1, 1/2, 1/4 limit)")
        mark_front(ax, pareto([(r["cpu_s"], r["error"]) for r in pois if r["cpu_s"] > 0]),
                   "Pareto front")
        ax.set_title("Poiseuille start-up, t = 0.225 s, Morris walls")
        ax.set_xlabel("CPU time [s]")
        ax.set_ylabel("scaled L2 / u_max")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        p = figs / "poiseuille_work_precision.png"
        fig.savefig(p, dpi=110)
        plt.close(fig)
        plots["poiseuille"] = p
    return plots
