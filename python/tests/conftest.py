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
