#!/usr/bin/env python3
"""Runs a tutorial page (docs/tutorials/*.md) as a test.

The page is read top to bottom, in one empty temporary directory:

* a fenced block right after `<!-- file: NAME -->` is written to NAME (any
  language: a scene, a sweep file, a script); it is not run;
* every other ```bash block is run with bash (-e -o pipefail), and every
  other ```python block with /usr/bin/python3;
* a block right after `<!-- skip -->` is shown to the reader but not run
  (commands for another machine: Slurm, ParaView's GUI, your own paths);
* `<!-- expect: REGEX -->` after a run block asserts that the block's
  stdout + stderr matches REGEX (Python re.search, multi-line);
  `<!-- expect-file: PATH -->` asserts that PATH exists in the directory.

The sadr executables' directory is put first on PATH (--bin) and the Python
package on PYTHONPATH (--python), as the tutorials tell the reader to do.
Exits 0 when every block ran with exit code 0 and every expectation held,
printing the wall time; otherwise prints the block, its output and why.

    run_tutorials.py --bin build/ci/bin [--python python] PAGE.md...
    run_tutorials.py --self-check      the runner's own checks (no sadr needed)
"""
import argparse
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import time

MARK = re.compile(r"^<!--\s*(file|skip|expect-file|expect)\s*:?\s*(.*?)\s*-->\s*$")
FENCE = re.compile(r"^(```+|~~~+)\s*([\w+-]*)")


def parse(text):
    """Steps in page order: ('file', name, body), ('run', lang, body, line),
    ('expect', regex, line), ('expect-file', path, line)."""
    steps, pending, lines, i = [], None, text.splitlines(), 0
    while i < len(lines):
        line = lines[i]
        m = MARK.match(line.strip())
        if m:
            kind, arg = m.group(1), m.group(2)
            if kind in ("file", "skip"):
                pending = (kind, arg)
            else:
                steps.append((kind, arg, i + 1))
            i += 1
            continue
        f = FENCE.match(line)
        if f:
            fence, lang, start = f.group(1), f.group(2), i + 1
            body = []
            i += 1
            while i < len(lines) and not lines[i].startswith(fence):
                body.append(lines[i])
                i += 1
            i += 1
            body = "\n".join(body) + "\n"
            if pending and pending[0] == "file":
                steps.append(("file", pending[1], body))
            elif pending and pending[0] == "skip":
                pass
            elif lang in ("bash", "sh", "shell"):
                steps.append(("run", "bash", body, start))
            elif lang in ("python", "py"):
                steps.append(("run", "python", body, start))
            pending = None
            continue
        if line.strip():
            pending = None if not line.strip().startswith("<!--") else pending
        i += 1
    return steps


def run_page(page, bindir, pythonpath, timeout, keep=False):
    text = pathlib.Path(page).read_text()
    steps = parse(text)
    env = dict(os.environ)
    if bindir:
        env["PATH"] = str(pathlib.Path(bindir).resolve()) + os.pathsep + env.get("PATH", "")
    if pythonpath:
        env["PYTHONPATH"] = str(pathlib.Path(pythonpath).resolve())
    env.setdefault("OMP_NUM_THREADS", "2")
    env["MPLBACKEND"] = "Agg"
    tmp = tempfile.mkdtemp(prefix="sadr-tutorial-")
    started = time.monotonic()
    last_out, last_line, failures, ran = None, 0, [], 0
    for step in steps:
        if step[0] == "file":
            path = pathlib.Path(tmp, step[1])
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(step[2])
        elif step[0] == "run":
            lang, body, line = step[1], step[2], step[3]
            cmd = (["bash", "-e", "-o", "pipefail", "-c", body] if lang == "bash"
                   else ["/usr/bin/python3", "-c", body])
            left = timeout - (time.monotonic() - started)
            try:
                p = subprocess.run(cmd, cwd=tmp, env=env, stdout=subprocess.PIPE,
                                   stderr=subprocess.STDOUT, text=True,
                                   timeout=max(left, 1))
            except subprocess.TimeoutExpired:
                failures.append(f"{page}:{line}: timed out after {timeout} s in total")
                break
            ran += 1
            last_out, last_line = p.stdout, line
            print(f"--- {page}:{line} ({lang}) exit {p.returncode}\n{p.stdout}", end="")
            if p.returncode != 0:
                failures.append(f"{page}:{line}: exit code {p.returncode}")
                break
        elif step[0] == "expect":
            if last_out is None:
                failures.append(f"{page}:{step[2]}: expect before any run block")
            elif not re.search(step[1], last_out, re.M):
                failures.append(f"{page}:{step[2]}: output of the block at line {last_line} "
                                f"does not match /{step[1]}/")
        elif step[0] == "expect-file":
            if not pathlib.Path(tmp, step[1]).exists():
                failures.append(f"{page}:{step[2]}: {step[1]} was not written")
    wall = time.monotonic() - started
    if not keep:
        subprocess.run(["rm", "-rf", tmp])
    for f in failures:
        print("FAILED:", f)
    print(f"{page}: {ran} blocks run, {sum(s[0].startswith('expect') for s in steps)} "
          f"expectations, wall time {wall:.1f} s: {'ok' if not failures else 'FAILED'}"
          + (f" (kept {tmp})" if keep else ""))
    return not failures, wall


SELF_PAGE = """# t
<!-- file: a.txt -->
```text
hello tutorial
```
```bash
cat a.txt
```
<!-- expect: ^hello tutorial$ -->
<!-- skip -->
```bash
exit 3
```
```python
print(6 * 7)
```
<!-- expect: 42 -->
```bash
echo done > out.txt
```
<!-- expect-file: out.txt -->
"""


def self_check():
    ok = True
    with tempfile.TemporaryDirectory() as d:
        page = pathlib.Path(d, "page.md")
        page.write_text(SELF_PAGE)
        good, _ = run_page(page, None, None, 30)
        ok &= good
        for bad in (SELF_PAGE.replace("^hello tutorial$", "^goodbye$"),
                    SELF_PAGE.replace("print(6 * 7)", "raise SystemExit(1)"),
                    SELF_PAGE.replace("expect-file: out.txt", "expect-file: missing.txt"),
                    SELF_PAGE.replace("<!-- skip -->\n", "")):
            page.write_text(bad)
            failed_as_expected = not run_page(page, None, None, 30)[0]
            ok &= failed_as_expected
    print("self-check:", "ok" if ok else "FAILED")
    return 0 if ok else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("pages", nargs="*")
    ap.add_argument("--bin", help="directory of sadr, fluid_service and ssa_service")
    ap.add_argument("--python", help="directory of the sadr Python package (PYTHONPATH)")
    ap.add_argument("--timeout", type=float, default=300, help="seconds per page")
    ap.add_argument("--keep", action="store_true", help="keep the temporary directory")
    ap.add_argument("--self-check", action="store_true")
    a = ap.parse_args()
    if a.self_check:
        return self_check()
    ok = True
    for page in a.pages:
        ok &= run_page(page, a.bin, a.python, a.timeout, a.keep)[0]
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
