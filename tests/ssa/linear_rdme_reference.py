#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Exact mean and variance of a first-order RDME on an explicit graph (scipy), written for
tests/ssa/validation_test.cpp as an implementation independent of the C++ one
(tests/ssa/linear_exact.hpp, Eigen).

Input: the JSON of sadr::ssa::graph_to_json ("n_voxels", directed "edges" [[i, j, d_ij]],
"k" per-molecule decay A -> 0, "b" births 0 -> A per voxel (scalar or list), "x0", "fixed"
reservoir voxels {"index", "count"} held constant, "times", "variance").
For the free voxels F the mean obeys exactly dm/dt = M m + s with
    M = R_FF^T - diag(sum over all j of d_ij) - k I,   s_i = b_i + sum_w d_wi N_w,
so [m(t); 1] = expm(t [[M, s], [0, 0]]) [m0; 1]. Molecules move independently, so
X(t) = sum_j Multinomial(x0_j, P[:, j](t)) + Poisson(lam(t)) with P(t) = expm(M t) and lam the
mean started from zero (Jahnke & Huisinga 2007), hence
    Var X_i = sum_j x0_j P_ij (1 - P_ij) + lam_i.
Output CSV: t, voxel, mean, var (var empty when "variance" is false).

    linear_rdme_reference.py GRAPH.json --out MEAN.csv
"""
import argparse
import json

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import expm_multiply


def solve(g):
    n = int(g["n_voxels"])
    fixed = [int(i) for i in g.get("fixed", {}).get("index", [])]
    counts = dict(zip(fixed, (float(c) for c in g.get("fixed", {}).get("count", []))))
    free = [i for i in range(n) if i not in counts]
    pos = {v: a for a, v in enumerate(free)}
    nf = len(free)
    b = g.get("b", 0.0)
    b = np.full(n, float(b)) if np.isscalar(b) else np.asarray(b, dtype=float)
    out_rate = np.zeros(n)
    rows, cols, vals = [], [], []
    s = np.array([b[v] for v in free])
    for i, j, d in g["edges"]:
        i, j, d = int(i), int(j), float(d)
        out_rate[i] += d
        if i in pos and j in pos:  # dm_j/dt gains d_ij m_i
            rows.append(pos[j])
            cols.append(pos[i])
            vals.append(d)
        elif i in counts and j in pos:  # a reservoir emits into j
            s[pos[j]] += d * counts[i]
    k = float(g.get("k", 0.0))
    m = sp.csc_matrix((vals, (rows, cols)), shape=(nf, nf))
    m = m - sp.diags(np.array([out_rate[v] for v in free]) + k)
    aug = sp.bmat([[m, sp.csc_matrix(s.reshape(-1, 1))], [None, sp.csc_matrix((1, 1))]]).tocsc()
    x0 = np.asarray(g["x0"], dtype=float)
    m0 = np.array([x0[v] for v in free])
    result = []
    for t in g["times"]:
        t = float(t)
        mean = expm_multiply(t * aug, np.append(m0, 1.0))[:nf]
        var = None
        if g.get("variance", True):
            lam = expm_multiply(t * aug, np.append(np.zeros(nf), 1.0))[:nf]
            var = lam.copy()
            for a, v in enumerate(free):
                if x0[v] > 0:
                    e = np.zeros(nf)
                    e[a] = 1.0
                    col = expm_multiply(t * m.tocsc(), e)
                    var += x0[v] * col * (1.0 - col)
        for a, v in enumerate(free):
            result.append((t, v, mean[a], None if var is None else var[a]))
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("graph")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    with open(a.graph) as f:
        g = json.load(f)
    with open(a.out, "w") as f:
        f.write("t,voxel,mean,var\n")
        for t, v, mean, var in solve(g):
            f.write(f"{t!r},{v},{mean!r},{'' if var is None else repr(var)}\n")


if __name__ == "__main__":
    main()
