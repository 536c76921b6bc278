#!/usr/bin/python3
"""Measures hilite's speed table and writes it into docs/speed.md (between the speed:begin and speed:end markers).

Every number in the table is measured by this run: build/bin/hilite_bench (Google Benchmark, medians of
--repetitions), whole-process wall times of the hilite executable (medians of --repeats), and the plain-numpy
baseline (bench/numpy_baseline.py) on the same 86-angle sweep in the same run. Run it on an idle machine:

    /usr/bin/python3 bench/speed_table.py --build build            # prints the table and rewrites docs/speed.md
    /usr/bin/python3 bench/speed_table.py --build build --no-write # prints it only

The load average before and after is printed with the table: a loaded machine's numbers are not the tool's.
"""

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
BEGIN = "<!-- speed:begin (bench/speed_table.py) -->\n"
END = "<!-- speed:end -->"

# (label, benchmark name as Google Benchmark prints it, counter to report instead of the time, or None)
BENCHMARKS = [
    ("one auto-framed measurement at 512² (aim at 64², final render cropped to the highlight, readback, "
     "analysis, diagnoses), in-process", "BM_MeasureAutoFramed/512/1/real_time", None),
    ("the same without the crop (whole 512² frame)", "BM_MeasureAutoFramed/512/0/real_time", None),
    ("`--tolerance 1e-3` (GGX α 0.1 at 60°), in-process", "BM_Tolerance/0/real_time", None),
    ("its two renders alone (draw + readback): the 64² aim / the final 102k-pixel crop of 512²",
     ["BM_DrawCrop/0/real_time", "BM_DrawCrop/1/real_time"], None),
    ("draw 512² / 2048²", ["BM_Draw/512/real_time", "BM_Draw/2048/real_time"], None),
    ("analysis (sub-pixel boundary) 512² / 2048²", ["BM_Analysis/512/1", "BM_Analysis/2048/1"], None),
    ("86 angles through the library (`Session::measure`, 0:85:1 at 512²)", "BM_SessionSweep86/real_time", None),
    ("`hilite fit`: 4 models × 18 angles × 5 thresholds at 256², a GGX 0.1 MERL table",
     "BM_Fit4Models/iterations:1/real_time", None),
]
FILTER = "BM_MeasureAutoFramed/512/|BM_Tolerance/0|BM_DrawCrop|BM_Draw/(512|2048)|BM_Analysis/(512|2048)/1|BM_SessionSweep86|BM_Fit4Models"


def fail(msg):
    print(f"speed_table.py: {msg}", file=sys.stderr)
    sys.exit(2)


def fmt_ms(ms):
    if ms >= 1000:
        return f"{ms / 1000:.2f} s"
    return f"{ms:.3g} ms" if ms < 10 else f"{ms:.0f} ms"


def benchmarks(bench, repetitions):
    out = subprocess.run([bench, f"--benchmark_filter={FILTER}", f"--benchmark_repetitions={repetitions}",
                          "--benchmark_report_aggregates_only=true", "--benchmark_format=json"],
                         check=True, capture_output=True, text=True).stdout
    medians = {}
    for b in json.loads(out)["benchmarks"]:
        name = b["name"]
        unit = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b.get("time_unit", "ns")]
        if b.get("aggregate_name") == "median" or (b.get("run_type") == "iteration" and b.get("iterations") == 1):
            base = name[: -len("_median")] if name.endswith("_median") else name
            medians[base] = b["real_time"] * unit
    return medians


def wall(cmd, repeats, extra_env=None):
    times = []
    env = dict(os.environ, **(extra_env or {}))
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
        times.append((time.perf_counter() - t0) * 1e3)
    return statistics.median(times)


def machine(hilite):
    cpu = platform.processor() or "?"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    gl = subprocess.run([hilite, "explain", "--part", "gl"], capture_output=True, text=True).stdout
    renderer = next((l.split(":", 1)[1].strip() for l in gl.splitlines() if "renderer" in l.lower()), "?")
    return f"{os.cpu_count()} cores, {cpu}, GL {renderer}"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="build folder (bin/hilite, bin/hilite_bench)")
    ap.add_argument("--repetitions", type=int, default=5, help="Google Benchmark repetitions (median)")
    ap.add_argument("--repeats", type=int, default=3, help="whole-process runs (median)")
    ap.add_argument("--no-write", action="store_true", help="print the table, leave docs/speed.md as it is")
    args = ap.parse_args(argv)
    hilite = os.path.join(args.build, "bin", "hilite")
    bench = os.path.join(args.build, "bin", "hilite_bench")
    for exe in (hilite, bench):
        if not os.access(exe, os.X_OK):
            fail(f"--build {args.build}: no {exe} (cmake --build {args.build})")
    if args.repetitions < 1 or args.repeats < 1:
        fail("--repetitions and --repeats: at least 1")
    readme = os.path.join(ROOT, "docs", "speed.md")
    text = open(readme, encoding="utf-8").read()
    if not args.no_write and (BEGIN not in text or END not in text):
        fail(f"{readme}: no speed:begin / speed:end markers")

    load0 = os.getloadavg()[0]
    env = dict(os.environ, MESA_SHADER_CACHE_DISABLE="true")
    os.environ.update(env)
    med = benchmarks(bench, args.repetitions)
    rows = []
    for label, names, _ in BENCHMARKS:
        names = names if isinstance(names, list) else [names]
        missing = [n for n in names if n not in med]
        if missing:
            fail(f"benchmark {missing[0]} did not run (names: {', '.join(sorted(med))})")
        rows.append((label, " / ".join(fmt_ms(med[n]) for n in names)))

    sweep = [hilite, "measure", "--model", "ggx", "--roughness", "0.1", "--geometry", "smith", "--fresnel", "schlick",
             "--f0", "0.04", "--size", "512", "--incidence", "0:85:1", "--json"]
    one = sweep[:-3] + ["--incidence", "60", "--json"]
    half = sweep[:-3] + ["--incidence", "0:85:0.5", "--json"]
    t_sweep = wall(sweep, args.repeats)
    t_one = wall(one, args.repeats)
    t_half = wall(half, args.repeats)
    rows.append(("`hilite measure` one angle (60°), whole process incl. start-up (no shader cache)", fmt_ms(t_one)))
    rows.append(("`hilite measure --incidence 0:85:1 --size 512`, whole process", fmt_ms(t_sweep)))
    # What a further angle costs a process (171 angles against 86), beside what it costs in-process.
    in_process = med["BM_SessionSweep86/real_time"] / 86
    rows.append(("each further angle of a whole process (0:85:0.5 against 0:85:1) / in-process (`Session`)",
                 f"{fmt_ms((t_half - t_sweep) / 85)} / {fmt_ms(in_process)}"))
    # The numpy baseline in its own process, twice: as Python starts by default, and with glibc's malloc told
    # to keep freed memory (no mmap per large temporary, no trimming). On this VM every fresh page faults
    # expensively, and numpy's 2 MB temporaries otherwise take new pages each time: measured 13.8 s against
    # 1.47 s for the same arithmetic. hilite is timed both ways too; the fair ratio is against the faster baseline.
    sys.path.insert(0, HERE)
    import numpy_baseline  # noqa: E402 (beside this script)
    tuned = numpy_baseline.MALLOC_KEEPS_MEMORY
    t_numpy = numpy_baseline.sweep_seconds() * 1e3
    t_numpy_tuned = numpy_baseline.sweep_seconds(tuned) * 1e3
    t_sweep_tuned = wall(sweep, args.repeats, tuned)
    rows.append(("the same 86 measurements in plain numpy (`bench/numpy_baseline.py`, float64, this run), "
                 "glibc's default malloc",
                 f"{fmt_ms(t_numpy)} ({t_numpy / t_sweep:.1f}× hilite's whole process)"))
    rows.append(("the same in numpy with `MALLOC_MMAP_THRESHOLD_` and `MALLOC_TRIM_THRESHOLD_` set to 1e9 "
                 "(freed memory reused: no page faults), hilite likewise",
                 f"{fmt_ms(t_numpy_tuned)} ({t_numpy_tuned / t_sweep_tuned:.1f}× hilite's {fmt_ms(t_sweep_tuned)})"))
    with tempfile.TemporaryDirectory() as tmp:
        t_exp = wall([hilite, "run", "eccentricity", "-o", os.path.join(tmp, "e")], 1)
    rows.append(("default experiment (`hilite run eccentricity`: 360 measurements at 256², plots, contact sheet)",
                 fmt_ms(t_exp)))
    load1 = os.getloadavg()[0]

    table = (f"Measured by `bench/speed_table.py` on {time.strftime('%Y-%m-%d')}: {machine(hilite)}; load average "
             f"{load0:.2f} before, {load1:.2f} after; benchmark medians of {args.repetitions}, whole-process medians "
             f"of {args.repeats}.\n\n| what | time |\n|---|---|\n")
    table += "".join(f"| {label} | {value} |\n" for label, value in rows)
    print(table)
    if not args.no_write:
        a, b = text.index(BEGIN) + len(BEGIN), text.index(END)
        tmp = readme + ".tmp"
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(text[:a] + table + text[b:])
        os.replace(tmp, readme)
    return 0


if __name__ == "__main__":
    sys.exit(main())
