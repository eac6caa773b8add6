#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Writes the coagulation scenes from the one home of the model's numbers.

The species (Table II), the parameters (Table V, tDPD units, accelerated, corrected) and the
injury constants come from tests/data/refs/coagulation/cascade_reference.py; the decomposition
of the 23 source terms of li2015 Table III into 22 reactions with rate laws lives here (REACTIONS
below; docs/coagulation.md has the table). The reference integrates Table III as printed (sums of
terms per species), the scenes carry the reactions: the well-mixed test compares the two.

  /usr/bin/python3 bench/coagulation/make_scenes.py            # rewrite the four scenes
  /usr/bin/python3 bench/coagulation/make_scenes.py --check    # exit 1 if a scene differs

Scenes: examples/coagulation_well_mixed.yaml (one particle, static backend, Table III + the
injury sources of Table IV as volume sources, as the reference's `injury` case),
examples/coagulation_cascade.yaml (the li2015 channel, tdpd),
examples/coagulation_cascade_sdpd.yaml (the same chemistry and geometry on sdpd) and
examples/coagulation_cascade_prescribed.yaml (on the prescribed Poiseuille field: the run that
fits this machine, docs/coagulation.md).
"""
import argparse
import importlib.util
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location(
    "cascade_reference", REPO / "tests/data/refs/coagulation/cascade_reference.py")
ref = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ref)

# Table III as reactions: (name, equation, law). A law is ("ma", k) for mass action,
# ("mm", kcat, Km, catalyst) for Michaelis-Menten on the single reactant, or ("expr", text).
# Species indices of the paper in the comments ([i] = Table II index).
REACTIONS = [
    ("IX_act", "IX -> IXa", ("mm", "k9", "K9M", "XIa")),           # Q1, Q2
    ("IXa_AT", "IXa + ATIII -> 0", ("ma", "h9")),                  # Q1, Q15
    ("VIII_act", "VIII -> VIIIa", ("mm", "k8", "K8M", "IIa")),     # Q3, Q4 (sign corrected)
    ("VIIIa_decay", "VIIIa -> 0", ("ma", "h8")),                   # Q3
    ("VIIIa_APC", "VIIIa -> 0", ("mm", "hC8", "HC8M", "APC")),     # Q3
    ("V_act", "V -> Va", ("mm", "k5", "K5M", "IIa")),              # Q5, Q6
    ("Va_decay", "Va -> 0", ("ma", "h5")),                         # Q5
    ("Va_APC", "Va -> 0", ("mm", "hC5", "HC5M", "APC")),           # Q5
    ("X_act", "X -> Xa", ("mm", "k10", "K10M", "Z")),              # Q7, Q8 (tenase Z)
    ("Xa_AT", "Xa + ATIII -> 0", ("ma", "h10")),                   # Q7, Q15
    ("Xa_TFPI", "Xa + TFPI -> 0", ("ma", "hTFPI")),                # Q7, Q16
    ("II_act", "II -> IIa", ("mm", "k2", "K2M", "W")),             # Q9, Q10 (prothrombinase W)
    ("IIa_AT", "IIa + ATIII -> 0", ("ma", "h2")),                  # Q9, Q15
    ("I_act", "I -> Ia", ("mm", "k1", "K1M", "IIa")),              # Q11, Q12
    ("Ia_lysis", "Ia -> 0", ("mm", "h1", "H1M", "PLA")),           # Q11
    ("XI_act", "XI -> XIa", ("mm", "k11", "K11M", "IIa")),         # Q13, Q14
    ("XIa_AT", "XIa + ATIII -> 0", ("ma", "h11A3")),               # Q13, Q15
    ("XIa_a1AT", "XIa + a1AT -> 0", ("ma", "h11L1")),              # Q13, Q19
    ("PC_act", "PC -> APC", ("mm", "kPC", "KPCM", "IIa")),         # Q17, Q18
    ("APC_a1AT", "APC + a1AT -> 0", ("ma", "hPC")),                # Q17, Q19
    ("PLS_act", "PLS -> PLA", ("mm", "kPLA", "KPLAM", "tPA")),     # Q21, Q22
    ("PLA_a2AP", "PLA + a2AP -> 0", ("ma", "hPLA")),               # Q21, Q23
]

# Table IV: (species gaining, species losing or None, flux density law without the factor L).
INJURY = [
    ("IXa", "IX", "k79*TFVIIa*IX/(K79M + IX)"),
    ("Xa", "X", "k710*TFVIIa*X/(K710M + X)"),
    ("XIa", "XI", "phi11*XIIa*XI/(PHI11M + XI)"),
    ("tPA", None, "(ktPAC + ktPAIIa*exp(-ktPAIIa_decay*t)*IIa + ktPAIa*Ia)*ENDO"),
]
def chemistry_tail(p, regions, fluxes=False):
    """The assigned species, Table III as reactions and the injury terms: volume sources in
    `regions`, or (fluxes) no injury reaction here, the fluxes follow as `boundary_fluxes`."""
    lines = [f'  - {{name: {name}, assigned: "{expr}"}}   # [{idx}]'
             for name, idx, expr in ref.ASSIGNED]
    return lines + reactions_yaml(p) + ([] if fluxes else injury_reactions("LF", regions))


def injury_entries(factor, before="", after=""):
    """Table IV's terms as scene entries, the flux density times `factor`; `before` / `after`
    the keys placing them (a face and region for a flux, regions for a volume source)."""
    out = []
    for gain, lose, expr in INJURY:
        eq = f"{lose} -> {gain}" if lose else f"0 -> {gain}"
        out.append(f'  - {{name: injury_{gain}, equation: "{eq}", {before}'
                   f'law: {{type: expression, expression: "{factor}*{expr}"}}{after}}}')
    return out


def injury_fluxes(factor):
    """Table IV as what it is, Neumann flux laws on the injured wall (`boundary_fluxes`: the
    fluid's y- face inside region `injury`), the flux density times L = `factor`."""
    return (["boundary_fluxes:   # li2015 Table IV on the injured wall 10 < x < 20 (docs/coagulation.md)"]
            + injury_entries(factor, before="face: y-, region: injury, "))


def injury_reactions(factor, regions=""):
    """Table IV as volume sources: flux density x L / delta, `factor` the parameter name."""
    return (["  # Table IV injury terms as volume sources (flux density x L / delta)"]
            + injury_entries(factor, after=regions))


def num(v):
    return f"{v:.10g}"


def law_yaml(law, p, equation):
    if law[0] == "ma":
        return f"rate: {num(p[law[1]])}"
    if law[0] == "mm" and law[3] in {a[0] for a in ref.ASSIGNED}:
        # an assigned catalyst (Z, W) is no species of its own: the same law as an expression
        s = equation.split("->")[0].strip()  # the single reactant
        return law_yaml(("expr", f"{num(p[law[1]])}*{law[3]}*{s}/({num(p[law[2]])} + {s})"), p,
                        equation)
    if law[0] == "mm":
        return (f"law: {{type: michaelis_menten, kcat: {num(p[law[1]])}, Km: {num(p[law[2]])}, "
                f"catalyst: {law[3]}}}")
    return f'law: {{type: expression, expression: "{law[1]}"}}'


def parameters_yaml(p, extra):
    names = ["k79", "K79M", "k710", "K710M", "phi11", "PHI11M", "ktPAC", "ktPAIIa",
             "ktPAIIa_decay", "ktPAIa", "TFVIIa", "ENDO", "XIIa"]
    lines = ["parameters:   # Table IV constants (tDPD units, rates accelerated 1000x)"]
    for k, v in extra:
        lines.append(f"  {k}: {num(v)}")
    for k in names:
        lines.append(f"  {k}: {num(p[k])}")
    return lines


def reactions_yaml(p, indent="  "):
    out = ["reactions:   # li2015 Table III as 22 reactions (docs/coagulation.md)"]
    for name, eq, law in REACTIONS:
        out.append(f'{indent}- {{name: {name}, equation: "{eq}", {law_yaml(law, p, eq)}}}')
    return out


HEADER = "# GENERATED by bench/coagulation/make_scenes.py from tests/data/refs/coagulation/" \
         "cascade_reference.py; edit those, not this file."


def well_mixed():
    p = ref.rate_parameters()
    lines = [
        HEADER,
        "# The li2015 coagulation cascade (Anand et al. model, 25 species) in ONE well-mixed",
        "# voxel next to the injured wall: no flow, no diffusion. Table III as reactions plus the",
        "# Table IV injury terms as volume sources (flux density x L / delta, L = 100, delta = 1).",
        "# Deterministic species (integrated by fluid_service, Heun); compared with the scipy",
        "# Radau reference (case `injury`) by tests/python/test_coagulation.py. docs/coagulation.md.",
        "# Cost: about 1 s of CPU (examples/README.md).",
        "name: coagulation_well_mixed",
        "description: li2015 sec. III C cascade, one well-mixed voxel at the injury, tDPD units",
        "dimension: 1",
        "box: {lower: [0.0], upper: [1.0], periodic: [true]}",
        "particles: {spacing: 1.0}   # one particle (periodic cell centre x = 0.5), volume 1",
        "fluid:",
        "  backend: static",
        "  smoothing_length: 0.5",
        "  max_time_step: 0.005   # Heun sub-step; the reference error scales as its square",
    ]
    lines += parameters_yaml(p, [("LF", ref.L_INJURY / ref.DELTA)])
    lines.append("species:")
    for name, idx, c0, _ in ref.SPECIES:
        lines.append(f"  - {{name: {name}, stochastic: false, diffusivity: 0, "
                     f"initial: [{{concentration: {num(c0)}}}]}}   # [{idx}]")
    lines += chemistry_tail(p, "")
    lines += [
        "time: {coupling_step: 5.0, end: 400.0}",
        "output:",
        "  times: [" + ", ".join(num(t) for t in output_times(400.0, 5.0)) + "]",
        "  formats: [csv]",
        "seed: 1",
    ]
    return "\n".join(lines) + "\n"


def output_times(end, every):
    import numpy as np
    n = int(round(end / every))
    return list(np.unique(np.concatenate([np.linspace(0.0, min(5.0, end), 21),
                                          np.linspace(0.0, end, n + 1)])))


def channel(backend):
    """The li2015 channel, 100 long (x, the flow, periodic), 20 high (y, walls below y = 0 and
    above y = 20) and 10 deep (z, periodic): the paper's 100 x 10 x 20 with its height axis
    called y here, because the prescribed backend's Poiseuille field runs across y. The
    prescribed scene, the one run here, is the 2D x-y section of the same channel: nothing
    varies across the depth (periodic, the flow and the injury uniform in z), so the 3D problem
    is the 2D one; and its no-slip planes are the planes of the first and last fluid rows,
    y = 0 and y = 20 (the paper's H = 20), so the injury row stays on the injury."""
    p = ref.rate_parameters()
    tdpd = backend == "tdpd"
    slab = backend == "prescribed"
    # 160 x 32 x 16 cells of 0.625: number density 1/dx^3 = 4.096 (li2015: 4); the prescribed
    # scene (no momentum, the run that fits this machine) is coarser: dx = 1, h = 2 dx
    dx = 1.0 if slab else 0.625
    h = 2.9 if tdpd else (2 if slab else 3) * dx  # r_c or the SPH support
    nlayers = int(-(-h // dx))  # wall layers covering the interaction range
    ylo, yhi = -nlayers * dx, 20.0 + nlayers * dx
    rows = 1 if dx >= 1.0 else 2  # fluid rows of the injury layer, delta = rows dx
    delta = rows * dx
    u_max = 0.1386        # 1 mm/s in tDPD units (L* = 1 um, t* = 1.386e-4 s)
    h_eff = 20.0 + dx     # no-slip planes about half a spacing outside the last fluid rows
    depth = 10.0
    end = 600.0 if slab else 400.0
    # one fluid call per coupling step must answer within sadr's reply timeout (--timeout, 120 s):
    # ~10 sub-steps of tdpd (0.003, ~1 s CPU each here) or sdpd (7.9e-4, ~1.5 s CPU each) per
    # call; the prescribed scene's sub-step costs 4 ms (docs/coagulation.md, "The sdpd channel")
    tau = {"tdpd": 0.025, "sdpd": 0.01, "prescribed": 1.0}[backend]
    g = 8.0 * ref.NU * u_max / h_eff ** 2
    what = {"tdpd": "tdpd: the li2015 fluid (rho = 4, a = 18.75, gamma = 4.5, r_c = 2.9, "
                    "r_cc = 1.0)",
            "sdpd": "sdpd: an SDPD fluid of the same kinematic viscosity nu = 138.6",
            "prescribed": "prescribed: the Poiseuille field itself (no momentum equation), "
                          "no-slip at y = 0 and 20"}[backend]
    # 2D: the box, the regions and the lattice lose the depth coordinate
    zl, zu = ("", "") if slab else (", 0", f", {num(depth)}")
    size = "100 x 20 (x-y section)" if slab else f"100 x 20 x {num(depth)}"
    lines = [
        HEADER,
        "# li2015 sec. III C: coagulation and fibrinolysis in a micro-channel (Figs. 8-10), the",
        "# paper's 100 x 10 x 20 domain in tDPD units (L* = 1 um, t* = 1.386e-4 s, C* = 1 nM),",
        "# reactions accelerated 1000x; here x = flow (periodic), y = height 20 (the paper's z;",
        "# frozen wall layers below y = 0 and above y = 20), z = depth 10 (periodic"
        + ("; here its x-y section)." if slab else ")."),
        f"# Poiseuille flow with u_max = {u_max} (1 mm/s). The inlet buffer (0 <= x <= 2.9 = r_c)",
        "# holds every species at C_i0; particles carried out at x = 100 re-enter it. The injured",
        "# wall 10 < x < 20 (0.1 < x/L < 0.2) feeds the Table IV fluxes into the fluid next to it",
        ("# (tdpd has no per-particle boundary source: a layer of volume sources, delta = "
         f"{num(delta)},\n# the fluid particles there at t = 0, rate densities x L / delta; "
         "docs/coagulation.md \"Injury\")." if tdpd else
         "# as Neumann flux laws (`boundary_fluxes`) on the first fluid layer at y = 0 (the\n"
         "# particles there at t = 0; docs/coagulation.md \"Injury\")."),
        f"# Backend {what}.",
        {"tdpd": "# Cost: about 37 CPU hours to t = 400 (projected from a run to t = 0.05, 18.2 s of CPU).",
         "sdpd": "# Cost: about 220 CPU hours to t = 400 (projected from a run to t = 0.02, 40.7 s of CPU).",
         "prescribed": "# Cost: 5.2 CPU minutes to t = 600 (one fluid thread); examples/README.md."}[backend],
        "# docs/coagulation.md: the model, the corrections of the paper's tables, what was run.",
        f"name: coagulation_cascade{'' if tdpd else '_' + backend}",
        f"description: li2015 coagulation cascade in a {size} channel ({backend})",
        f"dimension: {2 if slab else 3}",
        "box:",
        f"  lower: [0.0, {num(ylo)}{', 0.0' if not slab else ''}]",
        f"  upper: [100.0, {num(yhi)}{zu}]",
        f"  periodic: [true, false{'' if slab else ', true'}]",
        "regions:",
        f"  - {{name: wall_lo, shape: box, lower: [0, {num(ylo)}{zl}], upper: [100, -0.3{zu}]}}",
        f"  - {{name: wall_hi, shape: box, lower: [0, 20.3{zl}], upper: [100, {num(yhi)}{zu}]}}",
        f"  - {{name: inlet, shape: box, lower: [0, -0.3{zl}], upper: [2.9, 20.3{zu}]}}",
        f"  - {{name: injury, shape: box, lower: [10, -0.3{zl}], upper: [20, {num(delta - 0.3)}{zu}], "
        f"kinds: [fluid]}}   # the fluid layer 0 <= y < {num(delta)} on the injured wall",
        "particles:",
        f"  spacing: {dx}",
        "  fill:",
        "    - {region: wall_lo, kind: wall}",
        "    - {region: wall_hi, kind: wall}",
        "    - {kind: fluid}",
        "fluid:",
        f"  backend: {backend}",
    ]
    if tdpd:
        lines += [
            "  smoothing_length: 2.9   # r_c (momentum); r_cc = 1.0 below (concentration)",
            "  reference_density: 4.096",
            "  temperature: 1.0",
            f"  shear_viscosity: {num(ref.NU)}   # not read by tdpd (nu follows from a, gamma, r_c)",
            f"  gravity: [{num(g)}, 0, 0]   # 8 nu u_max / H^2, nu = 138.6, H = {num(h_eff)}",
            "  parameters: {a: 18.75, gamma: 4.5, s1: 0.4, r_cc: 1.0}   # sigma = 3 at k_B T = 1",
        ]
    elif backend == "sdpd":
        lines += [
            f"  smoothing_length: {num(h)}   # 3 dx",
            "  reference_density: 1.0",
            f"  shear_viscosity: {num(ref.NU)}   # nu = 138.6 as the tDPD fluid",
            "  sound_speed: 2.0   # >= 10 u_max",
            "  temperature: 0.0",
            f"  gravity: [{num(g)}, 0, 0]   # 8 nu u_max / H^2, H = {num(h_eff)}",
        ]
    else:
        lines += [
            f"  smoothing_length: {num(h)}   # 2 dx (species operator)",
            f"  parameters: {{field: poiseuille, max_velocity: {u_max}, wall_lo: 0, wall_hi: 20}}"
            "   # H = 20: the injury row y = 0 does not move",
        ]
    # tdpd has no per-particle boundary source (it refuses deterministic fluxes): there the
    # injury stays a layer of volume sources of thickness delta; elsewhere it is the flux law
    fluxes = not tdpd
    lines += parameters_yaml(p, [("Linj", ref.L_INJURY)] if fluxes
                             else [("LF", ref.L_INJURY / delta)])
    lines.append("species:")
    lines.append("  # diffusivity: " + ("kappa_i = (D_i - 0.00261) / 0.0645 (li2015 tDPD fit), "
                                         if tdpd else "D_i, ") + "D_i = 138.6 / Sc_i (Table II)")
    for (name, idx, c0, sc), (_, d, kappa) in zip(ref.SPECIES, ref.diffusivities()):
        diff = kappa if tdpd else d
        bnd = [f"{{region: inlet, condition: inflow, value: {num(c0)}}}"]
        lines.append(f"  - {{name: {name}, stochastic: false, diffusivity: {diff:.6g}, "
                     f"initial: [{{concentration: {num(c0)}}}],   # [{idx}] Sc {sc}")
        lines.append(f"     boundaries: [{', '.join(bnd)}]}}")
    lines += chemistry_tail(p, ", regions: [injury]", fluxes)
    lines += injury_fluxes("Linj") if fluxes else []
    lines += [
        f"time: {{coupling_step: {num(tau)}, end: {num(end)}}}",
        "output:",
        "  every: 10.0",
        "  formats: [csv]",
        "  species: [IIa, Ia, ATIII, APC]",
        "seed: 2015",
    ]
    return "\n".join(lines) + "\n"


SCENES = {
    "examples/coagulation_well_mixed.yaml": well_mixed,
    "examples/coagulation_cascade.yaml": lambda: channel("tdpd"),
    "examples/coagulation_cascade_sdpd.yaml": lambda: channel("sdpd"),
    "examples/coagulation_cascade_prescribed.yaml": lambda: channel("prescribed"),
}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="compare instead of writing")
    args = ap.parse_args()
    bad = 0
    for rel, make in SCENES.items():
        text = make()
        path = REPO / rel
        if args.check:
            if not path.exists() or path.read_text() != text:
                print(f"{rel}: differs from make_scenes.py output (rerun without --check)")
                bad += 1
        else:
            path.write_text(text)
            print(f"wrote {rel}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
