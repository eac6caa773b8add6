# SPDX-License-Identifier: MIT
"""`sadr summary DIR` and the same table at the end of `sadr run` (not with -q),
checked against the package's own reading of the run."""
import csv
import re

import numpy as np

import sadr
from conftest import poiseuille, static_scene


def species_rows(text):
    """{label: (first, last)} from the summary's species table."""
    rows = {}
    block = text.split("species totals", 1)[1].split("wall time per stage", 1)[0]
    for line in block.splitlines()[2:]:
        m = re.match(r"\s+(\S.*?)\s+(\S+)\s+(\S+)$", line)
        if m:
            rows[m.group(1)] = (float(m.group(2)), float(m.group(3)))
    return rows


def test_summary_of_a_run(tmp_path):
    scene = static_scene(end=0.5, every=0.25)
    scene.write(tmp_path / "s.yaml")
    out = tmp_path / "run"
    loud = sadr.run_cli(["run", tmp_path / "s.yaml", "-o", out])
    quiet = sadr.run_cli(["run", tmp_path / "s.yaml", "-o", out, "--force", "-q"])
    text = sadr.run_cli(["summary", out]).stdout
    assert "sadr summary: " in loud.stderr and "sadr summary" not in quiet.stderr
    assert loud.stderr[loud.stderr.index("sadr summary: "):].splitlines()[1:3] == text.splitlines()[1:3]
    run = sadr.Run(out)
    first, last = run.frame(0), run.frame(-1)
    rows = species_rows(text)
    assert rows["A"] == (first.species["A"].sum(), last.species["A"].sum())
    amount = rows["B (amount, sum c V)"]
    np.testing.assert_allclose(amount, [np.sum(f.species["B"] * f.volume) for f in (first, last)],
                               rtol=1e-9)
    steps = run.manifest["steps"]
    assert f"t = 0.5: {steps} coupling steps, {run.manifest['fluid_substeps']} fluid sub-steps" in text
    fluid = float(re.search(r"^\s+fluid\s+(\S+)", text, re.M).group(1))
    assert abs(fluid - run.timings["fluid"]) <= 5e-4
    assert f"{out}/run.json" in text and "static_reaction_diffusion.pvd" in text


def test_summary_of_an_ensemble(static_ensemble):
    text = sadr.run_cli(["summary", static_ensemble.path]).stdout
    assert "ensemble: 4 realizations (4 with status ok)" in text
    rows = species_rows(text)
    mean_last = static_ensemble.mean_frame(-1)["A"][0].sum()
    np.testing.assert_allclose(rows["A"][1], mean_last, rtol=1e-9)
    steps = sum(r.manifest["steps"] for r in static_ensemble.runs)
    assert f"{steps} coupling steps" in text


def test_summary_refuses_other_folders(tmp_path):
    try:
        sadr.run_cli(["summary", tmp_path])
    except sadr.InvalidInput as e:
        assert "neither a run (run.json) nor an ensemble" in e.message
    else:
        raise AssertionError("sadr summary accepted an empty folder")


def test_events_counted(tmp_path):
    """Decay only, no diffusion: every SSA event is one A -> 0, so run.json's
    ssa_events (and the summary) equal the molecules lost, exactly."""
    s = static_scene(end=0.5, every=0.25)
    s["species[0].diffusivity"] = 0.0
    s["species[0].initial"] = [{"region": "source", "count": 50}]
    s["reactions"] = [r for r in s["reactions"] if r["name"] != "make_A"]
    run = s.run(tmp_path / "decay")
    lost = run.frame(0).species["A"].sum() - run.frame(-1).species["A"].sum()
    assert lost > 100  # 50 on each of the ~70 source particles, rate 1, t = 0.5
    assert run.manifest["ssa_events"] == lost
    text = sadr.run_cli(["summary", run.path]).stdout
    assert f"SSA events: {int(lost)} (reactions + diffusion jumps)" in text


def health_block(text):
    return text.split("  health (", 1)[1].split("\n  outputs:", 1)[0]


def test_health_of_a_sound_run(tmp_path):
    """A short Poiseuille run: no fluid in walls, no holes, density within 1e-3 of the start,
    the tracer (no reaction, no-flux walls) conserved to the molecule."""
    run = poiseuille(end=0.5, formats=("csv",)).run(tmp_path / "p")
    text = sadr.run_cli(["summary", run.path]).stdout
    block = health_block(text)
    assert block.startswith("6 frame(s) checked; dx = 0.05, h = 0.15 from the scene; rho0 = 1")
    assert "fluid inside walls: none (wall particles closer than dx/2)" in block
    assert "empty holes: none (cells of 0.1667 >= h)" in block
    rho_max = float(re.search(r"density \|rho/rho0 - 1\|: max (\S+)", block).group(1))
    assert 0 < rho_max < 1e-3
    assert "T: 8000 -> 8000 (+0); nothing: no reaction or boundary changes it" in block
    assert block.rstrip().endswith("no warnings") and "WARNING" not in block


def test_health_finds_a_particle_in_a_wall_and_a_hole(tmp_path):
    """The last frame of a sound run edited: a fluid particle put onto a wall particle and a
    0.4 x 0.4 block of fluid (with its tracer) removed. The summary names the particle, finds
    the hole and the tracer's unexplained loss."""
    run = poiseuille(end=0.5, formats=("csv",)).run(tmp_path / "p")
    last = sorted((run.path / "frames").glob("*.csv"))[-1]
    with open(last, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    col = {name: k for k, name in enumerate(header)}
    wall = next(r for r in body if r[col["kind"]] == "1" and float(r[col["y"]]) < -0.1)
    mover = next(r for r in body if r[col["kind"]] == "0" and float(r[col["y"]]) > 0.9)
    mover[col["x"]], mover[col["y"]] = wall[col["x"]], wall[col["y"]]
    kept = [r for r in body if not (r[col["kind"]] == "0" and
                                    0.3 < float(r[col["x"]]) < 0.7 and 0.3 < float(r[col["y"]]) < 0.7)]
    assert len(body) - len(kept) > 20
    with open(last, "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows([header] + kept)
    text = sadr.run_cli(["summary", run.path]).stdout
    block = health_block(text)
    assert f"deepest: particle {int(float(mover[col['id']]))} at" in block
    assert "0.025 past the surface, t = 0.5" in block
    assert "empty holes: up to 1 (t = 0.5), 1 at the last frame" in block
    assert "WARNING: fluid particles inside walls at 1 checked frame(s), up to 1" in block
    assert "WARNING: empty holes larger than the kernel support at 1 checked frame(s)" in block
    assert "WARNING: species T: its total changed" in block
