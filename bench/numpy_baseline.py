"""The highlight measurement in plain numpy: what `hilite measure` does for one auto-framed 512x512
measurement, written the way a careful numpy user would, as the baseline bench_python.py times hilite against.

Scene (fixed; bench_python.py measures hilite on the same one): a distant light at theta_i in the x-z
plane, GGX alpha 0.1, height-correlated Smith G2 (what --geometry smith is, include/hilite/brdf/params.hpp), Schlick
F0 0.04 (grey, so the luminance is the value), irradiance 1. The lobe is L(we) = f(wi, we) E cos(theta_i).

The work per angle, as ../../shared/notes/measurement.md defines the measurement and
src/measurement/{lobe_survey,measure_scene}.cpp does it:
  (a) a survey of the hemisphere (29 rings dense toward the horizon x 72 azimuths, as lobe_survey.cpp),
      the global peak by compass climbs from the mirror direction and the survey's best maxima, the parts of
      {L >= 0.5 peak} (the strip above the horizon at 58-64 deg is a part of its own), then per part a coarse
      64x64 grid to aim and size its frame;
  (b) per part the final size x size evaluation over its frame in the (u, v) chart about the mirror
      direction (azimuthal-equidistant). hilite renders a pinhole view; sampling the chart directly on a
      grid is less work (every sample has the same chart area, no Jacobian), so the comparison favours numpy;
  (c) the region's area moments (each sample weighted by its chart area, du dv), the parts' moments added,
      and the ellipse of the same moments: aspect = minor / major, semi-axes 2 sqrt(lambda).
Vectorised float64; the Python loops run over parts, aiming rounds and climb steps, never over samples.
Limits: this scene only (no other model, light or diagnosis), and a pixel is in the region by its centre
(hilite interpolates the boundary), which costs it some 1e-4 of aspect at 512^2.

Run as a script to compare with the CLI:  /usr/bin/python3 bench/numpy_baseline.py --cli build/bin/hilite

Time it with glibc's malloc keeping freed memory as well (MALLOC_MMAP_THRESHOLD_=1000000000
MALLOC_TRIM_THRESHOLD_=1000000000): each 512^2 float64 temporary is 2 MB, which glibc otherwise maps fresh and
returns, and where page faults are expensive (this project's VM) that alone made the sweep 9x slower (13.8 s
against 1.47 s). bench/speed_table.py and python/bench/bench_python.py time both and judge against the faster.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

ALPHA = 0.1
F0 = 0.04
FRAC = 0.5
AIM_SIZE = 64
# Survey rings (deg above the horizon): every 4 deg, then ever closer to the horizon (lobe_survey.cpp rings()).
RINGS_DEG = np.array([*np.arange(88.0, 3.0, -4.0), 2.0, 1.0, 0.5, 0.2, 0.05, 0.01, 1e-4])
AZIMUTHS = 72


class Lobe:
    """L(we) for the scene at theta_i, and the mirror chart (u, v) <-> we."""

    def __init__(self, theta_deg):
        t = math.radians(theta_deg)
        self.wi = np.array([math.sin(t), 0.0, math.cos(t)])
        self.wr = np.array([-math.sin(t), 0.0, math.cos(t)])
        self.eu = np.array([math.cos(t), 0.0, math.sin(t)])  # +u towards the normal
        self.ev = np.array([0.0, 1.0, 0.0])

    def direction(self, u, v):
        """we at chart (u, v) (radians): cos(rho) wr + sin(rho)/rho (u eu + v ev), rho = |(u, v)|."""
        rho = np.hypot(u, v)
        c, s = np.cos(rho), np.sinc(rho / np.pi)  # sinc(x) = sin(pi x) / (pi x): sin(rho) / rho, 1 at 0
        return [c * self.wr[k] + s * (u * self.eu[k] + v * self.ev[k]) for k in range(3)]

    def chart(self, x, y, z):
        """(u, v) of directions (components x, y, z)."""
        cu = x * self.eu[0] + z * self.eu[2]
        cv = y
        cw = x * self.wr[0] + z * self.wr[2]
        rho = np.arctan2(np.hypot(cu, cv), cw)
        psi = np.arctan2(cv, cu)
        return rho * np.cos(psi), rho * np.sin(psi)

    def value(self, x, y, z):
        """L = D G2 F / (4 cos_i cos_o) * cos_i for directions (x, y, z); 0 at and below the horizon."""
        wi = self.wi
        hx, hy, hz = x + wi[0], y + wi[1], z + wi[2]
        inv = 1.0 / np.sqrt(hx * hx + hy * hy + hz * hz)
        hx, hy, hz = hx * inv, hy * inv, hz * inv
        a2 = ALPHA * ALPHA
        d = hz * hz * a2 + (hx * hx + hy * hy)
        D = np.where(hz > 0, a2 / (np.pi * d * d), 0.0)  # GGX, Walter et al. 2007
        zo = np.where(z > 0, z, 1.0)  # below the horizon: masked out below, kept finite here
        lam_o = 0.5 * (-1.0 + np.sqrt(1.0 + a2 * np.maximum(0.0, 1.0 - zo * zo) / (zo * zo)))  # Heitz 2014 eq. 72
        lam_i = 0.5 * (-1.0 + math.sqrt(1.0 + a2 * max(0.0, 1.0 - wi[2] ** 2) / wi[2] ** 2))
        c = np.clip(1.0 - (x * hx + y * hy + z * hz), 0.0, 1.0)
        F = F0 + (1.0 - F0) * c**5  # Schlick 1994
        return np.where(z > 0, D * F / ((1.0 + lam_i + lam_o) * 4.0 * zo), 0.0)  # G2 height-correlated

    def at(self, u, v):
        return self.value(*self.direction(u, v))


def climb(lobe, starts, until=1e-10):
    """Compass search in the chart from every start at once (lobe_survey.cpp climb): a step that finds a
    higher point moves there and doubles (to 4 deg), else halves, from 1 deg down to `until` rad."""
    q = np.array(starts, dtype=float)  # (S, 2)
    best = lobe.at(q[:, 0], q[:, 1])
    step = np.full(len(q), math.radians(1.0))
    r = 1.0 / math.sqrt(2.0)
    dirs = np.array([[1, 0], [-1, 0], [0, 1], [0, -1], [r, r], [-r, -r], [r, -r], [-r, r]])
    for _ in range(4000):
        live = step > until
        if not live.any():
            break
        p = q[:, None, :] + step[:, None, None] * dirs[None, :, :]  # (S, 8, 2)
        x = lobe.at(p[..., 0], p[..., 1])
        k = np.argmax(x, axis=1)
        xk = x[np.arange(len(q)), k]
        up = live & (xk > best)
        q[up] = p[up, k[up]]
        best[up] = xk[up]
        step = np.where(up, np.minimum(2.0 * step, math.radians(4.0)), np.where(live, 0.5 * step, step))
    return q, best


def label(mask, wrap_columns=False):
    """4-connected components of a boolean image by min-label propagation (vectorised; iterations ~ the
    longest path). Returns labels (-1 outside)."""
    big = mask.size
    lab = np.where(mask, np.arange(mask.size).reshape(mask.shape), big)
    while True:
        m = lab.copy()
        m[1:] = np.minimum(m[1:], lab[:-1])
        m[:-1] = np.minimum(m[:-1], lab[1:])
        if wrap_columns:
            m = np.minimum(m, np.roll(lab, 1, axis=1))
            m = np.minimum(m, np.roll(lab, -1, axis=1))
        else:
            m[:, 1:] = np.minimum(m[:, 1:], lab[:, :-1])
            m[:, :-1] = np.minimum(m[:, :-1], lab[:, 1:])
        m = np.where(mask, m, big)
        if np.array_equal(m, lab):
            break
        lab = m
    return np.where(mask, lab, -1)


def survey(lobe):
    """(a) The hemisphere's samples, the global peak, the level and the parts' chart boxes (radians)."""
    elev = np.radians(RINGS_DEG)[:, None]
    az = np.pi + 2.0 * np.pi * np.arange(AZIMUTHS)[None, :] / AZIMUTHS  # the forward direction first
    x, y, z = np.cos(elev) * np.cos(az), np.cos(elev) * np.sin(az), np.sin(elev) * np.ones_like(az)
    val = lobe.value(x, y, z)
    su, sv = lobe.chart(x, y, z)
    # Peak: climbs from the mirror direction and the grid's four best local maxima.
    pad = np.pad(val, ((1, 1), (0, 0)), constant_values=-1.0)
    top = (val > 0) & (val >= pad[:-2]) & (val >= pad[2:]) & (val >= np.roll(val, 1, 1)) & (val >= np.roll(val, -1, 1))
    order = np.argsort(-val[top])[:4]
    starts = [(0.0, 0.0)] + list(zip(su[top][order], sv[top][order]))
    q, best = climb(lobe, starts)
    peak = max(best.max(), val.max())
    peak_uv = q[np.argmax(best)]
    level = FRAC * peak
    lab = label(val >= level, wrap_columns=True)
    grow = math.radians(5.0)  # a grid step: the azimuth spacing, more than any ring spacing
    boxes = []
    for k in np.unique(lab[lab >= 0]):
        inside = lab == k
        boxes.append([su[inside].min() - grow, su[inside].max() + grow, sv[inside].min() - grow, sv[inside].max() + grow,
                      val[inside].max()])
    holds_peak = [b[0] <= peak_uv[0] <= b[1] and b[2] <= peak_uv[1] <= b[3] for b in boxes]
    if not any(holds_peak):  # a lobe narrower than the grid: a part about the climbed peak
        boxes.append([peak_uv[0] - grow, peak_uv[0] + grow, peak_uv[1] - grow, peak_uv[1] + grow, peak])
    boxes.sort(key=lambda b: -b[4])
    return peak, level, [b[:4] for b in boxes]


def grid(box, n):
    """Sample centres of an n x n grid over a chart box (u0, u1, v0, v1), and the sample area."""
    u0, u1, v0, v1 = box
    du, dv = (u1 - u0) / n, (v1 - v0) / n
    u = u0 + du * (np.arange(n) + 0.5)
    v = v0 + dv * (np.arange(n) + 0.5)
    return np.meshgrid(u, v, indexing="xy") + [du * dv]


def aim(lobe, box, level):
    """A coarse AIM_SIZE^2 grid over the box; grows it until the region stays off its edges, then returns the
    region's box grown by 1.5 coarse samples (a sample is in by its centre; the frame moves by half of one)."""
    for _ in range(8):
        u, v, _a = grid(box, AIM_SIZE)
        inside = lobe.at(u, v) >= level
        if not inside.any():
            return None
        rows, cols = np.any(inside, axis=1), np.any(inside, axis=0)
        du, dv = (box[1] - box[0]) / AIM_SIZE, (box[3] - box[2]) / AIM_SIZE
        if rows[0] or rows[-1] or cols[0] or cols[-1]:  # on the edge: widen and look again
            cu, cv, hu, hv = 0.5 * (box[0] + box[1]), 0.5 * (box[2] + box[3]), box[1] - box[0], box[3] - box[2]
            box = [cu - hu, cu + hu, cv - hv, cv + hv]
            continue
        ui, vi = u[0, cols], v[rows, 0]
        return [ui.min() - 1.5 * du, ui.max() + 1.5 * du, vi.min() - 1.5 * dv, vi.max() + 1.5 * dv]
    return box


def measure(theta_deg, size=512):
    """One measurement at theta_i (deg): dict with aspect, major_deg, minor_deg, centroid_u_deg, parts."""
    lobe = Lobe(theta_deg)
    peak, level, survey_boxes = survey(lobe)
    frames = [b for b in (aim(lobe, box, level) for box in survey_boxes) if b is not None]
    m = np.zeros(6)  # area, Su, Sv, Suu, Suv, Svv
    for k, box in enumerate(frames):
        u, v, area = grid(box, size)
        keep = lobe.at(u, v) >= level
        for b in frames[:k]:  # counted in an earlier part's frame already
            keep &= ~((u >= b[0]) & (u <= b[1]) & (v >= b[2]) & (v <= b[3]))
        uk, vk = u[keep], v[keep]
        m += area * np.array([uk.size, uk.sum(), vk.sum(), (uk * uk).sum(), (uk * vk).sum(), (vk * vk).sum()])
    a, su, sv, suu, suv, svv = m
    cu, cv = su / a, sv / a
    cuu, cuv, cvv = suu / a - cu * cu, suv / a - cu * cv, svv / a - cv * cv
    tr, det = cuu + cvv, cuu * cvv - cuv * cuv
    disc = math.sqrt(max(0.0, 0.25 * tr * tr - det))
    lmax, lmin = 0.5 * tr + disc, max(0.0, 0.5 * tr - disc)
    return {"incidence_deg": float(theta_deg), "aspect": math.sqrt(lmin / lmax), "major_deg": math.degrees(2 * math.sqrt(lmax)),
            "minor_deg": math.degrees(2 * math.sqrt(lmin)), "centroid_u_deg": math.degrees(cu),
            "area_deg2": math.degrees(math.degrees(a)), "peak": float(peak), "parts": len(frames)}


def sweep(thetas, size=512):
    """measure() at each angle: a columnar dict {field: numpy array}."""
    rows = [measure(t, size) for t in thetas]
    return {k: np.array([r[k] for r in rows]) for k in rows[0]}


# glibc's malloc keeping freed memory: no fresh pages per 2 MB temporary (see the module's docstring).
MALLOC_KEEPS_MEMORY = {"MALLOC_MMAP_THRESHOLD_": "1000000000", "MALLOC_TRIM_THRESHOLD_": "1000000000"}


def sweep_seconds(extra_env=None):
    """sweep(0..85) in a fresh /usr/bin/python3 whose environment adds extra_env (malloc's settings are read
    at start-up), the sweep alone timed."""
    code = ("import sys, time; sys.path.insert(0, sys.argv[1]); import numpy as np, numpy_baseline as b; "
            "t = time.perf_counter(); b.sweep(np.arange(86.0)); print(time.perf_counter() - t)")
    here = os.path.dirname(os.path.abspath(__file__))
    out = subprocess.run(["/usr/bin/python3", "-c", code, here], check=True, capture_output=True, text=True,
                         env=dict(os.environ, **(extra_env or {}))).stdout
    return float(out.split()[-1])


def cli_rows(hilite, thetas):
    """hilite's rows for the same scene, by its CLI."""
    out = subprocess.run([hilite, "measure", "--model", "ggx", "--roughness", str(ALPHA), "--geometry", "smith",
                          "--fresnel", "schlick", "--f0", str(F0), "--size", "512",
                          "--incidence", ",".join(f"{t:g}" for t in thetas), "--json"],
                         check=True, capture_output=True, text=True).stdout
    return [json.loads(line) for line in out.splitlines() if line.strip()]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cli", default="build/bin/hilite", help="hilite executable to compare with")
    ap.add_argument("--size", type=int, default=512)
    args = ap.parse_args(argv)
    thetas = np.arange(86.0)
    t0 = time.perf_counter()
    mine = sweep(thetas, args.size)
    seconds = time.perf_counter() - t0
    rows = cli_rows(args.cli, thetas)
    diff = np.array([abs(r["aspect"] - a) for r, a in zip(rows, mine["aspect"])])
    for t, r, a, d, p in zip(thetas, rows, mine["aspect"], diff, mine["parts"]):
        print(f"{t:4.0f}  hilite {r['aspect']:.6f}  numpy {a:.6f}  |diff| {d:.2e}  parts {r['components']}/{p}")
    print(f"numpy sweep of {len(thetas)} angles: {seconds:.2f} s; max |aspect diff| {diff.max():.2e} "
          f"at {thetas[np.argmax(diff)]:g} deg")
    return 0 if diff.max() <= 2e-3 else 1


if __name__ == "__main__":
    sys.exit(main())
