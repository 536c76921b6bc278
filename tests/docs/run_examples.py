#!/usr/bin/env python3
"""Runs the examples of README.md and docs/*.md (docs/development.md, "Tested examples").

- ```console blocks: each `$ ` line is run with bash; the lines up to the next `$ ` are its expected output,
  compared token by token, numbers to the digits printed (|x| < 1e-6 on both sides counts as equal: rounding
  noise of a zero).
- ```sh and ```python blocks that follow a line `<!-- test -->`: run, and must succeed.
- ```toml blocks whose first line is `# NAME.toml`: written to NAME.toml first.
Each document runs in a temporary folder of its own (blocks in order), with `experiments` linked into it,
build/bin on PATH and build/python on PYTHONPATH. Prints every block it ran.
"""
import argparse, glob, os, re, shutil, subprocess, sys, tempfile

NUM = re.compile(r'^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$')


def blocks(path):
    """(line number, language, text lines, marked) of each fenced block."""
    out, lines = [], open(path, encoding="utf-8").read().split("\n")
    i = 0
    while i < len(lines):
        m = re.match(r'^```(\S*)', lines[i])
        if m and not lines[i].startswith("```\n"):
            lang = m.group(1)
            marked = i > 0 and lines[i - 1].strip() == "<!-- test -->"
            j = i + 1
            while j < len(lines) and not lines[j].startswith("```"):
                j += 1
            out.append((i + 1, lang, lines[i + 1:j], marked))
            i = j + 1
        else:
            i += 1
    return out


def same_token(e, a):
    if e == a:
        return True
    if NUM.match(e) and NUM.match(a):
        x, y = float(e), float(a)
        if abs(x) < 1e-6 and abs(y) < 1e-6:
            return True
        mant, _, exp = e.lower().partition("e")
        decimals = len(mant.split(".")[1]) if "." in mant else 0
        unit = 10.0 ** (-decimals) * (10.0 ** int(exp) if exp else 1.0)
        return abs(x - y) <= 1.0001 * unit
    return False


def same_line(e, a):
    te, ta = e.split(), a.split()
    return len(te) == len(ta) and all(same_token(x, y) for x, y in zip(te, ta))


def run_console(text, cwd, env, where):
    cmds = []
    for line in text:
        if line.startswith("$ "):
            cmds.append((line[2:], []))
        elif cmds:
            cmds[-1][1].append(line)
    fails = []
    for cmd, expected in cmds:
        r = subprocess.run(["bash", "-c", cmd], cwd=cwd, env=env, capture_output=True, text=True, timeout=600)
        got = (r.stdout + r.stderr).rstrip("\n").split("\n") if (r.stdout + r.stderr) else []
        exp = [l for l in expected]
        while exp and exp[-1] == "":
            exp.pop()
        if len(got) != len(exp) or not all(same_line(e, a) for e, a in zip(exp, got)):
            fails.append(f"{where}: `{cmd}` (exit {r.returncode}) printed\n" + "\n".join(got) +
                         "\nwhere the page shows\n" + "\n".join(exp))
    return len(cmds), fails


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--build", required=True)
    args = ap.parse_args()
    docs = [os.path.join(args.source, "README.md")] + sorted(glob.glob(os.path.join(args.source, "docs", "*.md")))
    env = dict(os.environ)
    env["PATH"] = os.path.join(args.build, "bin") + os.pathsep + env.get("PATH", "")
    pydir = os.path.join(args.build, "python")
    have_python = os.path.isdir(os.path.join(pydir, "hilite"))
    env["PYTHONPATH"] = pydir
    env.setdefault("MESA_SHADER_CACHE_DISABLE", "true")
    env["COLUMNS"] = "100"  # help output is wrapped to $COLUMNS off a terminal: the docs show it at 100
    ran, fails = [], []
    # Every relative link of the pages leads to a file of the tree (a page moved, a picture renamed).
    for doc in docs:
        for m in re.finditer(r'\]\(([^)#\s]+)(#[^)]*)?\)', open(doc, encoding="utf-8").read()):
            target = m.group(1)
            if not re.match(r'^[a-z]+:', target) and not os.path.exists(os.path.join(os.path.dirname(doc), target)):
                fails.append(f"{os.path.relpath(doc, args.source)}: a link to {target}, which does not exist")
    for doc in docs:
        name = os.path.relpath(doc, args.source)
        todo = [b for b in blocks(doc) if b[1] == "console" or b[3] or
                (b[1] == "toml" and b[2] and re.match(r'^# [\w.-]+\.toml$', b[2][0]))]
        if not todo:
            continue
        cwd = tempfile.mkdtemp(prefix="hilite-docs-")
        os.symlink(os.path.join(args.source, "experiments"), os.path.join(cwd, "experiments"))
        try:
            for line, lang, text, marked in todo:
                where = f"{name}:{line}"
                if lang == "toml" and text and re.match(r'^# [\w.-]+\.toml$', text[0]):
                    open(os.path.join(cwd, text[0][2:]), "w").write("\n".join(text) + "\n")
                    ran.append(f"{where} toml -> {text[0][2:]}")
                elif lang == "console":
                    n, f = run_console(text, cwd, env, where)
                    fails += f
                    ran.append(f"{where} console, {n} command(s){' FAILED' if f else ''}")
                elif lang in ("sh", "bash") and marked:
                    r = subprocess.run(["bash", "-e", "-c", "\n".join(text)], cwd=cwd, env=env, capture_output=True,
                                       text=True, timeout=600)
                    ok = r.returncode == 0
                    if not ok:
                        fails.append(f"{where}: sh block exited {r.returncode}:\n{r.stdout}{r.stderr}")
                    ran.append(f"{where} sh{'' if ok else ' FAILED'}")
                elif lang == "python" and marked:
                    if not have_python:
                        ran.append(f"{where} python: skipped, no Python module in this build ({pydir})")
                        continue
                    r = subprocess.run([sys.executable, "-c", "\n".join(text)], cwd=cwd, env=env, capture_output=True,
                                       text=True, timeout=600)
                    ok = r.returncode == 0
                    if not ok:
                        fails.append(f"{where}: python block exited {r.returncode}:\n{r.stdout}{r.stderr}")
                    ran.append(f"{where} python{'' if ok else ' FAILED'}")
        finally:
            shutil.rmtree(cwd, ignore_errors=True)
    print(f"checked the relative links of {len(docs)} pages; ran the examples of the docs:")
    for r in ran:
        print("  " + r)
    for f in fails:
        print("\n" + f, file=sys.stderr)
    return 1 if fails or not ran else 0


if __name__ == "__main__":
    sys.exit(main())
