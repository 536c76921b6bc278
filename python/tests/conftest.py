"""Shared helpers: the CLI the module is compared with ($HILITE_CLI, set by ctest), and its JSON rows."""

import json
import os
import subprocess

import numpy as np
import pytest

CLI = os.environ.get("HILITE_CLI") or os.path.join(os.path.dirname(__file__), "..", "..", "build", "bin", "hilite")
# Fields that are times (render_ms, measure_ms, startup_ms, ...), not results: they differ between any two runs.
def is_time(key):
    return key.endswith("_ms")


def cli(*args, check=True):
    r = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError(f"hilite {' '.join(map(str, args))}: exit {r.returncode}: {r.stderr}")
    return r


def cli_rows(*args):
    return [json.loads(line) for line in cli(*args, "--json").stdout.splitlines() if line.strip()]


def without_times(row):
    if isinstance(row, dict):
        return {k: without_times(v) for k, v in row.items() if not is_time(k)}
    if isinstance(row, list):
        return [without_times(v) for v in row]
    return row


def rows(path):
    """A results.jsonl's rows without their timing fields."""
    return [without_times(json.loads(line)) for line in open(path)]


def read_pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3)[::-1]  # PFM rows run bottom to top


@pytest.fixture
def hilite():
    import hilite as h
    return h


def stub_typed_dicts(hilite):
    """The TypedDicts of the generated __init__.pyi: {class name: {field: annotation text}}."""
    import ast
    tree = ast.parse(open(os.path.join(os.path.dirname(hilite.__file__), "__init__.pyi")).read())
    return {n.name: {a.target.id: ast.unparse(a.annotation) for a in n.body if isinstance(a, ast.AnnAssign)}
            for n in tree.body if isinstance(n, ast.ClassDef) and any(ast.unparse(b) == "TypedDict" for b in n.bases)}


def _split(text, sep):
    """`text` split at `sep` outside brackets."""
    parts, depth, cur = [], 0, ""
    for ch in text:
        depth += ch == "["
        depth -= ch == "]"
        if ch == sep and depth == 0:
            parts.append(cur.strip())
            cur = ""
        else:
            cur += ch
    return parts + [cur.strip()]


def matches(value, annotation, dicts):
    """Whether `value` has the stub's type `annotation` (the forms gen_stubs.py writes)."""
    for t in _split(annotation, "|"):
        if t == "None" and value is None or t == "Any":
            return True
        if t == "bool" and isinstance(value, bool):
            return True
        if t == "int" and isinstance(value, int) and not isinstance(value, bool):
            return True
        if t == "float" and isinstance(value, (int, float)) and not isinstance(value, bool):
            return True
        if t == "str" and isinstance(value, str):
            return True
        if t.startswith("Literal[") and value in [eval(x) for x in _split(t[8:-1], ",")]:
            return True
        if t.startswith("list[") and isinstance(value, list) and all(matches(v, t[5:-1], dicts) for v in value):
            return True
        if t.startswith("dict[") and isinstance(value, dict):
            _, vt = _split(t[5:-1], ",")
            if all(isinstance(k, str) and matches(v, vt, dicts) for k, v in value.items()):
                return True
        if t in dicts and isinstance(value, dict) and not typed_dict_mismatches(value, t, dicts):
            return True
    return False


def typed_dict_mismatches(row, name, dicts):
    """The keys of `row` that the stub's TypedDict `name` lacks or types otherwise ([] when it describes it)."""
    fields = dicts[name]
    return [f"{k}: {v!r} is not {fields.get(k, '(no such field)')}" for k, v in row.items()
            if k not in fields or not matches(v, fields[k], dicts)]
