#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Per-process cost of coupled_step.py's scene in the processes mode.

coupled_step.py reports times the services measure (fluid_compute, ssa_graph,
ssa_nsm) and call times; on a loaded 2-core machine those are wall times of
processes that compete for the cores. This probe runs the same scene (its
SCENE text, imported) with `sadr run` and wraps each service executable, so
that per process it can report:

  --wrap rusage     CPU seconds (user + sys) and context switches of
                    fluid_service, ssa_service and sadr itself (wait4's rusage)
  --wrap callgrind  instructions (Ir) per process, each service under
                    valgrind --tool=callgrind (load-independent); sadr itself
                    runs natively (its Ir: --wrap callgrind-sadr, with
                    --env OMP_WAIT_POLICY=passive: else sadr re-executes itself
                    to set it, which valgrind does not follow)
  --wrap callgrind-cache  the same with --cache-sim=yes: simulated D1 and
                    last-level cache misses per process (valgrind's model
                    cache, not the host's)
  --wrap strace     system calls per process (strace -f -c)

How: sadr starts its services from the directory of its own executable, so
the probe copies `sadr` into a scratch bin/ and puts small wrappers named
fluid_service and ssa_service beside it; each wrapper forks the real service
(of the same build) under the chosen tool, forwards SIGTERM, waits for it and
writes its rusage as JSON. SADR_PARENT_PID (the services' parent-death
watchdog) is set to the service's real parent: the wrapper, or strace.

Per coupling step: run the scene at --steps A and B (A < B) and divide the
difference by B - A, which removes Init, the frame and the shutdown.

Usage: processes_probe.py --sadr BUILD/bin/sadr [--size 10000] [--steps 8 24]
                          [--wrap rusage|callgrind|callgrind-cache|callgrind-sadr|strace] [--mode processes|embedded]
                          [--repeat R] [--env OMP_WAIT_POLICY=passive] [--extra "--no-overlap"]
Prints one JSON object per repetition: the per-step differences per process
("per_step", "per_step_ms" of run.json's timings) and both runs in full.
"""
import argparse, glob, json, math, os, shutil, subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from coupled_step import SCENE  # noqa: E402  (the benchmark's scene, unchanged)

WRAPPER = r'''#!/usr/bin/python3
import json, os, resource, signal, sys
name = os.path.basename(sys.argv[0])
out = os.environ["PROBE_OUT"]
tool = json.loads(os.environ.get("PROBE_TOOL", "[]"))
real = os.path.join(os.environ["PROBE_REAL_BIN"], name)
me = os.getpid()
tool = [t.replace("%NAME%", name).replace("%PID%", str(me)).replace("%OUT%", out) for t in tool]
forks = bool(tool) and os.path.basename(tool[0]) == "strace"  # strace forks the service
pid = os.fork()
if pid == 0:
    # The service's parent: this wrapper, or strace (this child, after exec).
    os.environ["SADR_PARENT_PID"] = str(os.getpid() if forks else me)
    argv = tool + [real] + sys.argv[1:]
    os.execvp(argv[0], argv)


def forward(sig, frame):
    target = pid
    if forks:  # to the service itself; strace then writes its summary
        try:
            with open(f"/proc/{pid}/task/{pid}/children") as f:
                kids = f.read().split()
            target = int(kids[0]) if kids else pid
        except OSError:
            pass
    os.kill(target, sig)


signal.signal(signal.SIGTERM, forward)
signal.signal(signal.SIGINT, forward)
while True:
    try:
        _, status, ru = os.wait4(pid, 0)
        break
    except ChildProcessError:
        sys.exit(1)
me_ru = resource.getrusage(resource.RUSAGE_SELF)
with open(os.path.join(out, f"rusage-{name}-{me}.json"), "w") as f:
    json.dump({"name": name, "user": ru.ru_utime, "sys": ru.ru_stime, "nvcsw": ru.ru_nvcsw,
               "nivcsw": ru.ru_nivcsw, "minflt": ru.ru_minflt, "majflt": ru.ru_majflt,
               "maxrss_kb": ru.ru_maxrss, "wrapper_cpu": me_ru.ru_utime + me_ru.ru_stime,
               "status": status}, f)
sys.exit(os.waitstatus_to_exitcode(status) if hasattr(os, "waitstatus_to_exitcode") else 0)
'''


def make_bin(sadr, work):
    real_bin = os.path.dirname(os.path.abspath(sadr))
    b = os.path.join(work, "bin")
    os.makedirs(b, exist_ok=True)
    shutil.copy2(sadr, os.path.join(b, "sadr"))
    for name in ("fluid_service", "ssa_service"):
        p = os.path.join(b, name)
        with open(p, "w") as f:
            f.write(WRAPPER)
        os.chmod(p, 0o755)
    return b, real_bin


def callgrind_events(path):
    """{event: total} of a callgrind.out file ('events:' and 'totals:'/'summary:' lines):
    Ir, and with --cache-sim=yes also Dr, Dw, I1mr, D1mr, D1mw, ILmr, DLmr, DLmw."""
    names, totals = [], {}
    with open(path, errors="replace") as f:
        for line in f:
            if line.startswith("events:"):
                names = line.split()[1:]
            elif line.startswith("totals:") or line.startswith("summary:"):
                totals = dict(zip(names, map(int, line.split()[1:])))
    return totals


def strace_calls(path):
    """{syscall: calls} from a `strace -c` summary file."""
    calls = {}
    with open(path) as f:
        for line in f:
            parts = line.split()
            if len(parts) >= 5 and parts[0][0].isdigit() and parts[-1] != "total":
                try:
                    calls[parts[-1]] = int(parts[3])
                except ValueError:
                    pass
    return calls


def run_once(a, steps, work, b, real_bin):
    L = int(round(math.sqrt(a.size)))
    tau = 0.05
    scene = os.path.join(work, f"scene-{steps}.yaml")
    species = "species:\n  - {name: A, diffusivity: 5.0, initial: [{region: all, count: 1}]}\n"
    with open(scene, "w") as f:
        f.write(SCENE.format(n=L * L, L=float(L), species=species, tau=tau, end=tau * steps))
    out = tempfile.mkdtemp(prefix=f"probe-{steps}-", dir=work)
    tool = []
    if a.wrap in ("callgrind", "callgrind-cache"):
        tool = ["valgrind", "--tool=callgrind", "--callgrind-out-file=%OUT%/callgrind.%NAME%.%PID%"]
        if a.wrap == "callgrind-cache":
            tool.insert(2, "--cache-sim=yes")
    elif a.wrap == "strace":
        tool = ["strace", "-f", "-c", "-o", "%OUT%/strace.%NAME%.%PID%"]
    env = dict(os.environ, PROBE_OUT=out, PROBE_REAL_BIN=real_bin, PROBE_TOOL=json.dumps(tool))
    for kv in a.env:
        k, v = kv.split("=", 1)
        env[k] = v
    cmd = [os.path.join(b, "sadr"), "run", scene, "-q", "-o", os.path.join(out, "run"), "--force",
           "--timeout", "600"]
    if a.mode == "embedded":
        cmd.append("--embedded")
    cmd += a.extra.split()
    if a.wrap == "callgrind-sadr":
        cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}/callgrind.sadr.%p"] + cmd
    elif a.wrap == "strace":
        cmd = ["strace", "-c", "-o", f"{out}/strace.sadr.main"] + cmd
    p = subprocess.Popen(cmd, env=env, stderr=subprocess.DEVNULL)
    _, status, ru = os.wait4(p.pid, 0)
    if status != 0:
        raise SystemExit(f"sadr failed ({status}): {' '.join(cmd)}")
    with open(os.path.join(out, "run", "run.json")) as f:
        j = json.load(f)
    r = {"steps": steps, "timings_s": j["timings_s"], "fluid_substeps": j.get("fluid_substeps"),
         "overlapped_steps": j.get("overlapped_steps"), "procs": {}}
    total_cpu = ru.ru_utime + ru.ru_stime  # sadr plus the reaped wrappers and services
    services_cpu = 0.0
    for path in glob.glob(os.path.join(out, "rusage-*.json")):
        with open(path) as f:
            s = json.load(f)
        r["procs"][s["name"]] = {"cpu_s": s["user"] + s["sys"], "user_s": s["user"],
                                 "sys_s": s["sys"], "nvcsw": s["nvcsw"], "nivcsw": s["nivcsw"],
                                 "minflt": s["minflt"], "maxrss_kb": s["maxrss_kb"]}
        services_cpu += s["user"] + s["sys"] + s["wrapper_cpu"]
    r["procs"]["sadr"] = {"cpu_s": total_cpu - services_cpu, "nvcsw": ru.ru_nvcsw,
                          "nivcsw": ru.ru_nivcsw, "minflt": ru.ru_minflt}  # csw: sadr and its reaped children
    for path in glob.glob(os.path.join(out, "callgrind.*")):
        name = os.path.basename(path).split(".")[1]
        d = r["procs"].setdefault(name, {})
        for k, v in callgrind_events(path).items():
            d[k] = d.get(k, 0) + v
        d.setdefault("callgrind_files", []).append(path)
    for path in glob.glob(os.path.join(out, "strace.*")):
        name = os.path.basename(path).split(".")[1]
        r["procs"].setdefault(name, {})["syscalls"] = strace_calls(path)
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sadr", required=True)
    ap.add_argument("--size", type=int, default=10000)
    ap.add_argument("--steps", type=int, nargs=2, default=[8, 24])
    ap.add_argument("--wrap", default="rusage",
                    choices=["rusage", "callgrind", "callgrind-cache", "callgrind-sadr", "strace"])
    ap.add_argument("--mode", default="processes", choices=["processes", "embedded"])
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--env", action="append", default=[], help="NAME=VALUE for sadr and the services")
    ap.add_argument("--extra", default="", help="more sadr run options")
    ap.add_argument("--work", default=None, help="scratch directory (kept)")
    ap.add_argument("--label", default="")
    a = ap.parse_args()
    work = a.work or tempfile.mkdtemp(prefix="sadr-probe-")
    os.makedirs(work, exist_ok=True)
    b, real_bin = make_bin(a.sadr, work)
    lo, hi = a.steps
    for rep in range(a.repeat):
        runs = {s: run_once(a, s, work, b, real_bin) for s in (lo, hi)}
        per = {}
        for name in sorted(set(runs[lo]["procs"]) | set(runs[hi]["procs"])):
            x, y = runs[lo]["procs"].get(name, {}), runs[hi]["procs"].get(name, {})
            d = {}
            for k in ("cpu_s", "user_s", "sys_s", "nvcsw", "nivcsw", "minflt",
                      "Ir", "Dr", "Dw", "I1mr", "D1mr", "D1mw", "ILmr", "DLmr", "DLmw"):
                if k in x and k in y:
                    d[k] = (y[k] - x[k]) / (hi - lo)
            if "syscalls" in x and "syscalls" in y:
                d["syscalls"] = {c: (y["syscalls"].get(c, 0) - x["syscalls"].get(c, 0)) / (hi - lo)
                                 for c in sorted(set(x["syscalls"]) | set(y["syscalls"]))}
            per[name] = d
        tl, th = runs[lo]["timings_s"], runs[hi]["timings_s"]
        per_t = {k: 1e3 * (th.get(k, 0) - tl.get(k, 0)) / (hi - lo) for k in sorted(th)}
        print(json.dumps({"label": a.label, "sadr": a.sadr, "mode": a.mode, "wrap": a.wrap,
                          "env": a.env, "extra": a.extra, "steps": [lo, hi], "repeat": rep,
                          "per_step": per, "per_step_ms": per_t,
                          "loadavg": open("/proc/loadavg").read().split()[:3],
                          "runs": runs}), flush=True)


if __name__ == "__main__":
    main()
