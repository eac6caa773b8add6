#!/usr/bin/python3
"""Table-driven hostile-input test: every case in hostile_cases.txt runs one
`sadr` invocation (after optional set-up runs and checkpoint edits) and must
exit with its code and print its message. Usage:

    run_hostile.py BIN_DIR CASES_FILE [CASE_NAME_SUBSTRING]

File format (one block per case; `#` starts a comment line):

    [base NAME]            a scene template (lines until the next [..])
    [case NAME]
    scene: BASE            the template written as {scene}
    replace: OLD => NEW    text substitution in the scene ({repeat:X:N} = X N times)
    file: PATH             create a regular file (relative to the case directory)
    write: PATH => TEXT    create PATH holding TEXT (\\n = newline; {repeat:X:N} as above)
    mkdir: PATH            create a directory (relative to the case directory)
    env: K=V               environment for every sadr call of the case
    before: ARGS           a sadr call that must exit 0 first
    edit: FILE KEY=JSON    set a key (a.b.0.c for nested) in a JSON file
    args: ARGS             the sadr call under test ({scene}, {out}, {dir})
    program: NAME          run BIN_DIR/NAME instead of sadr (e.g. fluid_service)
    exit: N                expected exit code
    message: TEXT          must appear in stdout + stderr (several allowed)
    absent-text: TEXT      must not appear
    absent: PATH           must not exist afterwards (relative to the case directory)
    file-has: PATH TEXT    the file must contain TEXT afterwards
"""
import json, os, shlex, subprocess, sys, tempfile

TIMEOUT = float(os.environ.get("HOSTILE_TIMEOUT", "60"))  # seconds per sadr call

def parse(path):
    bases, cases, cur = {}, [], None
    for raw in open(path, encoding="utf-8"):
        line = raw.rstrip("\n")
        if line.startswith("[base "):
            cur = ("base", line[6:-1].strip(), [])
            bases[cur[1]] = cur[2]
            continue
        if line.startswith("[case "):
            cur = ("case", line[6:-1].strip(), [])
            cases.append(cur)
            continue
        if cur is None or (cur[0] == "case" and (not line.strip() or line.lstrip().startswith("#"))):
            continue
        cur[2].append(line)
    return {k: "\n".join(v) + "\n" for k, v in bases.items()}, cases

def expand(text):
    while "{repeat:" in text:
        i = text.index("{repeat:")
        j = text.index("}", i)
        what, n = text[i + 8:j].rsplit(":", 1)
        text = text[:i] + what * int(n) + text[j + 1:]
    return text

def set_json(path, key, value):
    with open(path) as f:
        doc = json.load(f)
    parts = key.split(".")
    node = doc
    for p in parts[:-1]:
        node = node[int(p)] if isinstance(node, list) else node[p]
    last = parts[-1]
    if isinstance(node, list):
        node[int(last)] = value
    else:
        node[last] = value
    with open(path, "w") as f:
        json.dump(doc, f)

def run_case(bindir, bases, name, lines):
    spec = {"replace": [], "message": [], "absent-text": [], "absent": [], "before": [],
            "edit": [], "env": [], "file": [], "file-has": [], "write": [], "mkdir": []}
    for line in lines:
        key, _, value = line.partition(":")
        key, value = key.strip(), value.strip()
        if key in spec:
            spec[key].append(value)
        else:
            spec[key] = value
    with tempfile.TemporaryDirectory(prefix="hostile-") as d:
        scene = os.path.join(d, "scene.yaml")
        text = bases[spec["scene"]] if "scene" in spec else ""
        for r in spec["replace"]:
            old, new = r.split(" => ", 1)
            if old not in text:
                return f"replace target '{old}' not in base '{spec.get('scene')}'"
            text = text.replace(old, expand(new).replace("\\n", "\n"))
        with open(scene, "w") as f:
            f.write(text)
        for fpath in spec["file"]:
            with open(os.path.join(d, fpath), "w") as f:
                f.write("not a directory\n")
        for m in spec["mkdir"]:
            os.makedirs(os.path.join(d, m), exist_ok=True)
        for w in spec["write"]:
            fpath, _, content = w.partition(" => ")
            with open(os.path.join(d, fpath), "w") as f:
                f.write(expand(content).replace("\\n", "\n"))
        env = dict(os.environ)
        for e in spec["env"]:
            k, _, v = e.partition("=")
            env[k] = v
        subst = lambda s: [a.format(scene=scene, out=os.path.join(d, "out"), dir=d)
                           for a in shlex.split(expand(s))]
        sadr = os.path.join(bindir, "sadr")
        for b in spec["before"]:
            p = subprocess.run([sadr] + subst(b), cwd=d, env=env, capture_output=True, text=True,
                               timeout=TIMEOUT)
            if p.returncode != 0:
                return f"set-up 'sadr {b}' exited {p.returncode}: {p.stderr[-2000:]}"
        for e in spec["edit"]:
            fpath, _, kv = e.partition(" ")
            k, _, v = kv.partition("=")
            set_json(os.path.join(d, fpath), k, json.loads(v))
        program = os.path.join(bindir, spec.get("program", "sadr"))
        try:
            p = subprocess.run([program] + subst(spec["args"]), cwd=d, env=env, capture_output=True,
                               text=True, errors="replace", timeout=TIMEOUT)
        except subprocess.TimeoutExpired:
            return f"still running after {TIMEOUT} s (killed)"
        out = p.stdout + p.stderr
        problems = []
        if p.returncode != int(spec["exit"]):
            problems.append(f"exit {p.returncode}, expected {spec['exit']}")
        for m in spec["message"]:
            if m not in out:
                problems.append(f"message '{m}' missing")
        for m in spec["absent-text"]:
            if m in out:
                problems.append(f"text '{m}' present")
        for a in spec["absent"]:
            if os.path.lexists(os.path.normpath(os.path.join(d, a))):
                problems.append(f"'{a}' exists")
        for fh in spec["file-has"]:
            fpath, _, want = fh.partition(" ")
            try:
                with open(os.path.join(d, fpath), errors="replace") as f:
                    if want not in f.read():
                        problems.append(f"'{fpath}' lacks '{want}'")
            except OSError as e:
                problems.append(f"'{fpath}': {e}")
        if len(out) > 20000:
            problems.append(f"{len(out)} bytes of output (echoed input not truncated?)")
        if problems:
            return "; ".join(problems) + "\n    output: " + out[-1500:].replace("\n", "\n    ")
    return None

def main():
    bindir, cases_file = os.path.abspath(sys.argv[1]), sys.argv[2]
    only = sys.argv[3] if len(sys.argv) > 3 else ""
    bases, cases = parse(cases_file)
    failed = 0
    ran = 0
    for _, name, lines in cases:
        if only not in name:
            continue
        ran += 1
        why = run_case(bindir, bases, name, lines)
        print(("FAIL " if why else "ok   ") + name + (": " + why if why else ""), flush=True)
        failed += bool(why)
    print(f"{ran - failed}/{ran} hostile cases pass")
    sys.exit(1 if failed or ran == 0 else 0)

main()
