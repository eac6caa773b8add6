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
With --resume, every example is also cut in half: OLD runs it to the middle
(--stop-at, which writes a checkpoint), NEW resumes that checkpoint to the
same stop time as the whole run, and the result must equal OLD's whole run:
checkpoints written by the old build resume bit-identically on the new one.
Every `frames/*` file, the `.pvd` index and the checkpoint blobs are
compared byte by byte; run.json is not (it holds wall times). A scene that
fails on both builds with the same exit code is reported as `both-fail`
(a refusal test's scene, say), which counts as identical; anything else that
differs is a failure. Exit 0 when every scene is identical.

With --fluid-blob-payload, fluid checkpoint blobs are compared by content
after the fluid state header (backend name and state version included), and
their file names without the content hash: for a change of the header layout
only (issue 14: the fluid core owns it, old headers are still read), which
must leave everything after it, and every frame, byte-identical.
"""
import argparse
import hashlib
import pathlib
import re
import shutil
import struct
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
    "natural_convection_ra1e4": "1.0",
    "natural_convection_ra1e5": "1.0",
    "natural_convection_ra1e6": "1.0",
    "natural_convection_ra1e4_stochastic": "1.0",
    "natural_convection_ra1e5_stochastic": "1.0",
    "natural_convection_ra1e6_stochastic": "1.0",
    "coagulation_cascade": "0.006",  # 110k tdpd particles, ~1 s CPU per sub-step of 0.003
    "coagulation_cascade_sdpd": "0.0016",  # sub-steps of 7.9e-4
    "coagulation_cascade_prescribed": "2.0",
}

# e2e scenes that run until a test kills a service (end 1000-2000): cut as well.
E2E_STOP_AT = {
    "KilledSsaService": "2.0",
}


def e2e_extra(scene: pathlib.Path) -> list[str]:
    for key, stop in E2E_STOP_AT.items():
        if key in scene.name:
            return ["--stop-at", stop]
    return []


FLUID_BLOB = re.compile(r"(.*checkpoint/fluid-\d{12})-[0-9a-f]{8}\.blob$")
# Fluid state headers: format 1 (backend_base.hpp) and the per-backend ones before it.
LEGACY_TAGS = {0x3144504453524441, 0x3154415453524441}  # sdpd, static


def fluid_state_payload(state: bytes) -> bytes:
    """backend name + state version + everything after the header of a fluid state blob."""
    (n,) = struct.unpack_from("<Q", state, 0)
    if n in LEGACY_TAGS:  # tag, version, name
        (ver,) = struct.unpack_from("<I", state, 8)
        (ln,) = struct.unpack_from("<Q", state, 12)
        name, rest = state[20:20 + ln], state[20 + ln:]
    elif state[8:8 + n] == b"sadr.tdpd":  # "sadr.tdpd", version
        (ver,) = struct.unpack_from("<I", state, 8 + n)
        name, rest = b"tdpd", state[12 + n:]
    elif state[8:8 + n] == b"sadr.fluid.state":  # tag, format, name, version
        at = 8 + n + 4
        (ln,) = struct.unpack_from("<Q", state, at)
        name = state[at + 8:at + 8 + ln]
        (ver,) = struct.unpack_from("<I", state, at + 8 + ln)
        rest = state[at + 12 + ln:]
    else:
        return state
    return name + b"/" + str(ver).encode() + b"/" + rest


def varint(b: bytes, i: int) -> tuple[int, int]:
    v = shift = 0
    while True:
        c = b[i]
        i += 1
        v |= (c & 0x7F) << shift
        shift += 7
        if c < 0x80:
            return v, i


def snapshot_digest(data: bytes) -> str:
    """sha256 of a serialized sadr.common.v1.Snapshot with field 5 (blob) by its payload."""
    h = hashlib.sha256()
    i = 0
    while i < len(data):
        start = i
        tag, i = varint(data, i)
        wire = tag & 7
        if wire == 0:
            _, i = varint(data, i)
        elif wire == 1:
            i += 8
        elif wire == 5:
            i += 4
        elif wire == 2:
            n, j = varint(data, i)
            i = j + n
            if tag >> 3 == 5:
                h.update(b"blob:" + fluid_state_payload(data[j:i]))
                continue
        else:
            return hashlib.sha256(data).hexdigest()
        h.update(data[start:i])
    return h.hexdigest()


def digest_tree(out: pathlib.Path, fluid_payload: bool = False,
                frames_only: bool = False) -> dict[str, str]:
    """Relative path -> sha256 of every compared file of one run."""
    files = {}
    for p in sorted(out.rglob("*")):
        if not p.is_file():
            continue
        rel = p.relative_to(out).as_posix()
        if rel.endswith("run.json") or rel.endswith(".log") or rel.endswith("checkpoint.json"):
            continue
        if frames_only and rel.startswith("checkpoint/"):
            continue
        m = FLUID_BLOB.match(rel) if fluid_payload else None
        if m:
            files[m.group(1) + ".blob"] = snapshot_digest(p.read_bytes())
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


def end_time(scene: pathlib.Path, extra: list[str]) -> float:
    """The stop time of the whole run: --stop-at if given, else time.end of the scene."""
    if "--stop-at" in extra:
        return float(extra[extra.index("--stop-at") + 1])
    m = re.search(r"\bend:\s*([0-9.eE+-]+)", scene.read_text())
    if not m:
        raise SystemExit(f"{scene}: no time.end found")
    return float(m.group(1))


def resume_one(old: pathlib.Path, new: pathlib.Path, scene: pathlib.Path, out: pathlib.Path,
               extra: list[str]):
    """OLD to the middle, NEW resumes to the end; returns (rc, log)."""
    stop = end_time(scene, extra)
    half = list(extra)
    if "--stop-at" in half:
        i = half.index("--stop-at")
        del half[i:i + 2]
    rc, _, log = run_one(old, scene, out, half + ["--stop-at", repr(stop / 2)])
    if rc != 0:
        return rc, "old half: " + log
    cmd = [str(new / "sadr"), "resume", str(out / "checkpoint"), "-q"]
    if "--stop-at" in extra:
        cmd += ["--stop-at", repr(stop)]
    p = subprocess.run(cmd, cwd=scene.parent, capture_output=True, text=True)
    return p.returncode, (p.stdout + p.stderr)[-400:]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("old_bin", type=lambda p: pathlib.Path(p).resolve())
    ap.add_argument("new_bin", type=lambda p: pathlib.Path(p).resolve())
    ap.add_argument("--scenes", type=pathlib.Path, help="folder of extra scene YAML files")
    ap.add_argument("--work", type=pathlib.Path, default=pathlib.Path("/tmp/sadr-compare"))
    ap.add_argument("--only", help="substring: run only scenes whose name contains it")
    ap.add_argument("--resume", action="store_true",
                    help="also resume OLD's mid-run checkpoint of every example with NEW")
    ap.add_argument("--frames-only", action="store_true",
                    help="leave checkpoint/ out (a change meant to alter step counts, "
                         "e.g. frame-to-frame SSA steps, keeps frames but not blob names)")
    ap.add_argument("--fluid-blob-payload", action="store_true",
                    help="compare fluid checkpoint blobs after their state header (see above)")
    args = ap.parse_args()

    scenes = [(p, ["--stop-at", STOP_AT[p.stem]] if p.stem in STOP_AT else [])
              for p in sorted((ROOT / "examples").glob("*.yaml"))]
    if args.scenes:
        scenes += [(p, e2e_extra(p)) for p in sorted(args.scenes.glob("*.yaml"))]
    if args.only:
        scenes = [s for s in scenes if args.only in s[0].name]

    failures = resumed = 0
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
            da = digest_tree(oa, args.fluid_blob_payload, args.frames_only)
            db = digest_tree(ob, args.fluid_blob_payload, args.frames_only)
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
        if args.resume and scene.parent.name == "examples" and ok and rca == 0:
            orr = args.work / "resume" / tag
            rcr, logr = resume_one(args.old_bin, args.new_bin, scene, orr, extra)
            dr = digest_tree(orr, args.fluid_blob_payload, args.frames_only) if rcr == 0 else {}
            ref = digest_tree(oa, args.fluid_blob_payload, args.frames_only)
            if not any(k.startswith("checkpoint/") for k in ref):
                # The whole run wrote no checkpoint; the half run's stays: frames only.
                dr = {k: v for k, v in dr.items() if not k.startswith("checkpoint/")}
            rok = rcr == 0 and dr == ref
            resumed += 1
            print(f"{tag + ' (old half + new resume)':48s} {'identical' if rok else 'DIFFERS':10s}"
                  f" {len(dr):5d}", flush=True)
            if not rok:
                failures += 1
                print("  resume:", logr.strip().replace("\n", " | ")[-300:])
    total = len(scenes) + resumed
    print(f"{total - failures} identical, {failures} differ (of {len(scenes)} scenes"
          f"{f' and {resumed} resumed runs' if resumed else ''})")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
