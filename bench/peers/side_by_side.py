#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Ours against the peers built on this machine, side by side (issue #20).

    bench/peers/side_by_side.py --build build/release \\
        --lammps /work/peers/lammps/build/lmp \\
        --urdme /work/peers/urdme/driver/urdme_nsm_driver \\
        [--pairs 5] [--only sdpd,tdpd,nsm] [--memory] [--out bench/results/peers_side_by_side]

Timing (default): interleaved pairs ours / peer (the order alternates from pair to pair),
CPU time of one thread (OMP_NUM_THREADS=1), on the same workloads:
  * SDPD, 4 cases (3D/2D, ~1e4/~1e5 particles): our `fluid_bench --case` against LAMMPS
    `pair_style sdpd/taitwater/isothermal` (package DPD-SMOOTH) + `atom_style sph` and
    `fix sph` (package SPH) on the same periodic lattice at rest
    (dx = 1, h = 3, c0 = 10, rho0 = 1, eta = 1, k_B T = 0.01, dt = 0.02). Particle-steps per
    CPU-second; our step is a predictor-corrector step (two force evaluations), LAMMPS'
    Verlet step one.
  * tDPD, 1 species, 10648 particles: our `fluid_tdpd_bench --small` (its 1-species row)
    against LAMMPS `pair_style tdpd` + `fix mvv/tdpd` (package DPD-MESO) (rho = 4, r_c = r_cc = 1.58,
    a = 18.75, gamma = 4.5, s1 = 0.41, kappa = 0.5, no random flux, power_c = 2, lambda = 0.5,
    k_B T = 1, dt = 0.01; 20 warm-up steps, 100 timed). LAMMPS' pair loop draws the
    random-flux Gaussian even at epsilon = 0 (its code as it is); its concentrations start
    uniform (ours in stripes), which the cost does not depend on.
  * NSM, `ssa_bench` cases (a) 32^3 diffusion 1e5 molecules, (b) (a) + A + B <-> C,
    (c) 100^3 voxels 3e6 molecules: ns per event against URDME's nsm() (its C core) fed the
    same lattice (6 neighbours, hop rate 1 per molecule per edge, C at 1/2; bind 0.5, unbind 1).
LAMMPS CPU time is its loop time x its reported CPU use; ours is the benchmarks' own CPU time
of the timed loop; URDME's driver reports process CPU of the nsm() call minus an init-only call.

--memory: process peak RSS at two sizes per case, each command's own (run under GNU time:
ru_maxrss of a process forked from this script never reads below the script's own peak, which
flattened a small peer's slope); the slope is bytes per particle / per voxel (the binary and
libraries drop out). Not load-sensitive. --only selects the cases here too.
Cases: SDPD 3D / 2D (fluid_bench --case, 2 steps), tDPD 1 species (fluid_tdpd_bench --species 1
--quick, 10648 and 97336 particles; LAMMPS the tdpd deck, 2 + 5 steps), NSM (ssa_bench a).

The peers are not part of this repository and are never committed; this script only writes our
own input decks. The URDME driver's contract: `DRIVER N_SIDE MOLECULES REACTIONS(0|1) EVENTS
SEED` builds the periodic N_SIDE^3 lattice above around URDME's nsm() and prints one JSON line
with "events", "cpu_s", "ns_per_event", "peak_rss_kib".
Writes OUT.md (a table to paste into README.md and bench/results) and OUT.json.
"""
import argparse
import datetime
import json
import os
import pathlib
import re
import statistics
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench" / "validation"))
from measure import commit, run_measured  # noqa: E402

# (name, dimension, particles per axis, timed steps)
SDPD_CASES = [("SDPD 3D 1e4", 3, 22, 100), ("SDPD 3D 1e5", 3, 46, 10),
              ("SDPD 2D 1e4", 2, 100, 400), ("SDPD 2D 1e5", 2, 316, 40)]
# (name, scenario, lattice side, molecules per species, reactions, events)
NSM_CASES = [("NSM (a) 32^3 diffusion", "a", 32, 100000, 0, 3e7),
             ("NSM (b) (a) + A+B<->C", "b", 32, 100000, 1, 3e7),
             ("NSM (c) 100^3 voxels", "c", 100, 3000000, 0, 1e7)]

SDPD_DECK = """# sadr bench/peers/side_by_side.py: fluid_bench's SDPD workload
units lj
dimension {dim}
boundary p p p
atom_style sph
lattice {lat} 1.0
region box block 0 {n} 0 {n} {zlo} {zhi}
create_box 1 box
create_atoms 1 box
mass 1 1.0
set group all sph/rho 1.0
pair_style sdpd/taitwater/isothermal 0.01 1.0 12345
pair_coeff 1 1 1.0 10.0 3.0
neighbor 0.3 bin
neigh_modify every 1 delay 0 check yes
fix 1 all sph
{enforce}
timestep 0.02
thermo 0
run 2
run {steps}
"""

TDPD_DECK = """# sadr bench/peers/side_by_side.py: fluid_tdpd_bench's workload, 1 species
units lj
dimension 3
boundary p p p
atom_style tdpd 1
comm_modify vel yes
lattice sc 4.0
region box block 0 {n} 0 {n} 0 {n}
create_box 1 box
create_atoms 1 box
mass 1 1.0
displace_atoms all random 0.19 0.19 0.19 3 units box
set group all cc 1 1.0
velocity all create 1.0 4928459 dist gaussian
pair_style tdpd 1.0 1.58 12345
pair_coeff 1 1 18.75 4.5 0.41 1.58 1.58 0.5 0.0 2.0
neighbor 0.474 bin
neigh_modify every 1 delay 0 check yes
fix 1 all mvv/tdpd 0.5
timestep 0.01
thermo 0
run {warmup}
run {steps}
"""


def lammps_rate(lmp, deck_text, work, tag, own_peak=False):
    """Runs one LAMMPS deck; returns particle-steps per CPU-second of the last run and the
    process record (peak RSS)."""
    deck = work / f"{tag}.in"
    log = work / f"{tag}.log"
    deck.write_text(deck_text)
    r = run_measured([lmp, "-in", deck, "-log", log, "-screen", "none"], cwd=work,
                     own_peak=own_peak)
    if r["rc"]:
        sys.exit(f"LAMMPS failed (exit {r['rc']}) on {deck}; see {log}")
    text = log.read_text()
    loops = re.findall(r"Loop time of ([\d.eE+-]+) on 1 procs for (\d+) steps with (\d+) atoms",
                       text)
    cpu_use = re.findall(r"([\d.]+)% CPU use", text)
    if not loops or not cpu_use:
        sys.exit(f"no loop time / CPU use in {log}")
    t, steps, atoms = float(loops[-1][0]), int(loops[-1][1]), int(loops[-1][2])
    cpu = t * float(cpu_use[-1]) / 100.0
    return atoms * steps / cpu, atoms, r


def env1():
    e = dict(os.environ)
    e["OMP_NUM_THREADS"] = "1"
    return e


def ours_sdpd(build, dim, side, steps):
    n = side ** dim
    r = subprocess.run([build / "bench/fluid/fluid_bench", "--case", str(dim), str(n), "1",
                        str(steps)], capture_output=True, text=True, env=env1(), check=True)
    return float(re.search(r"thread\(s\): ([\d.eE+-]+) particle-steps/CPU-s", r.stdout).group(1))


def ours_tdpd(build, work):
    out = work / "tdpd.json"
    subprocess.run([build / "bench/fluid_tdpd/fluid_tdpd_bench", str(out), "--small"],
                   capture_output=True, text=True, env=env1(), check=True)
    rows = json.loads(out.read_text())["runs"]
    return next(x["rate"] for x in rows if x["species"] == 1)


def ours_nsm(build, scenario, side, events, baseline=0):
    cmd = [build / "bench/ssa/ssa_bench", scenario, "--events", f"{events:g}",
           "--baseline-events", str(baseline)]
    if scenario == "a" and side != 32:
        cmd += ["--n", str(side)]
    p = subprocess.run(cmd, capture_output=True, text=True, env=env1(), check=True)
    return json.loads(p.stdout.splitlines()[0])


def peer_nsm(urdme, side, molecules, reactions, events):
    p = subprocess.run([urdme, str(side), str(molecules), str(reactions), f"{events:g}", "1"],
                       capture_output=True, text=True, check=True)
    return json.loads(p.stdout.splitlines()[-1])


def sdpd_deck(dim, side, steps):
    return SDPD_DECK.format(dim=dim, lat="sc" if dim == 3 else "sq", n=side,
                            zlo=0 if dim == 3 else -0.5, zhi=side if dim == 3 else 0.5,
                            enforce="fix 2 all enforce2d" if dim == 2 else "", steps=steps)


def timing(a, work):
    rows = []

    def pairs(name, unit, ours_fn, peer_fn, peer_name, higher_is_better):
        ratios, o_all, p_all = [], [], []
        for k in range(a.pairs):
            order = (ours_fn, peer_fn) if k % 2 == 0 else (peer_fn, ours_fn)
            res = {f: f() for f in order}
            o, p = res[ours_fn], res[peer_fn]
            o_all.append(o)
            p_all.append(p)
            ratios.append(o / p if higher_is_better else p / o)
            print(f"  {name} pair {k + 1}: ours {o:.4g}, {peer_name} {p:.4g} {unit} -> "
                  f"{ratios[-1]:.2f}x", flush=True)
        rows.append({"case": name, "unit": unit, "peer": peer_name, "ours": o_all, "peer_values": p_all,
                     "ratios": ratios, "median": statistics.median(ratios), "min": min(ratios),
                     "max": max(ratios)})

    only = set(a.only.split(","))
    if "sdpd" in only:
        for name, dim, side, steps in SDPD_CASES:
            pairs(name, "particle-steps/CPU-s",
                  lambda d=dim, s=side, st=steps: ours_sdpd(a.build, d, s, st),
                  lambda d=dim, s=side, st=steps, nm=name: lammps_rate(
                      a.lammps, sdpd_deck(d, s, st), work, nm.replace(" ", "_"))[0],
                  "LAMMPS", True)
    if "tdpd" in only:
        pairs("tDPD 1 species 1e4", "particle-steps/CPU-s", lambda: ours_tdpd(a.build, work),
              lambda: lammps_rate(a.lammps, TDPD_DECK.format(n=22, warmup=20, steps=100), work,
                                  "tdpd")[0], "LAMMPS", True)
    if "nsm" in only:
        for name, sc, side, mol, rx, ev in NSM_CASES:
            pairs(name, "ns/event", lambda s=sc, sd=side, e=ev: ours_nsm(a.build, s, sd, e)["ns_per_event"],
                  lambda sd=side, m=mol, r=rx, e=ev: peer_nsm(a.urdme, sd, m, r, e)["ns_per_event"],
                  "URDME", False)
    return rows


def memory(a, work):
    """Peak RSS slope between two sizes, ours and the peer's, per particle / voxel."""
    out = []

    def slope(fn, sizes):
        (n1, k1), (n2, k2) = (fn(s) for s in sizes)
        return (k2 - k1) * 1024.0 / (n2 - n1), k1, k2, n1, n2

    def ours_fluid(dim):
        def f(side):
            n = side ** dim
            r = run_measured([a.build / "bench/fluid/fluid_bench", "--case", dim, n, 1, 2],
                             env=env1(), own_peak=True)
            return n, r["maxrss_kib"]
        return f

    def peer_fluid(dim):
        def f(side):
            _, atoms, r = lammps_rate(a.lammps, sdpd_deck(dim, side, 2), work, f"mem{dim}_{side}",
                                      own_peak=True)
            return atoms, r["maxrss_kib"]
        return f

    def ours_ssa(side):
        r = run_measured([a.build / "bench/ssa/ssa_bench", "a", "--n", side, "--events", "1e5",
                          "--baseline-events", 0], env=env1(), own_peak=True)
        return side ** 3, r["maxrss_kib"]

    def peer_ssa(side):
        r = run_measured([a.urdme, side, 3 * side ** 3, 0, "1e5", 1], own_peak=True)
        return side ** 3, r["maxrss_kib"]

    only = set(a.only.split(","))
    for name, dim, sizes in (("SDPD 3D", 3, (22, 46)), ("SDPD 2D", 2, (100, 316))):
        if "sdpd" not in only:
            break
        o = slope(ours_fluid(dim), sizes)
        p = slope(peer_fluid(dim), sizes)
        out.append({"case": f"{name}, bytes per particle (h = 3 dx)", "ours": o[0], "peer": p[0],
                    "peer_name": "LAMMPS", "sizes": [o[3], o[4]],
                    "ours_peak_kib": [o[1], o[2]], "peer_peak_kib": [p[1], p[2]]})
        print(f"  memory {name}: ours {o[0]:.0f} B/particle, LAMMPS {p[0]:.0f}", flush=True)
    def ours_tdpd(side):
        size = "--small" if side == 22 else "--large"
        r = run_measured([a.build / "bench/fluid_tdpd/fluid_tdpd_bench", work / "tdpd_mem.json",
                          "--quick", size, "--species", 1, "--steps", 2], env=env1(), own_peak=True)
        return side ** 3, r["maxrss_kib"]

    def peer_tdpd(side):
        deck = TDPD_DECK.format(n=side, warmup=2, steps=5)
        _, atoms, r = lammps_rate(a.lammps, deck, work, f"memtdpd_{side}", own_peak=True)
        return atoms, r["maxrss_kib"]

    if "tdpd" in only:
        o = slope(ours_tdpd, (22, 46))
        p = slope(peer_tdpd, (22, 46))
        out.append({"case": "tDPD 1 species, bytes per particle (rho = 4, r_c = 1.58)",
                    "ours": o[0], "peer": p[0], "peer_name": "LAMMPS", "sizes": [o[3], o[4]],
                    "ours_peak_kib": [o[1], o[2]], "peer_peak_kib": [p[1], p[2]]})
        print(f"  memory tDPD: ours {o[0]:.0f} B/particle, LAMMPS {p[0]:.0f}", flush=True)
    if "nsm" in only:
        o = slope(ours_ssa, (32, 64))
        p = slope(peer_ssa, (32, 64))
        out.append({"case": "NSM, bytes per voxel (case (a) lattice, 32^3 -> 64^3, "
                            "3 molecules/voxel)",
                    "ours": o[0], "peer": p[0], "peer_name": "URDME", "sizes": [o[3], o[4]],
                    "ours_peak_kib": [o[1], o[2]], "peer_peak_kib": [p[1], p[2]]})
        print(f"  memory NSM: ours {o[0]:.0f} B/voxel, URDME {p[0]:.0f}", flush=True)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(ROOT / "build/release"))
    ap.add_argument("--lammps", required=True, help="the LAMMPS binary (lmp), built elsewhere")
    ap.add_argument("--urdme", required=True, help="the URDME nsm() driver, built elsewhere")
    ap.add_argument("--pairs", type=int, default=5)
    ap.add_argument("--only", default="sdpd,tdpd,nsm")
    ap.add_argument("--memory", action="store_true", help="peak RSS per particle/voxel instead")
    ap.add_argument("--smoke", action="store_true",
                    help="every case 1/100 as long: checks that the script and both sides run; "
                         "its figures mean nothing")
    ap.add_argument("--out", default=str(ROOT / "bench/results/peers_side_by_side"))
    a = ap.parse_args()
    a.build = pathlib.Path(a.build).resolve()
    a.lammps = pathlib.Path(a.lammps).resolve()
    a.urdme = pathlib.Path(a.urdme).resolve()
    if a.smoke:
        global SDPD_CASES, NSM_CASES
        SDPD_CASES = [(n, d, s, max(1, st // 100)) for n, d, s, st in SDPD_CASES]
        NSM_CASES = [(n, sc, sd, m, r, ev / 100) for n, sc, sd, m, r, ev in NSM_CASES]
    load = os.getloadavg()
    stamp = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    cmd = "bench/peers/side_by_side.py " + " ".join(sys.argv[1:])
    with tempfile.TemporaryDirectory(prefix="sadr-peers-") as tmp:
        work = pathlib.Path(tmp)
        rows = memory(a, work) if a.memory else timing(a, work)
    load_end = os.getloadavg()
    rev = commit()
    lines = [f"Side by side, {stamp}, code at `{rev}`, load average {load[0]:.1f} at the start, "
             f"{load_end[0]:.1f} at the end; `{cmd}`", ""]
    if a.smoke:
        lines = ["**--smoke: every case 1/100 as long; these figures mean nothing.**", ""] + lines
    if a.memory:
        lines += ["| process peak RSS (slope between two sizes) | ours | peer | ours / peer |",
                  "|---|---|---|---|"]
        for r in rows:
            lines.append(f"| {r['case']} | {r['ours']:.0f} B | {r['peer_name']} {r['peer']:.0f} B "
                         f"| {r['ours'] / r['peer']:.2f}x |")
    else:
        lines += [f"| case ({a.pairs} interleaved pairs, 1 thread, CPU time) | ours (median) "
                  "| peer (median) | ours / peer: median (min-max) |", "|---|---|---|---|"]
        for r in rows:
            lines.append(f"| {r['case']} | {statistics.median(r['ours']):.3g} {r['unit']} | "
                         f"{r['peer']} {statistics.median(r['peer_values']):.3g} | "
                         f"**{r['median']:.2f}x** ({r['min']:.2f}-{r['max']:.2f}) |")
        lines += ["", "Ratios are speed ours / peer (for ns/event: peer / ours), per pair."]
    text = "\n".join(lines) + "\n"
    print("\n" + text)
    out = pathlib.Path(a.out + ("_memory" if a.memory else ""))
    out.parent.mkdir(parents=True, exist_ok=True)
    out.with_suffix(".md").write_text(text)
    out.with_suffix(".json").write_text(json.dumps(
        {"command": cmd, "commit": rev, "utc": stamp, "load": [load, load_end], "rows": rows},
        indent=1) + "\n")


if __name__ == "__main__":
    main()
