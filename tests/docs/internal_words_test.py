#!/usr/bin/env python3
"""Fails when a user-facing file uses project-internal words.

User-facing files: README.md, docs/**/*.md, mkdocs.yml and every text file
under examples/ (scenes and their comment headers, scripts, notebooks' cell
sources). Internal words mean nothing to a user: issue numbers ("#15",
"issue 12"), work rounds ("round 5"), "session", goals stated as "target ...
met", commit hashes (7-40 hex digits with at least one letter and one
digit) and ISO dates (of investigations). Dated measurement logs belong in
bench/results/, beside their results.

Generated reports (GENERATED below) name the commit and date they were
generated from and the goals they check, so hashes, dates and targets are
allowed there; issue numbers, rounds and sessions are not.

    internal_words_test.py [--root DIR]    check the tree (exit 1 on a hit)
    internal_words_test.py --self-check    plant each word, check it is caught
"""
import argparse
import json
import pathlib
import re
import sys
import tempfile

RULES = [
    ("issue number", re.compile(r"(?<![\w&/])#\d+\b")),
    ("issue number", re.compile(r"\bissues?\s*#?\d+\b", re.I)),
    ("work round", re.compile(r"\bround\s*\d+\b", re.I)),
    ("session", re.compile(r"\bsessions?\b", re.I)),
    ("target", re.compile(r"\btargets?\b[^.\n]{0,80}?\b(met|missed|not met)\b", re.I)),
    ("target", re.compile(r"\btargets?\s*[:(]?\s*(>=|<=|<|>|≤|≥)?\s*\d", re.I)),
    ("commit hash", re.compile(r"(?<![.\w])(?=[0-9a-f]*[0-9])(?=[0-9a-f]*[a-f])[0-9a-f]{7,40}\b(?![-+]\d)")),
    ("commit hash", re.compile(r"\+dirty\b")),
    ("date", re.compile(r"\b20\d\d-[01]\d-[0-3]\d\b")),
]
# Generated reports: provenance (commit, date) and the goals they check are allowed.
GENERATED = {"docs/validation-report.md", "docs/validation/stability_map.md",
             "docs/fluid-error-table.md"}
PROVENANCE = {"commit hash", "date", "target"}
TEXT_SUFFIXES = {".md", ".yaml", ".yml", ".py", ".txt", ".ipynb", ".sh", ""}


def user_files(root):
    root = pathlib.Path(root)
    files = [root / "README.md", root / "mkdocs.yml"]
    files += sorted((root / "docs").rglob("*.md"))
    files += sorted(p for p in (root / "examples").rglob("*")
                    if p.is_file() and p.suffix in TEXT_SUFFIXES)
    return [p for p in files if p.is_file()]


def lines_of(path):
    """(line number, text) pairs; a notebook's cell sources only (outputs are generated)."""
    text = path.read_text(encoding="utf-8", errors="replace")
    if path.suffix == ".ipynb":
        nb = json.loads(text)
        n = 0
        for cell in nb.get("cells", []):
            src = cell.get("source", [])
            for line in (src if isinstance(src, list) else src.splitlines()):
                n += 1
                yield n, line.rstrip("\n")
        return
    for n, line in enumerate(text.splitlines(), 1):
        yield n, line


def check(root):
    root = pathlib.Path(root)
    hits = []
    for path in user_files(root):
        rel = path.relative_to(root).as_posix()
        for n, line in lines_of(path):
            for what, rx in RULES:
                if rel in GENERATED and what in PROVENANCE:
                    continue
                m = rx.search(line)
                if m:
                    hits.append(f"{rel}:{n}: {what}: '{m.group(0)}' in: {line.strip()[:160]}")
    return hits


PLANTED = [
    "See #15 for the details.",
    "This was fixed in issue 12.",
    "Measured in round 5 on a quiet machine.",
    "The session-start code was slower.",
    "3.4x LAMMPS (target 3x: met).",
    "goal missed (target: >= 10x cheaper)",
    "measured at commit a785c0f yesterday",
    "built from 311d111+dirty",
    "side by side on 2026-12-02, median of 5",
]
CLEAN = [
    "1000000 sub-steps, 2251799813685248 molecules, seed 1234567, beta 1.524157902758726e-05",
    "pd.read_csv(path, float_precision='round_trip') rounds 2 values",
    "each candidate's target voxel, coordinates and mass",
    "colour #1f77b4, ids [3, 4]; accessed 12 times",
]


def self_check():
    bad = []
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "docs").mkdir()
        (root / "examples").mkdir()
        (root / "README.md").write_text("\n".join(CLEAN) + "\n")
        if check(root):
            bad.append(f"false positives on clean text: {check(root)}")
        for i, word in enumerate(PLANTED):
            for place in ("docs/page.md", "examples/scene.yaml", "README.md"):
                text = "\n".join(CLEAN) + "\n" + ("# " if place.endswith(".yaml") else "") + word + "\n"
                (root / place).write_text(text)
                hits = check(root)
                if not hits:
                    bad.append(f"planted '{word}' in {place} was not caught")
                (root / place).write_text("\n".join(CLEAN) + "\n")
        # a generated report may name its commit and date, never an issue
        (root / "docs" / "validation-report.md").write_text("at commit a785c0f on 2026-12-02\n")
        if check(root):
            bad.append("provenance in a generated report was flagged")
        (root / "docs" / "validation-report.md").write_text("see #20\n")
        if not check(root):
            bad.append("an issue number in a generated report was not caught")
    for b in bad:
        print("SELF-CHECK FAILED:", b)
    print(f"self-check: {len(PLANTED)} planted words x 3 places, {len(CLEAN)} clean lines: "
          + ("ok" if not bad else f"{len(bad)} failures"))
    return 1 if bad else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=str(pathlib.Path(__file__).resolve().parents[2]))
    ap.add_argument("--self-check", action="store_true")
    a = ap.parse_args()
    if a.self_check:
        return self_check()
    hits = check(a.root)
    for h in hits:
        print(h)
    n = len(user_files(a.root))
    print(f"internal words: {len(hits)} hits in {n} user-facing files")
    return 1 if hits else 0


if __name__ == "__main__":
    sys.exit(main())
