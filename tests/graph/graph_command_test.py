#!/usr/bin/python3
"""`sadr graph` against a hand-computed graph, and the isolated-voxel warning
(issue #18).

    graph_command_test.py BIN_DIR

1. A 1D walled box [0, 1], spacing dx = 0.25 (5 particles, V = 0.25), h = 2 dx
   = 0.5: edges join r < h, so only nearest neighbours (r = 0.25): a chain of
   4 pairs, 8 directed edges. With the default (volume) convention
   D_ij = 2 V_j F(r) reg, F = 12 alpha (1 - q)^2 / h^2, alpha = 5 / (4 h) = 2.5,
   q = r / h = 1/2: F = 12 * 2.5 * 0.25 / 0.25 = 30; reg = r^2 / (r^2 + 0.01 h^2)
   = 0.0625 / 0.065; D = 2 * 0.25 * 30 * 0.0625 / 0.065 = 14.423076923076923.
   Rates kappa D: A (0.01) 0.14423076923076923, B (0.02) 0.28846153846153844.
   Degrees 1, 2, 2, 2, 1; one component; nothing isolated.
2. The same box filled only on [0, 0.5] and at x = 1: particle 3 (x = 1) has no
   neighbour within h: `sadr validate` warns with the count and the particle,
   and the graph has 2 components.
"""
import csv, io, json, math, os, subprocess, sys, tempfile

BASE = """name: chain
dimension: 1
box: {{lower: [0.0], upper: [1.0]}}
{regions}
particles:
  spacing: 0.25
{fill}
fluid: {{backend: static, h_over_dx: 2.0}}
species:
  - {{name: A, diffusivity: 0.01, initial: [{{count: 1}}]}}
  - {{name: B, diffusivity: 0.02}}
time: {{coupling_step: 0.1, end: 1.0}}
"""
D = 2 * 0.25 * 30 * 0.0625 / 0.065


def close(a, b):
    return math.isclose(a, b, rel_tol=1e-13)


def main():
    sadr = os.path.join(os.path.abspath(sys.argv[1]), "sadr")
    failures = []
    with tempfile.TemporaryDirectory(prefix="graph-") as d:
        chain = os.path.join(d, "chain.yaml")
        with open(chain, "w") as f:
            f.write(BASE.format(regions="", fill=""))
        r = subprocess.run([sadr, "graph", chain, "--format", "csv"], capture_output=True,
                           text=True)
        if r.returncode != 0:
            sys.exit(f"sadr graph failed: {r.stderr}")
        rows = list(csv.DictReader(io.StringIO(r.stdout)))
        pairs = sorted((int(x["source"]), int(x["target"])) for x in rows)
        want = sorted([(i, i + 1) for i in range(4)] + [(i + 1, i) for i in range(4)])
        if pairs != want:
            failures.append(f"edges {pairs}, expected {want}")
        for x in rows:
            w, a, b = float(x["weight"]), float(x["rate_A"]), float(x["rate_B"])
            if not (close(w, D) and close(a, 0.01 * D) and close(b, 0.02 * D)):
                failures.append(f"edge {x['source']}->{x['target']}: D = {w!r}, rates {a!r}, "
                                f"{b!r}; expected {D!r}, {0.01 * D!r}, {0.02 * D!r}")
        print(f"chain: {len(rows)} edges, D_ij = {float(rows[0]['weight'])!r} "
              f"(hand: {D!r})")
        out = os.path.join(d, "chain.json")
        r = subprocess.run([sadr, "graph", chain, "-o", out], capture_output=True, text=True)
        j = json.load(open(out))
        g = j["diagnostics"]
        expect = {"edges": 8, "components": 1, "isolated": 0, "min_degree": 1, "max_degree": 2}
        for k, v in expect.items():
            if g[k] != v:
                failures.append(f"json diagnostics {k} = {g[k]}, expected {v}")
        if not (close(g["min_rate"], 0.01 * D) and close(g["max_rate"], 0.02 * D)):
            failures.append(f"json rates [{g['min_rate']}, {g['max_rate']}]")
        if len(j["edges"]) != 8 or not close(j["edges"][0][2], D):
            failures.append(f"json edges {j['edges'][:2]}")
        if "1 connected component" not in r.stderr:
            failures.append(f"sadr graph diagnostics on stderr: {r.stderr!r}")
        # 2. an isolated particle
        gap = os.path.join(d, "gap.yaml")
        with open(gap, "w") as f:
            f.write(BASE.format(
                regions="regions:\n  - {name: near, shape: box, lower: [0.0], upper: [0.5]}\n"
                        "  - {name: far, shape: box, lower: [0.9], upper: [1.0]}",
                fill="  fill:\n    - {region: near}\n    - {region: far}"))
        r = subprocess.run([sadr, "validate", gap], capture_output=True, text=True)
        msg = "1 of 4 fluid voxels of the SSA graph have no fluid neighbour within h (e.g. particle 3)"
        if r.returncode != 0 or msg not in r.stderr:
            failures.append(f"validate of the gap scene: exit {r.returncode}, stderr {r.stderr!r}")
        if "2 connected components (largest 3), 1 isolated" not in r.stderr:
            failures.append(f"plan lines of the gap scene: {r.stderr!r}")
        r = subprocess.run([sadr, "run", gap, "-o", os.path.join(d, "gap_out"), "-q"],
                           capture_output=True, text=True)
        if r.returncode != 0 or msg not in r.stderr:
            failures.append(f"run -q of the gap scene: exit {r.returncode}, {r.stderr!r}")
    for f in failures:
        print("FAIL", f)
    sys.exit(1 if failures else 0)


main()
