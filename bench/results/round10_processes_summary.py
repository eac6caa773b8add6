#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Summary of bench/results/round10_processes.sh's raw files in directory T."""
import json, os, re, statistics, sys

T = sys.argv[1] if len(sys.argv) > 1 else "/tmp/r10"


def rows(name):
    path = os.path.join(T, name)
    return [json.loads(l) for l in open(path)] if os.path.exists(path) else []


def q(v):
    v = sorted(v)
    if not v:
        return "-"
    qs = statistics.quantiles(v, n=4) if len(v) >= 2 else [v[0]] * 3
    return f"median {statistics.median(v):.3f} (quartiles {qs[0]:.3f}-{qs[2]:.3f}, range {v[0]:.3f}-{v[-1]:.3f}, n {len(v)})"


print("## 1. per coupling step (callgrind; difference of 12- and 4-step runs / 8), millions")
print("   Ir: instructions; D1mr/D1mw: simulated L1 data read/write misses; DLmr/DLmw: last level")
ev = {}
for r in rows("callgrind.json"):
    for p, d in r["per_step"].items():
        if d.get("Ir"):
            ev[(r["label"], p)] = d
for p in ("fluid_service", "ssa_service", "sadr"):
    o, n = ev.get(("old", p)), ev.get(("new", p))
    if o and n:
        for k in ("Ir", "D1mr", "D1mw", "DLmr", "DLmw"):
            if k in o and k in n:
                ratio = f"  new/old {n[k]/o[k]:.4f}" if k == "Ir" or abs(o[k]) > 1e4 else ""
                print(f"{p:14s} {k:5s} old {o[k]/1e6:10.3f}  new {n[k]/1e6:10.3f}{ratio}")

print("\n## 2. system calls per coupling step (strace -c; difference of 40- and 10-step runs / 30)")
st = {r["label"]: r["per_step"] for r in rows("strace.json")}
if "old" in st and "new" in st:
    for p in ("sadr", "fluid_service", "ssa_service"):
        o, n = st["old"].get(p, {}).get("syscalls", {}), st["new"].get(p, {}).get("syscalls", {})
        print(f"{p}: total old {sum(o.values()):.1f} new {sum(n.values()):.1f}"
              + ("  (sadr: main thread only)" if p == "sadr" else ""))
        for c in sorted(set(o) | set(n)):
            if abs(o.get(c, 0)) >= 0.2 or abs(n.get(c, 0)) >= 0.2:
                print(f"   {c:14s} old {o.get(c, 0):6.2f}  new {n.get(c, 0):6.2f}")

print("\n## 3. coupled_step.py, rounds of old new new old (ratios of ms per step)")
pat = re.compile(r"^(old|new) r(\d+) (\S+) N=\s*\d+ .*?(?:embedded|processes)\s+fluid\s+([\d.]+)\s+transfer\s+([\d.]+)"
                 r"\s+rebuild\s+([\d.]+)\s+nsm\s+([\d.]+)\s+total\s+([\d.]+).*wall ([\d.]+)")
runs = {}
path = os.path.join(T, "coupled.txt")
for line in open(path) if os.path.exists(path) else []:
    m = pat.match(line)
    if m:
        b, r, mode = m.group(1), int(m.group(2)), m.group(3)
        vals = dict(zip(("fluid", "transfer", "rebuild", "nsm", "total", "wall"), map(float, m.groups()[3:])))
        runs.setdefault((mode, r), []).append((b, vals))
for mode in ("processes", "embedded", "processes-no-overlap"):
    rs = [v for (md, _), v in sorted(runs.items()) if md == mode and len(v) == 4]
    if not rs:
        continue
    print(f"### {mode}: {len(rs)} rounds")
    for col in ("fluid", "transfer", "rebuild", "total", "wall"):
        ab = [x[1][1][col] / x[0][1][col] for x in rs] + [x[2][1][col] / x[3][1][col] for x in rs]
        aa = [x[3][1][col] / x[0][1][col] for x in rs]
        bb = [x[2][1][col] / x[1][1][col] for x in rs]
        old = [x[i][1][col] for x in rs for i in (0, 3)]
        new = [x[i][1][col] for x in rs for i in (1, 2)]
        up = sum(1 for v in ab if v > 1)
        print(f"{col:8s} old ms {statistics.median(old):6.2f}  new ms {statistics.median(new):6.2f}")
        print(f"         new/old {q(ab)}, {up} of {len(ab)} > 1")
        print(f"         old/old {q(aa)}")
        print(f"         new/new {q(bb)}")

print("\n## 4. CPU ms per coupling step per process (wait4 rusage; difference of 40- and 10-step runs / 30)")
cpu, csw = {}, {}
for r in rows("rusage.json"):
    for p, d in r["per_step"].items():
        cpu.setdefault((r["label"], p), []).append(1e3 * d["cpu_s"])
        csw.setdefault((r["label"], p), []).append(d.get("nvcsw", 0))
for p in ("fluid_service", "ssa_service", "sadr"):
    o, n = cpu.get(("old", p), []), cpu.get(("new", p), [])
    if o and n:
        print(f"{p:14s} old {', '.join(f'{x:.2f}' for x in o)} (median {statistics.median(o):.2f})")
        print(f"{'':14s} new {', '.join(f'{x:.2f}' for x in n)} (median {statistics.median(n):.2f})"
              f"  new/old of medians {statistics.median(n)/statistics.median(o):.3f}")
print("voluntary context switches per coupling step (sadr: with its reaped children), medians:")
for p in ("fluid_service", "ssa_service", "sadr"):
    o, n = csw.get(("old", p), []), csw.get(("new", p), [])
    if o and n:
        print(f"{p:14s} old {statistics.median(o):.1f}  new {statistics.median(n):.1f}")
