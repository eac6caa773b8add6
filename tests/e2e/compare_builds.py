#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Runs every example and every e2e scene on two builds and compares frames.

Behaviour-preserving changes (refactors, the fluid seam, the typed clients)
must give byte-identical frames. This script is the check:

    tests/e2e/compare_builds.py OLD_BIN NEW_BIN [--scenes DIR] [--work DIR]

OLD_BIN and NEW_BIN are the `bin/` folders of two builds (e.g. a worktree of
the old commit built with `cmake --preset release`). Scenes come from
`examples/*.yaml` (each cut to its first frames with --stop-at, so the whole
set runs in a few minutes) and, with --scenes, from a folder of YAML files
collected from the e2e tests: run them once with

    SADR_SCENE_DUMP=/tmp/e2e-scenes ctest --preset ci -L e2e

(`tests/e2e/cli_test_support.hpp` copies every scene a test writes there).
Every `frames/*` file, the `.pvd` index and the checkpoint blobs are
compared byte by byte; run.json is not (it holds wall times). A scene that
fails on both builds with the same exit code is reported as `both-fail`
(a refusal test's scene, say), which counts as identical; anything else that
differs is a failure. Exit 0 when every scene is identical.
"""
import argparse
import hashlib
import pathlib
import shutil
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
# Examples whose full run takes minutes: cut to a few frames.
STOP_AT = {
    "yeast_cell_channel": "0.02",
    "poiseuille_tracer_2d": "1.0",
    "open_channel_tracer": "0.5",
    "annihilation_1d_stochastic_n65": "0.5",
    "annihilation_1d_stochastic_n33": "1.0",
}


def digest_tree(out: pathlib.Path) -> dict[str, str]:
    """Relative path -> sha256 of every compared file of one run."""
    files = {}
    for p in sorted(out.rglob("*")):
        if not p.is_file():
            continue
        rel = p.relative_to(out).as_posix()
        if rel.endswith("run.json") or rel.endswith(".log") or rel.endswith("checkpoint.json"):
            continue
        files[rel] = hashlib.sha256(p.read_bytes()).hexdigest()
    return files


def run_one(binary: pathlib.Path, scene: pathlib.Path, out: pathlib.Path, extra: list[str]):
    if out.exists():
        shutil.rmtree(out)
    cmd = [str(binary / "sadr"), "run", str(scene), "-o", str(out), "--force", "-q", *extra]
    t0 = time.monotonic()
    p = subprocess.run(cmd, cwd=scene.parent, capture_output=True, text=True)
    return p.returncode, time.monotonic() - t0, (p.stdout + p.stderr)[-400:]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("old_bin", type=pathlib.Path)
    ap.add_argument("new_bin", type=pathlib.Path)
    ap.add_argument("--scenes", type=pathlib.Path, help="folder of extra scene YAML files")
    ap.add_argument("--work", type=pathlib.Path, default=pathlib.Path("/tmp/sadr-compare"))
    ap.add_argument("--only", help="substring: run only scenes whose name contains it")
    args = ap.parse_args()

    scenes = [(p, ["--stop-at", STOP_AT[p.stem]] if p.stem in STOP_AT else [])
              for p in sorted((ROOT / "examples").glob("*.yaml"))]
    if args.scenes:
        scenes += [(p, []) for p in sorted(args.scenes.glob("*.yaml"))]
    if args.only:
        scenes = [s for s in scenes if args.only in s[0].name]

    failures = 0
    print(f"{'scene':48s} {'result':10s} {'files':>5s} {'old s':>7s} {'new s':>7s}")
    for scene, extra in scenes:
        tag = scene.stem if scene.parent.name == "examples" else "e2e/" + scene.stem
        oa, ob = args.work / "old" / tag, args.work / "new" / tag
        rca, ta, loga = run_one(args.old_bin, scene, oa, extra)
        rcb, tb, logb = run_one(args.new_bin, scene, ob, extra)
        if rca != 0 or rcb != 0:
            ok = rca == rcb
            result = "both-fail" if ok else f"rc {rca}/{rcb}"
            nfiles = 0
        else:
            da, db = digest_tree(oa), digest_tree(ob)
            ok = da == db and len(da) > 0
            nfiles = len(da)
            result = "identical" if ok else "DIFFERS"
            if not ok:
                only = sorted(set(da) ^ set(db))
                diff = sorted(k for k in set(da) & set(db) if da[k] != db[k])
                print(f"  only in one: {only[:5]}  differing: {diff[:5]}")
        print(f"{tag:48s} {result:10s} {nfiles:5d} {ta:7.2f} {tb:7.2f}", flush=True)
        if not ok:
            failures += 1
            print("  old:", loga.strip().replace("\n", " | ")[-200:])
            print("  new:", logb.strip().replace("\n", " | ")[-200:])
    print(f"{len(scenes) - failures} identical, {failures} differ (of {len(scenes)} scenes)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
