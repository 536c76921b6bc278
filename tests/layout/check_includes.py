#!/usr/bin/env python3
"""ctest include_direction: every project #include points down the layer list.

The layers and their arrows are the DEPS of each hilite_layer() in src/ (src/CMakeLists.txt and
src/<layer>/CMakeLists.txt); a layer may include its own headers and those of every layer it links,
directly or not. A file under src/<layer>/ or include/hilite/<layer>/ belongs to <layer>. Public headers
(include/hilite/) include only public headers ("hilite/..."), so the installed tree is closed. The include
paths cannot enforce any of this: every layer sees src/ and include/ in the build tree.
Exit 0 when every include is allowed, else 1 with one line per offending include."""
import os
import re
import sys

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
os.chdir(root)

layer_re = re.compile(r"hilite_layer\((\w+)(.*?)\)\s*$", re.S | re.M)
deps = {}
for d, _, files in os.walk("src"):
    for f in files:
        if f == "CMakeLists.txt":
            text = open(os.path.join(d, f)).read()
            for m in layer_re.finditer(text):
                body = m.group(2).split("DEPS", 1)
                deps[m.group(1)] = set(re.findall(r"\bhilite_(\w+)", body[1])) if len(body) > 1 else set()
if len(deps) < 5:
    sys.exit(f"check_includes: found only {sorted(deps)} in src/**/CMakeLists.txt: the parser is out of date")
for layer in deps:
    deps[layer].discard("glad")


def below(layer, seen=None):
    seen = set() if seen is None else seen
    for d in deps.get(layer, ()):
        if d not in seen:
            seen.add(d)
            below(d, seen)
    return seen


include_re = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
bad, checked = [], 0
for base in ("src", "include/hilite"):
    for d, _, files in os.walk(base):
        for f in files:
            if not f.endswith((".hpp", ".cpp", ".h", ".inc")):
                continue
            path = os.path.join(d, f)
            rel = os.path.relpath(path, base).split(os.sep)
            layer = rel[0] if len(rel) > 1 else None  # src/main.cpp, include/hilite/hilite.hpp: above every layer
            public = base == "include/hilite"
            for inc in include_re.findall(open(path, encoding="utf-8").read()):
                checked += 1
                target = inc[len("hilite/"):] if inc.startswith("hilite/") else inc
                if public and not inc.startswith("hilite/"):
                    bad.append(f'{path}: public header includes "{inc}", which is not public (hilite/...)')
                    continue
                if public and not os.path.exists(os.path.join("include", inc)) and not inc.endswith((".glsl", "version.hpp")):
                    bad.append(f'{path}: includes "{inc}", which is not under include/')
                    continue
                to = target.split("/")[0] if "/" in target else None
                if layer is None or to is None or to not in deps or to == layer:
                    continue
                if to not in below(layer):
                    bad.append(f'{path}: layer {layer} includes "{inc}" of layer {to}, which {layer} does not link '
                               f'(it links {", ".join(sorted(below(layer))) or "nothing"})')
for line in bad:
    print(line)
print(f"check_includes: {checked} includes in src/ and include/hilite/, {len(deps)} layers, {len(bad)} against the arrows")
sys.exit(1 if bad else 0)
