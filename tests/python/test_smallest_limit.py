# SPDX-License-Identifier: MIT
"""run.json's `fluid_smallest_limit` is a sub-step limit that holds for the whole run.

The fluid's stability limits follow the state. In the deterministic A + B -> 0 example the
species start at zero inside and fill in from the walls: at t = 0 only the diffusion limit
binds (0.00396), and the reaction limit tightens to 7.2e-4 by t = 1 as A and B meet. A
sub-step forced to a limit read at one moment of the run can therefore break the limit later
(the stability map once forced 0.00221, a mid-run reaction limit, and was 33 % wrong). The
smallest limit the automatic sub-steps met is reported after the run; forced at exactly that
figure the result agrees with a run at a tenth of it. Deterministic (static backend, no
noise): no false failures.

Measured: smallest limit 7.19e-4 (reaction, at t = 1); forced at 1.0x,
max |A - A_ref| / max A = 6.5e-8 (bound 1e-4)."""
import csv
import json
import subprocess

from conftest import REPO

SCENE = (REPO / "examples/annihilation_1d_deterministic.yaml").read_text()
SCENE = SCENE.replace("end: 4.0 ", "end: 1.0 ").replace(
    "times: [0.2, 0.4, 0.6, 0.8, 1.0, 2.0, 4.0]", "times: [1.0]")


def run(sadr_bin, tmp_path, name, fluid_lines=""):
    scene = tmp_path / f"{name}.yaml"
    scene.write_text(SCENE.replace("fluid:\n", "fluid:\n" + fluid_lines, 1))
    out = tmp_path / name
    proc = subprocess.run([str(sadr_bin), "run", str(scene), "--output", str(out), "--quiet",
                           "--force"], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr[-4000:]
    frame = sorted((out / "frames").glob("*.csv"))[-1]
    a = [float(r["A"]) for r in csv.DictReader(open(frame))]
    return json.loads((out / "run.json").read_text()), a


def test_forced_substep_at_the_reported_smallest_limit_is_accurate(sadr_bin, tmp_path):
    manifest, _ = run(sadr_bin, tmp_path, "auto")
    at0, smallest = manifest["fluid_at_t0"], manifest["fluid_smallest_limit"]
    print("at t = 0:", at0, "smallest:", smallest)
    assert at0["limiting_criterion"] == "diffusion", at0
    assert smallest["limiting_criterion"] == "reaction", smallest
    limit = smallest["stable_time_step"]
    assert limit < 0.5 * at0["stable_time_step"], (limit, at0)  # it tightens: 7.7e-4 / 3.96e-3
    assert 0 < smallest["time"] <= 1.0 + 1e-12, smallest

    forced, a = run(sadr_bin, tmp_path, "forced",
                    f"  max_time_step: {limit!r}\n  force_time_step: true\n")
    _, ref = run(sadr_bin, tmp_path, "fine", f"  max_time_step: {0.1 * limit!r}\n")
    err = max(abs(x - y) for x, y in zip(a, ref)) / max(abs(y) for y in ref)
    print(f"forced at the smallest limit {limit:.4g}: max |A - A_ref| / max = {err:.3g}")
    assert err < 1e-4, err
    # the forced run kept to every limit: nothing was taken above one
    assert forced["fluid_smallest_limit"]["stable_time_step"] >= 0.999 * limit
