#!/usr/bin/python3
"""Measures what experiments cost at scale and writes the numbers into docs/scaling.md (between the
scaling:begin and scaling:end markers).

Every number is measured by this run on this machine:
- per configuration, for each measurement kind: `hilite run` of the same sweep at two sizes, the difference in
  wall time over the difference in configurations (the process's start and the reports cancel out);
- rows written: build/bin/hilite_bench_scale's BM_RunRows (measured only, group commit, an fsync per row);
- merges: BM_Merge, S shards x R rows (wall time, the merge process's peak resident memory);
- a Dask client's share of a row: BM_ClientAppend;
- checking: `hilite run --check` of an experiment of 10^6 configurations.

    /usr/bin/python3 bench/scaling.py --build build             # prints the tables and rewrites docs/scaling.md
    /usr/bin/python3 bench/scaling.py --build build --no-write  # prints them only
"""

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
BEGIN = "<!-- scaling:begin (bench/scaling.py) -->\n"
END = "<!-- scaling:end -->"

HEAD = '[experiment]\nname = "{name}"\n'
SWEEP = '[[sweep]]\nkey = "light.incidence"\nvalues = [{values}]\n'

# (label, extra experiment text, small and large sweep sizes)
KINDS = [
    ("directional light, GGX α 0.1, 512² auto-framed", '[scene.material]\nmodel = "ggx"\nroughness = 0.1\n', 4, 24),
    ("point light at distance 10, GGX α 0.1", '[scene.material]\nmodel = "ggx"\nroughness = 0.1\n'
     '[scene.light]\nlight = "point"\nlight_distance = 10\n', 4, 24),
    ("the sun's disk (0.266°), GGX α 0.02", '[scene.material]\nmodel = "ggx"\nroughness = 0.02\n'
     '[scene.light]\nlight = "disk"\nlight_angle = 0.266\n', 2, 8),
    ("measured table (MERL .binary of GGX α 0.1)", '[scene.material]\nmeasured = "{table}"\n', 2, 8),
    (".brdf file (BRDF Explorer GGX)", '[scene.material]\nbrdf = "{brdf}"\n', 4, 16),
    ("bounces (Beckmann glass m 0.3, 50,000 paths)", '[scene.material]\nmodel = "beckmann"\nmaterial = "glass"\n'
     'roughness = 0.3\n[bounces]\npaths = 50000\n', 2, 6),
]


def fail(msg):
    print(f"scaling.py: {msg}", file=sys.stderr)
    sys.exit(1)


def wall(cmd):
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"{' '.join(cmd)}: exit {r.returncode}: {r.stderr.strip()[-400:]}")
    return time.perf_counter() - t0


def per_config(hilite, work, label, text, n1, n2, repeats):
    times = []
    for n in (n1, n2):
        values = ", ".join(f"{80.0 * i / max(1, n - 1):.3f}" for i in range(n))
        f = os.path.join(work, f"kind{n}.toml")
        with open(f, "w") as out:
            out.write(HEAD.format(name="kind") + text + SWEEP.format(values=values))
        best = None
        for _ in range(repeats):
            out_dir = os.path.join(work, f"out{n}")
            shutil.rmtree(out_dir, ignore_errors=True)
            t = wall([hilite, "run", f, "-o", out_dir])
            best = t if best is None else min(best, t)
        times.append(best)
    return (times[1] - times[0]) / (n2 - n1)


def bench(build, filt):
    exe = os.path.join(build, "bin", "hilite_bench_scale")
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        r = subprocess.run([exe, f"--benchmark_filter={filt}", f"--benchmark_out={out.name}",
                            "--benchmark_out_format=json"], capture_output=True, text=True)
        if r.returncode != 0:
            fail(f"{exe}: exit {r.returncode}: {r.stderr[-400:]}")
        return {b["name"]: b for b in json.load(open(out.name))["benchmarks"]}


def fmt_s(s):
    if s < 1e-3:
        return f"{s * 1e6:.0f} µs"
    if s < 1:
        return f"{s * 1e3:.1f} ms"
    return f"{s:.2f} s"


def fmt_h(s):
    h = s / 3600
    if h < 1:
        return f"{s / 60:.0f} min"
    if h < 48:
        return f"{h:.1f} h"
    return f"{h / 24:.0f} d"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--repeats", type=int, default=2, help="runs of each sweep (the fastest counts)")
    ap.add_argument("--no-write", action="store_true")
    ap.add_argument("--merge", default="200/50,200/500,200/5000", help="S/R pairs for BM_Merge")
    args = ap.parse_args(argv)
    hilite = os.path.join(args.build, "bin", "hilite")
    if not os.access(hilite, os.X_OK):
        fail(f"no {hilite}: build first")
    load0 = os.getloadavg()[0]
    work = tempfile.mkdtemp(prefix="hilite-scaling-")
    try:
        table = os.path.join(work, "ggx.binary")
        wall([hilite, "brdf", "tabulate", "--model", "ggx", "--roughness", "0.1", "-o", table])
        brdf = os.path.join(ROOT, "experiments", "brdfs", "ggx.brdf")
        kinds = []
        for label, text, n1, n2 in KINDS:
            c = per_config(hilite, work, label, text.format(table=table, brdf=brdf), n1, n2, args.repeats)
            kinds.append((label, c))
            print(f"{label}: {fmt_s(c)} a configuration", flush=True)
        rows = bench(args.build, "RunRows")
        unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
        run = {}
        for m in (0, 1, 2):
            b = rows[f"BM_RunRows/400/{m}/iterations:3/real_time"]
            run[m] = b["real_time"] * unit[b["time_unit"]] / 400
        b = bench(args.build, "ClientAppend")["BM_ClientAppend/20000/iterations:3/real_time"]
        client_row = b["real_time"] * unit[b["time_unit"]] / 20000
        merges = []
        for pair in args.merge.split(","):
            s, r = map(int, pair.split("/"))
            b = bench(args.build, f"Merge/{s}/{r}/")[f"BM_Merge/{s}/{r}/iterations:1/real_time"]
            merges.append((s, r, b["real_time"] * unit[b["time_unit"]], b["peak_MB"]))
            print(f"merge {s} x {r}: {b['real_time']:.1f} s, {b['peak_MB']:.0f} MB", flush=True)
        big = os.path.join(work, "big.toml")
        with open(big, "w") as out:
            out.write(HEAD.format(name="big") + '[[sweep]]\nkey = "material.roughness"\nvalues = [' +
                      ", ".join(f"{0.01 + 0.4 * i / 1000:.5f}" for i in range(1000)) + ']\n' +
                      SWEEP.format(values=", ".join(f"{80.0 * i / 1000:.3f}" for i in range(1000))))
        check = wall([hilite, "run", big, "--check", "-o", os.path.join(work, "big")])
    finally:
        shutil.rmtree(work, ignore_errors=True)
    load1 = os.getloadavg()[0]

    lines = [f"Measured by `bench/scaling.py` on {os.cpu_count()} cores (load average {load0:.2f} before, "
             f"{load1:.2f} after), llvmpipe; one `hilite` process at a time.\n",
             "| measurement kind | a configuration | 10^6 configurations | 10^8 configurations |",
             "|---|---|---|---|"]
    for label, c in kinds:
        lines.append(f"| {label} | {fmt_s(c)} | {fmt_h(c * 1e6)} | {fmt_h(c * 1e8)} |")
    lines += ["", "Rows written, per row of a 400-configuration sweep (BM_RunRows, the mean of 3 runs each; one GL context per run in each):", "",
              "| | per row | over measuring alone |", "|---|---|---|",
              f"| measured in process, not written | {fmt_s(run[0])} | |",
              f"| `hilite run` (group commit: an fsync at most every 100 ms) | {fmt_s(run[1])} | "
              f"{100 * (run[1] / run[0] - 1):+.1f}% |",
              f"| `hilite run --fsync-each-row` | {fmt_s(run[2])} | {100 * (run[2] / run[0] - 1):+.1f}% |",
              "", "`hilite merge` of S shards of R rows each (BM_Merge; generated rows with real fingerprints):", "",
              "| shards × rows | rows | wall time | per row | peak memory |", "|---|---|---|---|---|"]
    for s, r, t, mb in merges:
        lines.append(f"| {s} × {r} | {s * r:,} | {t:.1f} s | {fmt_s(t / (s * r))} | {mb:.0f} MB |")
    lines += ["", f"A Dask client's share of a row (BM_ClientAppend: parsed, its fingerprint checked, appended with group "
              f"commit; 20,000 rows): {fmt_s(client_row)}, at most {1 / client_row:,.0f} rows a second for the whole "
              "cluster."]
    lines += ["", f"`hilite run --check` of an experiment of 10^6 configurations (every one resolved and "
              f"validated, nothing measured): {check:.1f} s."]
    text = "\n".join(lines) + "\n"
    print(text)
    if args.no_write:
        return
    page = os.path.join(ROOT, "docs", "scaling.md")
    doc = open(page, encoding="utf-8").read()
    if BEGIN not in doc or END not in doc:
        fail(f"{page}: no {BEGIN.strip()} ... {END} markers")
    a, b = doc.index(BEGIN) + len(BEGIN), doc.index(END)
    with open(page, "w", encoding="utf-8") as f:
        f.write(doc[:a] + text + doc[b:])


if __name__ == "__main__":
    main()
