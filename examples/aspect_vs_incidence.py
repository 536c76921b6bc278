"""Aspect ratio of the half-maximum highlight against the angle of incidence, for a reflection lobe (Phong)
and three microfacet lobes (Blinn-Phong, Beckmann, GGX): the default experiment's aspect plot
(experiments/eccentricity.toml) from the Python module.

    PYTHONPATH=build/python /usr/bin/python3 examples/aspect_vs_incidence.py -o aspect.png --csv aspect.csv

The scene: f proportional to D (fresnel none, implicit geometry), 256x256 auto-framed GL measurements.
Each model's width parameter (exponent for phong and blinn, roughness for beckmann and ggx) is tuned so
that its semi-major axis at normal incidence equals GGX alpha 0.1's, by a bracketed root find in
log(parameter) on hilite.measure itself (`hilite run` matches on the CPU twin's half-width instead, so
the two differ by the matching tolerance: about 1e-4 of aspect). Theory: microfacet lobes narrow as
cos(theta_i); a reflection lobe stays round (1).
"""

import argparse
import csv
import math
import os
import sys

import numpy as np

import hilite

SCENE = dict(fresnel="none", geometry="implicit", size=256)
TARGET = dict(model="ggx", roughness=0.1)  # what every lobe's width is matched to
MODELS = ["phong", "blinn", "beckmann", "ggx"]
INCIDENCES = np.arange(0.0, 90.0, 1.0)  # 0..89 deg


def width_keyword(model):
    """The keyword that sets a model's lobe width: exponent (larger = narrower) or roughness."""
    return "exponent" if model in ("phong", "blinn") else "roughness"


def major_at_normal(model, value, size=SCENE["size"]):
    """Semi-major axis (deg) of the model's highlight at normal incidence, with width parameter `value`."""
    params = {**SCENE, "size": size, "model": model, width_keyword(model): value}
    return hilite.measure(incidence=0.0, **params)["major_deg"]


def match_width(model, target_deg, size=SCENE["size"], rel_tol=1e-6, max_evals=60):
    """The width parameter whose semi-major axis at normal incidence is target_deg: the Illinois variant of
    regula falsi in log(parameter), from a bracket widened until the sign changes. Returns (value, evals)."""
    if model == TARGET["model"]:
        return TARGET["roughness"], 0
    lo, hi = (math.log(10.0), math.log(1e4)) if width_keyword(model) == "exponent" else (math.log(0.01), math.log(0.5))
    f = lambda x: major_at_normal(model, math.exp(x), size) - target_deg  # noqa: E731
    flo, fhi, evals = f(lo), f(hi), 2
    while flo * fhi > 0 and evals < 20:  # widen the bracket (the major axis is monotonic in the width)
        lo, hi = lo - 2.0, hi + 2.0
        flo, fhi, evals = f(lo), f(hi), evals + 2
    if flo * fhi > 0:
        raise RuntimeError(f"{model}: no {width_keyword(model)} gives a semi-major axis of {target_deg:g} deg")
    side = 0
    while evals < max_evals:
        x = (lo * fhi - hi * flo) / (fhi - flo)
        fx = f(x)
        evals += 1
        if abs(fx) <= rel_tol * target_deg or hi - lo < 1e-12:
            return math.exp(x), evals
        if fx * fhi > 0:
            hi, fhi = x, fx
            if side == 1:
                flo *= 0.5  # Illinois: halve the stale end's value so the bracket closes from both sides
            side = 1
        else:
            lo, flo = x, fx
            if side == -1:
                fhi *= 0.5
            side = -1
    return math.exp(0.5 * (lo + hi)), evals


def aspect_rows(models=MODELS, incidences=INCIDENCES, size=SCENE["size"]):
    """For each model: the matched width and hilite.measure over the angles (one call, numpy array in).
    Returns a list of dicts: model, incidence_deg, aspect, matched_parameter."""
    target = major_at_normal(TARGET["model"], TARGET["roughness"], size)
    rows = []
    for model in models:
        value, _ = match_width(model, target, size)
        cols = hilite.measure(incidence=np.asarray(incidences, dtype=float),
                              **{**SCENE, "size": size, "model": model, width_keyword(model): value})
        for t, a in zip(cols["incidence_deg"], cols["aspect"]):
            rows.append({"model": model, "incidence_deg": float(t), "aspect": float(a), "matched_parameter": value})
    return rows


def write_csv(rows, path):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["model", "incidence_deg", "aspect", "matched_parameter"])
        w.writeheader()
        for r in rows:
            w.writerow({**r, "aspect": f"{r['aspect']:.10g}", "matched_parameter": f"{r['matched_parameter']:.10g}"})


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")  # headless: no display needed
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 5.5), dpi=110)
    for model, marker in zip(dict.fromkeys(r["model"] for r in rows), "osD^v<>"):
        t = [r["incidence_deg"] for r in rows if r["model"] == model]
        a = [r["aspect"] for r in rows if r["model"] == model]
        # hollow markers of different shapes: the microfacet curves lie on one another
        ax.plot(t, a, marker=marker, markersize=4, fillstyle="none", linewidth=1.0, label=model)
    x = np.linspace(0.0, 89.0, 300)
    ax.plot(x, np.cos(np.radians(x)), "k--", linewidth=1, label="cos(theta_i) (narrow microfacet lobe)")
    ax.plot(x, np.ones_like(x), "k:", linewidth=1, label="1 (reflection lobe)")
    ax.set_title("Aspect ratio (minor/major) of the half-maximum highlight")
    ax.set_xlabel("angle of incidence theta_i (deg)")
    ax.set_ylabel("aspect")
    ax.set_xlim(0, 89)
    ax.set_ylim(0, 1.05)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower left")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def folder_problem(path):
    """Why the folder of `path` cannot hold it ("" when it exists or can be made): a file where a folder of
    the path should be."""
    folder = os.path.dirname(os.path.abspath(path))
    while folder and not os.path.exists(folder):
        folder = os.path.dirname(folder)
    return "" if os.path.isdir(folder) else f"{folder} is a file, not a folder"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", default="aspect.png", help="the plot (PNG; default aspect.png)")
    ap.add_argument("--csv", help="also write model, incidence_deg, aspect, matched_parameter here")
    args = ap.parse_args(argv)
    folders = []
    for name, path in (("-o", args.output), ("--csv", args.csv)):  # refuse before measuring or writing
        if path is None:
            continue
        if not path:
            ap.error(f"{name}: an empty file name")
        why = folder_problem(path)
        if why:
            ap.error(f"{name} {path}: {why}")
        folders.append(os.path.dirname(os.path.abspath(path)))
    if not args.output.lower().endswith(".png"):
        ap.error(f"-o {args.output}: the plot is a PNG (a name ending in .png)")
    for folder in folders:  # made once everything is checked, as hilite makes an output folder
        os.makedirs(folder, exist_ok=True)
    rows = aspect_rows()
    for model in MODELS:
        r = [x for x in rows if x["model"] == model]
        at = {x["incidence_deg"]: x["aspect"] for x in r}
        print(f"{model:9} {width_keyword(model)} {r[0]['matched_parameter']:.6g}: aspect at 0/30/60/75/85 deg "
              + " ".join(f"{at[t]:.4f}" for t in (0.0, 30.0, 60.0, 75.0, 85.0)))
    plot(rows, args.output)
    print(f"wrote {args.output}")
    if args.csv:
        write_csv(rows, args.csv)
        print(f"wrote {args.csv}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
