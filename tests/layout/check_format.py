#!/usr/bin/env python3
"""ctest format_check: every C++ file of the project is as clang-format (.clang-format, Debian 12's
clang-format 14) writes it. Prints the files that differ (fix: scripts/format) and exits 1; 0 when none do."""
import os
import shutil
import subprocess
import sys

root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
tool = shutil.which("clang-format")
if not tool:
    sys.exit("format_check: clang-format not found (scripts/quickstart installs Debian's clang-format)")
files = []
for top in ("src", "include", "tests", "bench", "fuzz", "python/src"):
    for d, dirs, names in os.walk(os.path.join(root, top)):
        dirs[:] = [x for x in dirs if x != "corpus"]
        files += [os.path.join(d, n) for n in names if n.endswith((".cpp", ".hpp", ".h"))]
if len(files) < 100:
    sys.exit(f"format_check: found only {len(files)} C++ files under {root}")
bad = []
for i in range(0, len(files), 50):
    batch = sorted(files)[i:i + 50]
    r = subprocess.run([tool, "--dry-run", "--Werror", "--style=file", *batch], capture_output=True, text=True)
    if r.returncode != 0:
        bad += sorted({line.split(":")[0] for line in r.stderr.splitlines() if ": error:" in line})
for f in bad:
    print(os.path.relpath(f, root), "is not formatted (scripts/format rewrites it)")
print(f"format_check: {len(files)} files, {len(bad)} not as .clang-format writes them")
sys.exit(1 if bad else 0)
