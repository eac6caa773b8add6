#!/usr/bin/env python3
"""Writes docs/reference/cli.md from the executables' own --help, or checks it.

The page is every command's help verbatim: `sadr --help`, `sadr CMD --help`
for every subcommand `sadr --help` lists, and the two services' `--help`.
Nothing is written by hand, so the page cannot drift from the parsers: the
ctest `docs_cli_reference` runs `--check`, which fails with a diff when the
page differs from what the binaries print.

    gen_cli_reference.py --bin build/ci/bin [--out docs/reference/cli.md]
    gen_cli_reference.py --bin build/ci/bin --check
"""
import argparse
import difflib
import os
import pathlib
import re
import subprocess
import sys

HEADER = """# Command-line reference

Generated from the programs' own `--help` by `tests/docs/gen_cli_reference.py`
(a test fails when this page and the programs differ; regenerate with
`/usr/bin/python3 tests/docs/gen_cli_reference.py --bin build/release/bin`).
What the options do, with examples: [the options explained](../cli.md) and
[running sadr](../running.md). Exit codes: 0 ok, 1 invalid scene or input,
2 usage, 3 service failure, 4 numerical failure, 5 I/O failure,
130 interrupted (a checkpoint was written).
"""


def helptext(exe, args):
    env = dict(os.environ, COLUMNS="100", LC_ALL="C")
    p = subprocess.run([str(exe)] + args + ["--help"], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, env=env, timeout=60)
    if p.returncode != 0:
        raise SystemExit(f"{exe} {' '.join(args)} --help exited with {p.returncode}:\n{p.stdout}")
    # CLI11 prints the path it was invoked by ("Usage: build/ci/bin/sadr ..."): the page says "sadr"
    return p.stdout.replace(str(exe), pathlib.Path(exe).name).rstrip() + "\n"


def subcommands(top):
    """The names listed under CLI11's SUBCOMMANDS: heading, in order."""
    names, inside = [], False
    for line in top.splitlines():
        if re.match(r"^(SUBCOMMANDS|Subcommands):\s*$", line):
            inside = True
            continue
        if inside:
            m = re.match(r"^\s{1,4}([a-z][\w-]*)\b", line)
            if m:
                names.append(m.group(1))
            elif line.strip() and not line.startswith(" "):
                inside = False
    return names


def render(bindir):
    bindir = pathlib.Path(bindir)
    sadr = bindir / "sadr"
    top = helptext(sadr, [])
    cmds = subcommands(top)
    if not cmds:
        raise SystemExit("no SUBCOMMANDS section in `sadr --help`")
    out = [HEADER, "Commands: " + ", ".join(f"[`{c}`](#sadr-{c})" for c in cmds) + "; the services: "
           "[`fluid_service`](#fluid_service), [`ssa_service`](#ssa_service).\n",
           "## sadr\n", "```text", top.rstrip(), "```\n"]
    for c in cmds:
        out += [f"## sadr {c}\n", "```text", helptext(sadr, [c]).rstrip(), "```\n"]
    for svc in ("fluid_service", "ssa_service"):
        if (bindir / svc).exists():
            out += [f"## {svc}\n",
                    "Started by `sadr run` as child processes; run them yourself only for "
                    "services on other hosts ([cli.md](../cli.md#where-the-services-run)).\n",
                    "```text", helptext(bindir / svc, []).rstrip(), "```\n"]
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", required=True, help="directory of sadr and the services")
    ap.add_argument("--out", default=str(pathlib.Path(__file__).resolve().parents[2]
                                         / "docs" / "reference" / "cli.md"))
    ap.add_argument("--check", action="store_true", help="compare instead of writing")
    a = ap.parse_args()
    page = render(a.bin)
    out = pathlib.Path(a.out)
    if a.check:
        old = out.read_text() if out.exists() else ""
        if old == page:
            print(f"{out}: up to date with the programs' --help")
            return 0
        sys.stdout.writelines(difflib.unified_diff(
            old.splitlines(True), page.splitlines(True), str(out), "generated from --help"))
        print(f"\n{out} differs from the programs' --help: regenerate it with "
              f"/usr/bin/python3 {pathlib.Path(__file__).name} --bin {a.bin}")
        return 1
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(page)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
