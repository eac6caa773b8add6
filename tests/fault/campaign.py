#!/usr/bin/python3
"""Fault campaign (issue #18): kill -9 or SIGSTOP of a random process of a
moving, checkpointing run at a random moment, each trial checked automatically.

    campaign.py BIN_DIR [--trials N] [--seed S] [--workdir DIR] [--timeout S]

One uninterrupted run of SCENE (sdpd, particles move, checkpoints every 0.1)
gives the reference frames. Then every trial picks a target (fluid_service,
ssa_service or sadr), a fault and a moment, and checks:

  detected   a service fault: sadr names the process in its error (exit != 0)
             or in its restart warning; kill -9 of sadr: exit by SIGKILL;
             SIGSTOP of sadr (continued after a pause): nothing to detect, the
             run must simply finish (counted as detected when it exits 0);
  recovered  the run completes with frames and .pvd byte-identical to the
             reference: in place (--restart-on-failure), or by `sadr resume`
             from the last checkpoint (a fresh `sadr run --force` when the
             fault came before the first checkpoint);
  leaked     none of the trial's processes runs afterwards, and no
             /dev/shm/sadr-geometry-<pid>-*, <tmp>/sadr-run-<pid>-* or
             <tmp>/sadr-<pid>-* of the trial's sadr processes is left.

Service faults alternate between runs with `--restart-on-failure 2` (sadr
relaunches the services itself; a stopped service is found by `--timeout`)
and runs without (sadr exits naming the process; then `sadr resume`).
A trial whose target had already exited before the fault landed is redrawn
(counted as `missed`). A service fault that sadr never notices because the
run no longer needed that service (past its last request; sadr's shutdown
then removes it) is counted as `after last request`, and passes only if the
frames are identical and nothing leaked. Exit 0 when every trial was detected, recovered
byte-identically and leaked nothing.
"""
import argparse, filecmp, glob, os, random, shutil, signal, subprocess, sys, tempfile, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sadr_procs import children, comm, running, traces  # noqa: E402

# Small but moving (sdpd), both services, checkpoints at every frame.
SCENE = """name: campaign
dimension: 2
box: {lower: [0.0, 0.0], upper: [1.0, 1.0], periodic: [true, true]}
regions:
  - {name: left, shape: box, lower: [0.0, 0.0], upper: [0.5, 1.0]}
particles:
  spacing: 0.0625
  fill:
    - {region: left, kind: fluid, velocity: [0.2, 0.1]}
    - {kind: fluid, velocity: [-0.2, 0.0]}
fluid: {backend: sdpd, h_over_dx: 3.0, sound_speed: 1.0, shear_viscosity: 0.05, temperature: 0.001}
species:
  - {name: A, diffusivity: 0.01, initial: [{count: 20, region: left}]}
  - {name: B, diffusivity: 0.005}
reactions:
  - {name: convert, equation: "A -> B", rate: 0.5}
time: {coupling_step: 0.01, end: 0.6}
output: {every: 0.1, checkpoint_every: 0.1, formats: [csv, vtu]}
seed: 18
"""

SERVICES = ("fluid_service", "ssa_service")


def output_files(d):
    """Relative paths of what must be byte-identical: frames and the .pvd."""
    files = sorted(os.path.relpath(p, d) for p in glob.glob(os.path.join(d, "frames", "*")))
    return files + sorted(os.path.relpath(p, d) for p in glob.glob(os.path.join(d, "*.pvd")))


def identical(ref, out):
    a, b = output_files(ref), output_files(out)
    if a != b:
        return f"file lists differ: {sorted(set(a) ^ set(b))[:4]}"
    for f in a:
        if not filecmp.cmp(os.path.join(ref, f), os.path.join(out, f), shallow=False):
            return f"{f} differs"
    return None


class Runner:
    def __init__(self, sadr, scene, timeout):
        self.sadr, self.scene, self.timeout = sadr, scene, timeout
        self.pids = set()   # every process of this trial (sadr and services)
        self.sadrs = set()  # the sadr processes (their pids name the traces)

    def start(self, args):
        p = subprocess.Popen([self.sadr] + args, stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True)
        self.pids.add(p.pid)
        self.sadrs.add(p.pid)
        return p

    def watch(self, p):
        for c in children(p.pid):
            self.pids.add(c)

    def finish(self, p, limit=300):
        """Waits for p (recording its children) and returns (exit code, stderr)."""
        t0 = time.monotonic()
        while p.poll() is None and time.monotonic() - t0 < limit:
            self.watch(p)
            time.sleep(0.01)
        if p.poll() is None:
            p.kill()
        _, err = p.communicate()
        return p.returncode, err

    def run(self, args):
        return self.finish(self.start(args))


def trial(k, rng, sadr, scene, ref_dir, duration, work, timeout):
    target = rng.choice(("fluid_service", "ssa_service", "sadr"))
    fault = rng.choice(("SIGKILL", "SIGSTOP"))
    restart = target != "sadr" and k % 2 == 0
    moment = rng.uniform(0.05, 0.85) * duration
    out = os.path.join(work, f"trial{k:03d}")
    shutil.rmtree(out, ignore_errors=True)
    r = Runner(sadr, scene, timeout)
    args = ["run", scene, "-o", out, "-q", "--timeout", str(timeout)]
    if restart:
        args += ["--restart-on-failure", "2"]
    p = r.start(args)
    t0 = time.monotonic()
    victim = None
    while p.poll() is None and time.monotonic() - t0 < moment:
        r.watch(p)
        time.sleep(0.002)
    if p.poll() is None:
        if target == "sadr":
            victim = p.pid
        else:
            victim = next((c for c in children(p.pid) if comm(c) == target), None)
    if victim is None:
        code, _ = r.finish(p)
        return {"missed": True, "target": target, "fault": fault}
    r.pids.add(victim)
    injected = time.monotonic() - t0
    os.kill(victim, getattr(signal, fault))
    if target == "sadr" and fault == "SIGSTOP":
        time.sleep(rng.uniform(0.2, 1.0))
        os.kill(victim, signal.SIGCONT)
    code, err = r.finish(p)
    # Detection.
    if target == "sadr":
        detected = code == -9 if fault == "SIGKILL" else code == 0
        why = f"exit {code}"
    else:
        named = target in err
        detected = named and (code != 0 or "restarting the services" in err)
        why = f"exit {code}, stderr names {target}: {named}"
        if code == 0 and not named:
            # The run never asked the victim again (it was past its last
            # request; sadr's shutdown kills it): harmless, if the frames agree.
            detected, why = "late", why + " (fault after the service's last request)"
    # Recovery.
    how = "in place"
    if code != 0:
        if os.path.exists(os.path.join(out, "checkpoint", "checkpoint.json")):
            how = "resume"
            code2, err2 = r.run(["resume", os.path.join(out, "checkpoint"), "-q", "--timeout", str(timeout)])
        else:
            how = "rerun"
            code2, err2 = r.run(["run", scene, "-o", out, "-q", "--force", "--timeout",
                                 str(timeout)])
        if code2 != 0:
            how += f" failed (exit {code2}: {err2.strip()[-200:]})"
    diff = identical(ref_dir, out)
    recovered = diff is None and "failed" not in how
    # Leaks: give the services their watchdog time, then look.
    t1 = time.monotonic()
    while any(running(q) for q in r.pids) and time.monotonic() - t1 < 5:
        time.sleep(0.02)
    left = [q for q in r.pids if running(q)]
    for q in left:
        os.kill(q, signal.SIGKILL)
    leaked = left + [t for s in r.sadrs for t in traces(s)]
    shutil.rmtree(out, ignore_errors=True) if recovered and not leaked else None
    return {"missed": False, "target": target, "fault": fault, "restart": restart,
            "at": injected, "detected": detected, "why": why, "recovered": recovered,
            "how": how, "diff": diff, "leaked": leaked, "stderr": err.strip()[-300:]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("bindir")
    ap.add_argument("--trials", type=int, default=50)
    ap.add_argument("--seed", type=int, default=18)
    ap.add_argument("--workdir")
    ap.add_argument("--timeout", type=float, default=5.0,
                    help="sadr --timeout: how long a stopped service goes unnoticed [s]")
    a = ap.parse_args()
    sadr = os.path.join(os.path.abspath(a.bindir), "sadr")
    work = a.workdir or tempfile.mkdtemp(prefix="sadr-campaign-")
    os.makedirs(work, exist_ok=True)
    scene = os.path.join(work, "campaign.yaml")
    with open(scene, "w") as f:
        f.write(SCENE)
    ref = os.path.join(work, "reference")
    shutil.rmtree(ref, ignore_errors=True)
    t0 = time.monotonic()
    ref_run = Runner(sadr, scene, a.timeout)
    code, err = ref_run.run(["run", scene, "-o", ref, "-q"])
    duration = time.monotonic() - t0
    if code != 0:
        sys.exit(f"reference run failed (exit {code}): {err}")
    print(f"reference: {len(output_files(ref))} files in {duration:.2f} s")
    rng = random.Random(a.seed)
    results, missed, k = [], 0, 0
    while len(results) < a.trials:
        res = trial(k, rng, sadr, scene, ref, duration, work, a.timeout)
        k += 1
        if res["missed"]:
            missed += 1
            continue
        results.append(res)
        ok = res["detected"] is not False and res["recovered"] and not res["leaked"]
        print(f"{len(results):3d} {res['target']:13s} {res['fault']:7s} "
              f"{'restart' if res['restart'] else '       '} at {res['at']:5.2f} s: "
              f"detected={res['detected']} recovered={res['recovered']} ({res['how']}) "
              f"leaked={len(res['leaked'])}{'' if ok else '  <-- ' + res['why'] + ' ' + str(res['diff']) + ' ' + str(res['leaked']) + ' | ' + res['stderr']}",
              flush=True)
    print("\n| target | fault | trials | detected | after last request | recovered byte-identical "
          "| leaked |")
    print("|---|---|---|---|---|---|---|")
    groups = sorted({(r["target"], r["fault"]) for r in results})
    for g in groups + [("all", "")]:
        rs = [r for r in results if g[0] == "all" or (r["target"], r["fault"]) == g]
        print(f"| {g[0]} | {g[1]} | {len(rs)} | {sum(r['detected'] is True for r in rs)} | "
              f"{sum(r['detected'] == 'late' for r in rs)} | "
              f"{sum(r['recovered'] for r in rs)} | {sum(len(r['leaked']) > 0 for r in rs)} |")
    print(f"\n{missed} draws missed their target (it had exited) and were redrawn")
    bad = [r for r in results
           if r["detected"] is False or not r["recovered"] or r["leaked"]]
    if not a.workdir and not bad:
        shutil.rmtree(work, ignore_errors=True)
    sys.exit(1 if bad else 0)


main()
