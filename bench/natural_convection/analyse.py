#!/usr/bin/python3
"""Steady state and time (and ensemble) averages of a natural-convection run
(examples/natural_convection_ra1e*.yaml; docs/natural-convection.md).

    /usr/bin/python3 bench/natural_convection/analyse.py RUN [RUN ...] --ra 1e4
        [--molecules N] [--threshold 1e-3] [--rate-window 10] [--window T] [--json OUT.json]

RUN is the output directory of `sadr run` (frames/frame_*.csv), or of `sadr run -r R`
(realization_*/frames/frame_*.csv: every realization is one run). Several RUNs are realizations of
the same scene (e.g. different seeds). Each frame is measured with score_run.py's `measure`
(centre-line profiles, heat flows, kinetic energy, density variation); the measurements are cached
in RUN/.../natural_convection_series.json so that a second call reads no frame twice.

Steady-state criterion: for each quantity X of {kinetic energy E of the fluid, Nu near the cylinder
(circles r = 0.15-0.2), Nu on the enclosure (squares 0.05-0.1 inside the walls)}, the relative rate of
change |dX/dt| / |X| is the least-squares slope of X over the frames in [t - W, t] (W = --rate-window)
divided by their mean. The run is steady from the first frame time t_s from which on every later
frame's rates are all below --threshold (per unit time). (A stochastic run's per-frame Nu is too
noisy for this test: give --from the deterministic run's steady time, docs/natural-convection.md;
the drift of each quantity over the window, with its standard error, is printed for every run.) Then the profiles and Nu are averaged over
the frames in [t_s, t_s + T] (T = --window; default: to the end) and over the realizations, and scored
against the continuum reference and the digitised profiles (score_run.score).

Noise (reported for every run, deterministic ones included, where it is the residual unsteadiness):
sigma_frame = the root mean square over the centre-line points of the standard deviation of theta (v*)
across the window's frames of all realizations; its effect on the paper's metric, ||sigma||_2 / n, for
one frame and for the average (divided by sqrt(number of frames averaged), frames being independent
for the copy-number noise: a molecule leaves its particle in about dx^2 / kappa = 0.013 time units).
"""
import argparse
import glob
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tests", "data", "refs", "natural_convection"))
from score_run import Case, average, measure, read_frame, score  # noqa: E402

CACHE = "natural_convection_series.json"
CACHE_VERSION = 1


def run_dirs(paths):
    out = []
    for p in paths:
        reals = sorted(glob.glob(os.path.join(p, "realization_*")))
        dirs = reals if reals else [p]
        for d in dirs:
            if not glob.glob(os.path.join(d, "frames", "frame_*.csv")):
                sys.exit("%s: no frames/frame_*.csv (a `sadr run` output with csv frames?)" % d)
        out += dirs
    return out


def measure_run(run, case, h, dx, molecules):
    """The measurements of every frame of one run, from the cache where it is current."""
    key = {"version": CACHE_VERSION, "ra": case.ra, "h": h, "dx": dx, "molecules": molecules}
    path = os.path.join(run, CACHE)
    cached = {}
    if os.path.exists(path):
        with open(path) as f:
            c = json.load(f)
        if c.get("key") == key:
            cached = c["frames"]
    frames = sorted(glob.glob(os.path.join(run, "frames", "frame_*.csv")))
    out, changed = [], False
    for fpath in frames:
        name = os.path.basename(fpath)
        stamp = os.path.getmtime(fpath)
        if name in cached and cached[name]["mtime"] == stamp:
            m = {k: (np.array(v) if isinstance(v, list) else v) for k, v in cached[name]["m"].items()}
        else:
            fr = read_frame(fpath)
            if molecules > 0:
                fr["theta"] = fr["theta"] / molecules
            m = measure(fr, case, h, dx)
            cached[name] = {"mtime": stamp, "m": {k: (v.tolist() if isinstance(v, np.ndarray) else v)
                                                  for k, v in m.items()}}
            changed = True
        out.append(m)
    if changed:
        with open(path + ".tmp", "w") as f:
            json.dump({"key": key, "frames": cached}, f)
        os.replace(path + ".tmp", path)
    return out


SERIES = (("kinetic_energy", lambda m: m["kinetic_energy"]),
          ("Nu_near_cylinder", lambda m: float(np.mean(m["Q_near"]) / 2)),
          ("Nu_enclosure", lambda m: float(np.mean(m["Q_enclosure"]) / 2)))


def rates(times, ms, window):
    """Relative rates of change |slope| / |mean| over the trailing window, per quantity and frame
    (NaN where the window holds fewer than 3 frames or does not reach back W), and the standard
    error of each slope, relative to the same mean (from the scatter about the fitted line; NaN
    with 3 frames): a rate whose standard error is near the threshold cannot show it is below."""
    out, se = {}, {}
    for name, f in SERIES:
        x = np.array([f(m) for m in ms])
        r = np.full(len(times), np.nan)
        e = np.full(len(times), np.nan)
        for i, t in enumerate(times):
            sel = (times >= t - window - 1e-9) & (times <= t + 1e-9)
            if sel.sum() >= 3 and times[sel][0] <= t - window + 1e-9:
                ts, xs = times[sel], x[sel]
                slope, icpt = np.polyfit(ts, xs, 1)
                mean = max(abs(np.mean(xs)), 1e-300)
                r[i] = abs(slope) / mean
                if len(ts) > 3:
                    resid = xs - (slope * ts + icpt)
                    e[i] = math.sqrt(np.sum(resid ** 2) / (len(ts) - 2) / np.sum((ts - ts.mean()) ** 2)) / mean
        out[name] = r
        se[name] = e
    return out, se


def steady_time(times, rate, threshold):
    """First frame time from which every later rate is below the threshold (None: never)."""
    worst = np.max(np.vstack(list(rate.values())), axis=0)  # NaN where any quantity lacks a window
    ok = np.isfinite(worst) & (worst < threshold)
    for i in range(len(times)):
        if np.isfinite(worst[i]) and ok[i:].all():
            return float(times[i])
    return None


def analyse(runs, ra, h, dx, molecules, threshold, rate_window, window, start=None):
    case = Case(ra)
    per_run = []
    for run in runs:
        ms = measure_run(run, case, h, dx, molecules)
        times = np.array([m["time"] for m in ms])
        rate, rate_se = rates(times, ms, rate_window)
        per_run.append({"run": run, "ms": ms, "times": times, "rate": rate, "rate_se": rate_se,
                        "t_steady": steady_time(times, rate, threshold)})
    result = {"Ra": case.ra, "runs": runs, "molecules": molecules, "threshold_per_time": threshold,
              "rate_window": rate_window, "t_end": [float(r["times"][-1]) for r in per_run],
              "t_steady": [r["t_steady"] for r in per_run],
              "series": [{"time": r["times"].tolist(),
                          **{n: [f(m) for m in r["ms"]] for n, f in SERIES},
                          **{"rate_" + n: [None if not np.isfinite(v) else float(v) for v in r["rate"][n]]
                             for n, _ in SERIES},
                          **{"rate_se_" + n: [None if not np.isfinite(v) else float(v) for v in r["rate_se"][n]]
                             for n, _ in SERIES}} for r in per_run]}
    # Can the test resolve the threshold? The median standard error of the rates over the last
    # half of each run, per quantity: above a third of the threshold, a run with constant means
    # fails the test in some window by chance (docs/natural-convection.md, Ra = 1e6).
    result["rate_se_last_half"] = {}
    for r in per_run:
        half = r["times"] >= 0.5 * r["times"][-1]
        med = {n: (float(np.nanmedian(v[half])) if np.isfinite(v[half]).any() else None)
               for n, v in r["rate_se"].items()}
        result["rate_se_last_half"][r["run"]] = med
        worst = max((v for v in med.values() if v is not None), default=None)
        if worst is not None and worst > threshold / 3:
            p_fail = math.erfc(threshold / worst / math.sqrt(2))  # 2 (1 - Phi(threshold / SE))
            print("%s: note: the rates' standard error (median over the last half, up to %.1e per unit time) "
                  "is above a third of the threshold %g: a run without drift fails one window's test with "
                  "probability %.2g; more frames (output.every) or a longer --rate-window resolve it"
                  % (r["run"], worst, threshold, p_fail), file=sys.stderr)
    result["last_rates"] = {r["run"]: {n: (float(v[np.isfinite(v)][-1]) if np.isfinite(v).any() else None)
                                       for n, v in r["rate"].items()} for r in per_run}
    result["steady"] = all(t is not None for t in result["t_steady"])
    if not result["steady"]:
        bad = [r["run"] for r in per_run if r["t_steady"] is None]
        print("not steady by the criterion (rates < %g per unit time over %g): %s; last rates %s"
              % (threshold, rate_window, ", ".join(bad), result["last_rates"]), file=sys.stderr)
        if start is None:
            return result
        print("averaging from t = %g anyway (--from): NOT a steady average" % start, file=sys.stderr)
    t0 = max(result["t_steady"]) if start is None else start
    t1 = min(result["t_end"]) if window is None else t0 + window
    if t1 > min(result["t_end"]) + 1e-9:
        sys.exit("averaging window [%g, %g] ends after the shortest run (t = %g)" % (t0, t1, min(result["t_end"])))
    chosen, per_real = [], []
    result["window_rates"] = {}
    for r in per_run:
        sel = [m for m in r["ms"] if t0 - 1e-9 <= m["time"] <= t1 + 1e-9]
        if len(sel) >= 3:  # drift over the whole window: relative slope and its standard error
            t = np.array([m["time"] for m in sel])
            for name, f in SERIES:
                x = np.array([f(m) for m in sel])
                (slope, icpt), cov = np.polyfit(t, x, 1, cov=True) if len(sel) > 3 else (np.polyfit(t, x, 1), None)
                se = math.sqrt(cov[0][0]) if cov is not None else float("nan")
                result["window_rates"].setdefault(name, []).append(
                    [float(slope / np.mean(x)), float(se / abs(np.mean(x)))])
        chosen += sel
        per_real.append(score(average(sel), case))
    result["window"] = [t0, t1]
    result["frames_averaged"] = len(chosen)
    result["realizations"] = len(per_run)
    result["score"] = score(average(chosen), case)
    result["score"]["max_density_variation"] = max(m["max_density_variation"] for m in chosen)
    result["score"]["max_speed"] = max(m["max_speed"] for m in chosen)
    for q in ("theta", "vstar"):
        prof = np.array([m[q + "_dig"] for m in chosen])
        sd = prof.std(axis=0, ddof=1) if len(chosen) > 1 else np.zeros(prof.shape[1])
        n = prof.shape[1]
        result[q + "_sigma_frame_rms"] = float(np.sqrt(np.mean(sd ** 2)))
        result[q + "_noise_metric_one_frame"] = float(np.sqrt(np.sum(sd ** 2)) / n)
        result[q + "_noise_metric_average"] = float(np.sqrt(np.sum(sd ** 2)) / n / math.sqrt(len(chosen)))
        if len(per_real) > 1:
            e = np.array([s[q + "_err_digitised"] for s in per_real])
            result[q + "_err_digitised_realization_sd"] = float(e.std(ddof=1))
    if len(per_run) > 1:
        result["realization_noise"] = realization_noise(per_run, t0, t1)
    nu = np.array([float(np.mean(m["Q"]) / 2) for m in chosen])
    result["Nu_half_sd_frames"] = float(nu.std(ddof=1)) if len(nu) > 1 else 0.0
    result["profiles"] = {"x_ref": case.x_ref.tolist(),
                          **{q + "_ref": average(chosen)[q + "_ref"].tolist() for q in ("theta", "vstar")}}
    return result


def realization_noise(per_run, t0, t1):
    """Do frames and realizations count alike? From R realizations with the same frame times in the
    window: sigma_within = the frame-to-frame standard deviation inside a realization (pooled over
    the realizations), sigma_across = the standard deviation across realizations at equal times
    (pooled over the times), and sd_of_means = the standard deviation across realizations of each
    realization's F-frame window mean, against its prediction sigma_within / sqrt(F) for independent
    frames. Each is the root mean square over the digitised centre-line points; the metric columns
    are ||.||_2 / n of the same, for one realization's window mean and for the ensemble's."""
    sel = [[m for m in r["ms"] if t0 - 1e-9 <= m["time"] <= t1 + 1e-9] for r in per_run]
    times = [[round(m["time"], 6) for m in s] for s in sel]
    common = sorted(set(times[0]).intersection(*map(set, times[1:])))
    out = {"realizations": len(per_run), "frames_per_realization": len(common)}
    if len(common) < 2:
        return out
    for q in ("theta", "vstar"):
        # prof[r, f, i]: realization r, frame f (common times), point i
        prof = np.array([[m[q + "_dig"] for m in s if round(m["time"], 6) in common] for s in sel])
        R, F, n = prof.shape
        within = prof.var(axis=1, ddof=1).mean(axis=0)  # per point, pooled over realizations
        across = prof.var(axis=0, ddof=1).mean(axis=0)  # per point, pooled over times
        means = prof.mean(axis=1)  # R x n
        var_means = means.var(axis=0, ddof=1)
        out[q] = {"sigma_within_rms": float(np.sqrt(within.mean())),
                  "sigma_across_rms": float(np.sqrt(across.mean())),
                  "sd_of_window_means_rms": float(np.sqrt(var_means.mean())),
                  "predicted_sd_of_window_means_rms": float(np.sqrt(within.mean() / F)),
                  "metric_one_window_mean": float(np.sqrt(var_means.sum()) / n),
                  "predicted_metric_one_window_mean": float(np.sqrt(within.sum() / F) / n),
                  "metric_ensemble_mean": float(np.sqrt(var_means.sum()) / n / math.sqrt(R)),
                  "predicted_metric_ensemble_mean": float(np.sqrt(within.sum() / F) / n / math.sqrt(R)),
                  "lag1_autocorrelation": float(np.mean([
                      np.sum((p[1:] - p.mean(axis=0)) * (p[:-1] - p.mean(axis=0))) /
                      max(np.sum((p - p.mean(axis=0)) ** 2), 1e-300) for p in prof]))}
    return out


def against(runs, det_run, ra, h, dx, molecules, start):
    """Noise measured against the deterministic run of the same scene at equal times: for every
    frame time t >= start that both have, the root mean square over the digitised centre-line points
    of f_run(t) - f_det(t) (f = theta, v*), and that difference in the paper's metric. Needs no steady
    state: the deterministic run is the mean-field solution the stochastic one fluctuates about."""
    case = Case(ra)
    det = {round(m["time"], 6): m for m in measure_run(det_run, case, h, dx, 0.0)}
    out = {"det_run": det_run, "from": start, "times": []}
    diffs = {"theta": [], "vstar": []}
    for run in runs:
        for m in measure_run(run, case, h, dx, molecules):
            t = round(m["time"], 6)
            if t < start - 1e-9 or t not in det:
                continue
            out["times"].append(t)
            for q in diffs:
                diffs[q].append(m[q + "_dig"] - det[t][q + "_dig"])
    if not out["times"]:
        sys.exit("no common frame times >= %g with %s" % (start, det_run))
    for q, d in diffs.items():
        d = np.array(d)
        out[q + "_rms_diff"] = float(np.sqrt(np.mean(d ** 2)))
        out[q + "_metric_diff_one_frame"] = float(np.mean([np.sqrt(np.sum(x ** 2)) / len(x) for x in d]))
    return out


def load_result(arg):
    """An analyse.py --json output named by "PATH[=LABEL]" (the tables' argument form): (result, LABEL).
    Exits with a message when nothing was averaged (not steady and no --from)."""
    path, _, label = arg.partition("=")
    with open(path) as f:
        a = json.load(f)
    if "score" not in a:
        sys.exit("%s: nothing averaged (not steady by the criterion and no --from)" % path)
    return a, label


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--ra", type=float, required=True)
    ap.add_argument("--h", type=float, default=3.0 / 81.0, help="smoothing length (default 3/81)")
    ap.add_argument("--dx", type=float, default=1.0 / 81.0)
    ap.add_argument("--molecules", type=float, default=0.0,
                    help="stochastic variant: molecules per particle at theta = 1 (theta = count / N)")
    ap.add_argument("--threshold", type=float, default=1e-3, help="steady: |dX/dt| / |X| below this")
    ap.add_argument("--rate-window", type=float, default=10.0, help="time window of the slope fit")
    ap.add_argument("--window", type=float, default=None, help="averaging window length (default: to the end)")
    ap.add_argument("--from", dest="start", type=float, default=None,
                    help="average from this time on instead of the steady time (even when not steady: "
                         "the result says steady = false)")
    ap.add_argument("--against", help="deterministic run of the same scene: also report the noise as the "
                    "difference from it at equal frame times (from --from, default 0)")
    ap.add_argument("--json")
    args = ap.parse_args()
    res = analyse(run_dirs(args.runs), args.ra, args.h, args.dx, args.molecules, args.threshold,
                  args.rate_window, args.window, args.start)
    for i, s in enumerate(res["series"]):
        print("run %s" % res["runs"][i])
        print("  %6s %12s %10s %10s %10s %10s %10s" % ("t", "E", "Nu_cyl", "Nu_encl", "rate_E", "rate_Nuc", "rate_Nue"))
        for k, t in enumerate(s["time"]):
            rr = ["%10.2e" % s["rate_" + n][k] if s["rate_" + n][k] is not None else "%10s" % "-" for n, _ in SERIES]
            print("  %6.1f %12.5e %10.4f %10.4f %s" % (t, s["kinetic_energy"][k], s["Nu_near_cylinder"][k],
                                                     s["Nu_enclosure"][k], " ".join(rr)))
        print("  t_steady = %s; rates' standard error, median over the last half: %s" % (
            res["t_steady"][i], ", ".join("%s %s" % (n, "-" if v is None else "%.1e" % v)
                                          for n, v in res["rate_se_last_half"][res["runs"][i]].items())))
    if "score" in res:
        print("window %g-%g, %d frames from %d realization(s)" % (res["window"][0], res["window"][1],
                                                                  res["frames_averaged"], res["realizations"]))
        for k, v in list(res["score"].items()) + [(k, v) for k, v in res.items() if "noise" in k or "sigma" in k
                                                  or k.endswith("_sd") or k == "Nu_half_sd_frames"]:
            print("  %-30s %s" % (k, ("%.4g" % v) if isinstance(v, float) else v))
        for name, v in res["window_rates"].items():
            print("  drift over the window, %-16s %s per unit time" % (name, ", ".join(
                "%+.2e +- %.1e" % tuple(x) for x in v)))
        rn = res.get("realization_noise")
        if rn and "theta" in rn:
            print("  realizations against frames (%d realizations x %d common frames):"
                  % (rn["realizations"], rn["frames_per_realization"]))
            for q in ("theta", "vstar"):
                d = rn[q]
                print("    %-5s sigma within a realization %.4g, across realizations at equal t %.4g; "
                      "sd of the window means %.4g (predicted sigma_within/sqrt(F) %.4g); in the metric: "
                      "window mean %.3g (predicted %.3g), ensemble mean %.3g (predicted %.3g); "
                      "lag-1 autocorrelation %.2f"
                      % (q, d["sigma_within_rms"], d["sigma_across_rms"], d["sd_of_window_means_rms"],
                         d["predicted_sd_of_window_means_rms"], d["metric_one_window_mean"],
                         d["predicted_metric_one_window_mean"], d["metric_ensemble_mean"],
                         d["predicted_metric_ensemble_mean"], d["lag1_autocorrelation"]))
    if args.against:
        res["against"] = against(run_dirs(args.runs), args.against, args.ra, args.h, args.dx, args.molecules,
                                 args.start or 0.0)
        a = res["against"]
        print("against %s at %d common frame times from t = %g:" % (args.against, len(a["times"]), a["from"]))
        for q in ("theta", "vstar"):
            print("  %s: rms difference %.4g, in the paper's metric per frame %.4g"
                  % (q, a[q + "_rms_diff"], a[q + "_metric_diff_one_frame"]))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(res, f, indent=1)
    sys.exit(0 if res["steady"] else 3)


if __name__ == "__main__":
    main()
