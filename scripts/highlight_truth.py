#!/usr/bin/python3
"""Independent truth for hilite's highlight measurement (../shared/notes/measurement.md), numpy only.

Shares no code with hilite: the BRDF terms are written here from the papers (Walter et al. 2007, Heitz 2014,
Schlick 1994, Born & Wolf 1.5.2, Phong 1975 / Lewis 1994), in hilite's conventions (docs/terms.md), and the
region is found by exhaustive scan lines in the (u, v) chart: every crossing of L - T and of the horizon is
bisected to ~1e-15 rad, so each row is an exact set of intervals, whose moments 1, u, u^2 are integrated in
closed form; the rows are integrated over v by Gauss-Legendre between the v values where the topology of a
row changes (events, located by bisection), in t with v = mid - half cos t, which makes the sqrt behaviour
at tops, bottoms, merges and corners smooth. Parts: union-find on overlapping intervals. docs/truth.md.

Usage: highlight_truth.py            all cases -> tests/data/highlight_truth.csv, highlight_truth_parts.csv
       highlight_truth.py --only N   case N (0-based index, or a substring of its key string); print it
       highlight_truth.py --check    recompute 3 cheap cases and compare with the stored CSV (exit 1 if off)
"""
import argparse
import csv
import math
import os
import sys
import time

try:
    import numpy as np
except ImportError:   # ctest's SKIP_RETURN_CODE (tests/CMakeLists.txt): Debian's python3-numpy is not installed
    print("highlight_truth.py: numpy is missing (apt-get install python3-numpy): skipped")
    sys.exit(77)

DEG = math.pi / 180.0
INV_PI = 1.0 / math.pi

# ---------------------------------------------------------------- cases
def build_cases():
    c = []
    g01 = "model=ggx roughness=0.1"
    ss = "geometry=smith fresnel=schlick f0=0.04"
    # the reference table of notes/measurement.md
    for ti in (0, 30, 60, 75, 85):
        c.append(f"{g01} geometry=implicit fresnel=none incidence={ti} threshold=0.5")
    for ti in (0, 30, 60, 75, 85):
        c.append(f"model=phong exponent=1000 incidence={ti} threshold=0.5")
    c.append(f"{g01} geometry=smith fresnel=none incidence=45 threshold=0.5")
    # the sweep through the two-part range
    for ti in range(50, 76):
        c.append(f"{g01} {ss} incidence={ti} threshold=0.5")
    c.append(f"model=ggx roughness=0.2 {ss} incidence=45 threshold=0.5")
    c.append(f"{g01} {ss} incidence=72 threshold=0.3")
    c.append(f"model=ggx roughness=0.1 roughness-y=0.3 tangent-angle=30 {ss} incidence=60 threshold=0.5")
    c.append(f"model=ggx roughness=0.1 roughness-y=0.3 tangent-angle=30 {ss} incidence=60 azimuth=30 threshold=0.5")
    c.append(f"model=ggx roughness=0.3 roughness-y=0.1 tangent-angle=0 geometry=smith fresnel=none incidence=45 threshold=0.5")
    c.append(f"{g01} {ss} incidence=60 azimuth=37 threshold=0.5")
    for fr in (0.1, 0.3, 0.7, 0.9):
        c.append(f"{g01} {ss} incidence=45 threshold={fr}")
    c.append(f"{g01} {ss} incidence=60 threshold=0.1")
    for ti in (85, 89, 89.9):
        c.append(f"{g01} {ss} incidence={ti} threshold=0.5")
    for ti in (89, 89.9):
        c.append(f"{g01} geometry=implicit fresnel=none incidence={ti} threshold=0.5")
    for n in (1e4, 1e6):
        c.append(f"model=phong exponent={n:g} incidence=60 threshold=0.5")
        c.append(f"model=blinn exponent={n:g} {ss} incidence=60 threshold=0.5")
    c.append(f"model=blinn exponent=100 geometry=cook-torrance fresnel=schlick f0=0.04 incidence=60 threshold=0.5")
    c.append(f"model=blinn exponent=1000 geometry=implicit fresnel=none incidence=60 threshold=0.5")
    for r in (1e-3, 1e-5):
        c.append(f"model=ggx roughness={r:g} {ss} incidence=60 threshold=0.5")
    c.append(f"model=beckmann roughness=0.001 geometry=smith fresnel=dielectric eta=1.5 incidence=60 threshold=0.5")
    for r in (1, 2):
        c.append(f"model=ggx roughness={r} {ss} incidence=45 threshold=0.5")
    c.append(f"model=beckmann roughness=1 geometry=smith fresnel=schlick f0=0.04 incidence=45 threshold=0.5")
    c.append(f"model=beckmann roughness=0.1 geometry=implicit fresnel=none incidence=60 threshold=0.5")
    c.append(f"model=beckmann roughness=0.1 geometry=smith-separable fresnel=dielectric eta=1.5 incidence=60 threshold=0.5")
    c.append(f"model=beckmann roughness=0.1 geometry=cook-torrance fresnel=schlick f0=0.04 incidence=70 threshold=0.5")
    c.append(f"model=ggx roughness=0.1 geometry=cook-torrance fresnel=dielectric eta=1.5 incidence=60 threshold=0.5")
    c.append(f"model=ggx roughness=0.1 geometry=smith-separable fresnel=schlick f0=0.04 incidence=60 threshold=0.5")
    c.append(f"model=beckmann roughness=0.2 roughness-y=0.05 tangent-angle=45 geometry=smith-separable fresnel=dielectric eta=1.5 incidence=45 azimuth=30 threshold=0.5")
    c.append(f"model=ggx roughness=0.3 geometry=smith fresnel=dielectric eta=1.5 incidence=70 threshold=0.5")
    # unbounded at the horizon (G = 1 keeps 1 / cos(theta_o)): listed with components = 0, note 'unbounded'
    c.append(f"{g01} geometry=none fresnel=none incidence=60 threshold=0.5")
    c.append(f"model=beckmann roughness=0.1 geometry=none fresnel=schlick f0=0.04 incidence=30 threshold=0.5")
    return c


CHECK_CASES = ("model=phong exponent=1000 incidence=30 threshold=0.5",
               "model=ggx roughness=0.1 geometry=implicit fresnel=none incidence=60 threshold=0.5",
               "model=ggx roughness=0.1 geometry=smith fresnel=schlick f0=0.04 incidence=60 threshold=0.5")

KEYS = {"model", "roughness", "roughness-y", "tangent-angle", "exponent", "fresnel", "f0", "eta", "geometry",
        "incidence", "azimuth", "threshold"}


def parse_case(s):
    d = {}
    for tok in s.split():
        k, v = tok.split("=", 1)
        if k not in KEYS:
            raise ValueError(f"case '{s}': unknown key {k}")
        d[k] = v
    p = dict(model=d.get("model", "ggx"), roughness=float(d.get("roughness", 0.1)),
             exponent=float(d.get("exponent", 1000)), fresnel=d.get("fresnel", "none"),
             f0=float(d.get("f0", 0.04)), eta=float(d.get("eta", 1.5)), geometry=d.get("geometry", "implicit"),
             ti=float(d.get("incidence", 45)) * DEG, phi=float(d.get("azimuth", 0)) * DEG,
             tangent=float(d.get("tangent-angle", 0)) * DEG, frac=float(d.get("threshold", 0.5)))
    p["ry"] = float(d["roughness-y"]) if "roughness-y" in d else None
    return p


# ---------------------------------------------------------------- BRDF (from the literature)
def lambda_ggx(a2t2):
    # Heitz 2014 eq. 72: Lambda = (-1 + sqrt(1 + alpha^2 tan^2)) / 2
    return 0.5 * (np.sqrt(1.0 + a2t2) - 1.0)


def lambda_beckmann(a2t2):
    # Walter et al. 2007 rational fit in a = 1 / (m tan theta); hilite's convention (docs/terms.md)
    with np.errstate(divide="ignore", invalid="ignore"):
        a = 1.0 / np.sqrt(a2t2)
        lam = (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a)
    return np.where((a >= 1.6) | (a2t2 == 0), 0.0, lam)


class Brdf:
    """L(we) = f(wi, we) E cos(theta_i), E = 1, scalar (grey) Fresnel."""

    def __init__(self, p):
        self.p = p
        ti, ph = p["ti"], p["phi"]
        s, c, sp, cp = math.sin(ti), math.cos(ti), math.sin(ph), math.cos(ph)
        self.wi = np.array([s * cp, s * sp, c])
        self.wr = np.array([-s * cp, -s * sp, c])
        self.eu = np.array([c * cp, c * sp, s])   # in the plane of incidence, towards the normal
        self.ev = np.array([-sp, cp, 0.0])
        self.unbounded = p["model"] != "phong" and p["geometry"] == "none"

    def chart_dir(self, u, v):
        rho = np.hypot(u, v)
        with np.errstate(invalid="ignore", divide="ignore"):
            k = np.where(rho > 0, np.sin(rho) / np.where(rho > 0, rho, 1.0), 1.0)
        cr = np.cos(rho)
        return [cr * self.wr[i] + k * (u * self.eu[i] + v * self.ev[i]) for i in range(3)]

    def chart_coords(self, x, y, z):
        a = x * self.eu[0] + y * self.eu[1] + z * self.eu[2]
        b = x * self.ev[0] + y * self.ev[1]
        c = x * self.wr[0] + y * self.wr[1] + z * self.wr[2]
        s = np.hypot(a, b)
        rho = np.arctan2(s, c)
        with np.errstate(invalid="ignore", divide="ignore"):
            f = np.where(s > 0, rho / np.where(s > 0, s, 1.0), 1.0)
        return a * f, b * f

    def branch(self, u, v):
        """Cook-Torrance: 0 where G = 1, 1 where 2 NoH NoV / VoH, 2 where 2 NoH NoL / VoH is the min (the contour
        has a corner where it changes); 0 for every other model."""
        u = np.asarray(u, float)
        if self.p["model"] == "phong" or self.p["geometry"] != "cook-torrance" or u.size == 0:
            return np.zeros(u.shape, int)
        x, y, z = self.chart_dir(u, v)
        sx, sy, sz = x + self.wi[0], y + self.wi[1], z + self.wi[2]
        ln = np.sqrt(sx * sx + sy * sy + sz * sz)
        hz = sz / ln
        voh = (x * sx + y * sy + z * sz) / ln
        ci = self.wi[2]
        with np.errstate(all="ignore"):
            g = 2 * hz * np.minimum(z, ci) / voh
        return np.where(g >= 1, 0, np.where(z <= ci, 1, 2))

    def elev(self, u, v):
        x, y, z = self.chart_dir(u, v)
        return z

    def L_uv(self, u, v):
        x, y, z = self.chart_dir(u, v)
        rho = np.hypot(u, v)
        out = self.L_dir(x, y, z, rho)
        return np.where((z > 0) & (rho < math.pi), out, 0.0)

    def L_dir(self, x, y, z, rho=None):
        p = self.p
        ci = self.wi[2]
        with np.errstate(all="ignore"):
            if p["model"] == "phong":
                # Phong 1975, normalized (n+2)/(2 pi) (Lewis 1994): cos^n of the angle to wr
                if rho is None:
                    d2 = (x - self.wr[0]) ** 2 + (y - self.wr[1]) ** 2 + (z - self.wr[2]) ** 2
                    omc = 0.5 * d2
                else:
                    omc = 2.0 * np.sin(0.5 * rho) ** 2
                n = p["exponent"]
                val = (n + 2) * 0.5 * INV_PI * np.exp(n * np.log1p(-np.minimum(omc, 1.0)))
                val = np.where(omc < 1.0, val, 0.0)
                return val * ci
            sx, sy, sz = x + self.wi[0], y + self.wi[1], z + self.wi[2]
            ln = np.sqrt(sx * sx + sy * sy + sz * sz)
            hx, hy, hz = sx / ln, sy / ln, sz / ln
            sin2h = hx * hx + hy * hy
            voh = x * hx + y * hy + z * hz
            ct, st = math.cos(p["tangent"]), math.sin(p["tangent"])
            aniso = p["ry"] is not None and p["model"] in ("ggx", "beckmann")
            m = p["model"]
            if m == "ggx":
                if aniso:
                    ax, ay = p["roughness"], p["ry"]
                    tx = (hx * ct + hy * st) / ax
                    ty = (-hx * st + hy * ct) / ay
                    dd = tx * tx + ty * ty + hz * hz
                    D = 1.0 / (math.pi * ax * ay * dd * dd)   # Burley 2012 / Heitz 2014
                else:
                    a2 = p["roughness"] ** 2
                    dd = hz * hz * a2 + sin2h
                    D = a2 / (math.pi * dd * dd)   # Walter et al. 2007
            elif m == "beckmann":
                if aniso:
                    ax, ay = p["roughness"], p["ry"]
                    tx = (hx * ct + hy * st) / ax
                    ty = (-hx * st + hy * ct) / ay
                    D = np.exp(-(tx * tx + ty * ty) / (hz * hz)) / (math.pi * ax * ay * hz ** 4)
                else:
                    m2 = p["roughness"] ** 2
                    D = np.exp(-sin2h / (hz * hz * m2)) / (math.pi * m2 * hz ** 4)
            elif m == "blinn":
                n = p["exponent"]
                D = (n + 2) * 0.5 * INV_PI * np.exp(n * np.log1p(-sin2h / (1.0 + hz)))   # Blinn 1977
            else:
                raise ValueError(m)
            D = np.where(hz > 0, D, 0.0)
            fr = p["fresnel"]
            if fr == "none":
                F = 1.0
            elif fr == "schlick":
                F = p["f0"] + (1 - p["f0"]) * np.clip(1.0 - voh, 0, 1) ** 5
            elif fr == "dielectric":
                eta = p["eta"]
                c1 = np.clip(voh, 0, 1)
                s2t = (1 - c1 * c1) / (eta * eta)
                c2 = np.sqrt(np.maximum(0.0, 1 - s2t))
                rs = (c1 - eta * c2) / (c1 + eta * c2)
                rpp = (eta * c1 - c2) / (eta * c1 + c2)
                F = np.where(s2t >= 1, 1.0, 0.5 * (rs * rs + rpp * rpp))
            else:
                raise ValueError(fr)
            g = p["geometry"]
            if g == "implicit":
                val = D * F * 0.25
            elif g == "none":
                val = D * F / (4 * ci * z)
            elif g == "cook-torrance":
                G = np.minimum(1.0, 2 * hz * np.minimum(z, ci) / voh)
                val = D * F * G / (4 * ci * z)
            else:
                def a2t2(wx, wy, wz):
                    if m == "blinn":
                        mm = math.sqrt(2.0 / (p["exponent"] + 2.0))
                        return (wx * wx + wy * wy) * mm * mm / (wz * wz)
                    if aniso:
                        tx_ = wx * ct + wy * st
                        ty_ = -wx * st + wy * ct
                        return (tx_ ** 2 * p["roughness"] ** 2 + ty_ ** 2 * p["ry"] ** 2) / (wz * wz)
                    return (wx * wx + wy * wy) * p["roughness"] ** 2 / (wz * wz)
                lam = lambda_ggx if m == "ggx" else lambda_beckmann
                li = lam(a2t2(np.float64(self.wi[0]), np.float64(self.wi[1]), np.float64(self.wi[2])))
                lo = lam(a2t2(x, y, z))
                if g == "smith":
                    G = 1.0 / (1.0 + li + lo)   # Heitz 2014 eq. 99
                elif g == "smith-separable":
                    G = 1.0 / ((1.0 + li) * (1.0 + lo))   # Heitz 2014 eq. 98
                else:
                    raise ValueError(g)
                val = D * F * G / (4 * ci * z)
            return val * ci


# ---------------------------------------------------------------- the global peak
def nelder_mead(f, x0, scale, iters=400):
    pts = [np.array(x0, float), np.array(x0) + [scale, 0], np.array(x0) + [0, scale]]
    vals = [f(q) for q in pts]
    for _ in range(iters):
        order = np.argsort(vals)[::-1]   # maximize
        pts = [pts[i] for i in order]
        vals = [vals[i] for i in order]
        cen = 0.5 * (pts[0] + pts[1])
        xr = cen + (cen - pts[2]); fr = f(xr)
        if fr > vals[0]:
            xe = cen + 2 * (cen - pts[2]); fe = f(xe)
            pts[2], vals[2] = (xe, fe) if fe > fr else (xr, fr)
        elif fr > vals[1]:
            pts[2], vals[2] = xr, fr
        else:
            xc = cen + 0.5 * (pts[2] - cen); fc = f(xc)
            if fc > vals[2]:
                pts[2], vals[2] = xc, fc
            else:
                pts[1] = pts[0] + 0.5 * (pts[1] - pts[0]); vals[1] = f(pts[1])
                pts[2] = pts[0] + 0.5 * (pts[2] - pts[0]); vals[2] = f(pts[2])
        if max(np.abs(pts[1] - pts[0]).max(), np.abs(pts[2] - pts[0]).max()) < 1e-15 * (1 + abs(pts[0]).max()):
            break
    i = int(np.argmax(vals))
    return pts[i], vals[i]


def golden_max(f, a, b, iters=90):
    g = (math.sqrt(5) - 1) / 2
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(iters):
        if fc > fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a); fc = f(c)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a); fd = f(d)
    x = 0.5 * (a + b)
    return x, f(x)


HORIZON_E = 1e-10   # elevation (rad) of the horizon limit: L(e) = L(0+) + O(e)


def find_peak(B):
    """Global max of L over the visible hemisphere (sup: the horizon limit counts). Returns (peak, u, v, on_horizon,
    grid samples (u, v, L) for the bounding box)."""
    # chart polar grid about wr, rho geometric down to 1e-9 rad (tiny lobes), plus hemisphere grid graded to
    # the horizon, plus the horizon profile at elevation HORIZON_E
    rho = np.concatenate([[0.0], np.geomspace(1e-9, math.pi * 0.999999, 500)])
    psi = np.linspace(-math.pi, math.pi, 721)[:-1]
    R, P = np.meshgrid(rho, psi, indexing="ij")
    uA, vA = (R * np.cos(P)).ravel(), (R * np.sin(P)).ravel()
    LA = B.L_uv(uA, vA)
    el = np.concatenate([np.geomspace(1e-9, 0.3, 200), np.linspace(0.3, math.pi / 2, 200)[1:]])
    ph = np.linspace(-math.pi, math.pi, 1441)[:-1]
    E_, Ph = np.meshgrid(el, ph, indexing="ij")
    x, y, z = np.cos(E_) * np.cos(Ph), np.cos(E_) * np.sin(Ph), np.sin(E_)
    LB = B.L_dir(x.ravel(), y.ravel(), z.ravel())
    uB, vB = B.chart_coords(x.ravel(), y.ravel(), z.ravel())
    phH = np.linspace(-math.pi, math.pi, 16385)[:-1]
    eH = HORIZON_E

    def hor(phv):
        phv = np.asarray(phv, float)
        return B.L_dir(math.cos(eH) * np.cos(phv), math.cos(eH) * np.sin(phv), np.full_like(phv, math.sin(eH)))
    LH = hor(phH)
    u_all = np.concatenate([uA, uB]); v_all = np.concatenate([vA, vB]); L_all = np.concatenate([LA, LB])
    ok = np.isfinite(L_all)
    u_all, v_all, L_all = u_all[ok], v_all[ok], L_all[ok]
    # interior refinement from the best few grid points
    best = None
    order = np.argsort(L_all)[::-1]
    seeds = []
    for i in order[:200]:
        if all(math.hypot(u_all[i] - s[0], v_all[i] - s[1]) > 1e-3 for s in seeds):
            seeds.append((u_all[i], v_all[i]))
        if len(seeds) >= 3:
            break
    for su, sv in seeds:
        r0 = math.hypot(su, sv)
        scale = max(1e-9, 0.02 * r0, 1e-7)
        f = lambda q: float(B.L_uv(np.array([q[0]]), np.array([q[1]]))[0])
        for _ in range(3):
            q, val = nelder_mead(f, (su, sv), scale)
            su, sv = q
            scale *= 0.1
        if best is None or val > best[0]:
            best = (val, su, sv)
    # horizon sup
    ih = int(np.argmax(LH))
    d = phH[1] - phH[0]
    phb, Lh = golden_max(lambda t: float(hor(np.array([t]))[0]), phH[ih] - d, phH[ih] + d)
    on_h = Lh >= best[0]
    if not on_h:   # the interior search may have crept onto the horizon from above
        zb = B.elev(np.array([best[1]]), np.array([best[2]]))[0]
        on_h = zb < 1e-6
    if on_h:
        xh, yh, zh = math.cos(eH) * math.cos(phb), math.cos(eH) * math.sin(phb), math.sin(eH)
        uh, vh = B.chart_coords(np.array([xh]), np.array([yh]), np.array([zh]))
        peak = (max(Lh, best[0]), float(uh[0]), float(vh[0]))   # both are lower bounds of the sup
    else:
        peak = best
    xh, yh, zh = math.cos(eH) * np.cos(phH), math.cos(eH) * np.sin(phH), np.full_like(phH, math.sin(eH))
    uH, vH = B.chart_coords(xh, yh, zh)
    return peak[0], peak[1], peak[2], on_h, (np.concatenate([u_all, uH]), np.concatenate([v_all, vH]),
                                            np.concatenate([L_all, LH]), phH, LH, hor, [s_[1] for s_ in seeds])


def horizon_arc_rows(B, T, phH, LH, hor):
    """v of the chart points where the horizon limit crosses T (the corners of parts cut by the horizon), found by
    bisection in azimuth from every local maximum of the horizon profile, and v at those maxima: pilot rows there
    see every part that touches the horizon, however thin."""
    n = len(LH)
    d = phH[1] - phH[0]
    loc = np.nonzero((LH >= np.roll(LH, 1)) & (LH >= np.roll(LH, -1)) & (LH > 0.3 * T))[0]
    out = []
    eH = HORIZON_E
    f = lambda t: float(hor(np.array([t]))[0]) - T
    def chart_v(t):
        x, y, z = math.cos(eH) * math.cos(t), math.cos(eH) * math.sin(t), math.sin(eH)
        return float(B.chart_coords(np.array([x]), np.array([y]), np.array([z]))[1][0])
    for i in loc[:64]:
        t0, fm = golden_max(lambda t: f(t), phH[i] - d, phH[i] + d, 60)
        if fm < 0:
            continue
        out.append(chart_v(t0))
        for sgn in (-1, 1):
            k, t1 = 1, None
            while k < n:
                if LH[(i + sgn * k) % n] < T:
                    t1 = phH[i] + sgn * k * d
                    break
                k += 1
            if t1 is None:
                continue
            a, b = t0, t1   # f(a) >= 0 > f(b)
            for _ in range(60):
                m = 0.5 * (a + b)
                if f(m) >= 0:
                    a = m
                else:
                    b = m
            out.append(chart_v(a))
    return out


# ---------------------------------------------------------------- scan lines
class Rows:
    def __init__(self, B, T, ubox, S):
        self.B, self.T, self.u0, self.u1, self.S = B, T, ubox[0], ubox[1], S

    def g(self, u, v):
        return self.B.L_uv(u, v) - self.T

    def solve(self, vs, focus=None):
        """Intervals of {L >= T} on rows v (1-D array). focus: per row a list of (a, b) to sample densely.
        Returns per row a list of [a, b, a_is_horizon, b_is_horizon, a_at_box, b_at_box]."""
        out = []
        CH = max(1, 400000 // (self.S + 400))
        for c0 in range(0, len(vs), CH):
            out += self._solve(vs[c0:c0 + CH], None if focus is None else focus[c0:c0 + CH])
        return out

    def _solve(self, vs, focus):
        B, S = self.B, self.S
        R = len(vs)
        V = vs[:, None]
        us = np.linspace(self.u0, self.u1, S)[None, :].repeat(R, 0)
        # horizon crossings along each row: sign changes of we.z, bisected; graded samples on both sides
        z = B.elev(us, V + 0 * us)
        vis = z > 0
        ch = np.nonzero(vis[:, 1:] != vis[:, :-1])
        extra = []
        if len(ch[0]):
            rr, kk = ch
            lo, hi = us[rr, kk].copy(), us[rr, kk + 1].copy()
            vlo = vis[rr, kk]
            for _ in range(70):
                mid = 0.5 * (lo + hi)
                vm = B.elev(mid, vs[rr]) > 0
                same = vm == vlo
                lo = np.where(same, mid, lo); hi = np.where(same, hi, mid)
                if np.all(hi - lo <= 4e-16 * (1 + np.abs(lo))):
                    break
            uh = 0.5 * (lo + hi)
            du = (self.u1 - self.u0) / (S - 1)
            off = du * np.geomspace(1e-13, 1.0, 60)
            off = np.concatenate([-off, off])
            # at most 4 crossings per row kept
            cnt = np.zeros(R, int)
            slots = np.full((R, 4), np.nan)
            for r_, u_ in zip(rr, uh):
                if cnt[r_] < 4:
                    slots[r_, cnt[r_]] = u_
                    cnt[r_] += 1
            for j in range(4):
                col = slots[:, j]
                fill = np.where(np.isnan(col), self.u0, col)
                extra.append(np.clip(fill[:, None] + off[None, :], self.u0, self.u1))
        if focus is not None:
            for j in range(6):
                ab = np.array([f[j % len(f)] if len(f) else (self.u0, self.u0) for f in focus])
                a, b = ab[:, 0], ab[:, 1]
                w = np.maximum(b - a, 1e-300)
                t = np.linspace(-0.6, 1.6, 120)
                extra.append(np.clip(a[:, None] + w[:, None] * t[None, :], self.u0, self.u1))
        if extra:
            us = np.sort(np.concatenate([us] + extra, axis=1), axis=1)
        Vb = V + 0 * us
        gv = self.g(us, Vb)
        ins = gv >= 0
        ch = np.nonzero(ins[:, 1:] != ins[:, :-1])
        rr, kk = ch
        lo, hi = us[rr, kk].copy(), us[rr, kk + 1].copy()
        ilo = ins[rr, kk]
        vr = vs[rr]
        for _ in range(64):
            mid = 0.5 * (lo + hi)
            im = self.g(mid, vr) >= 0
            same = im == ilo
            lo = np.where(same, mid, lo); hi = np.where(same, hi, mid)
            if np.all(hi - lo <= 4e-16 * (1 + np.abs(lo))):
                break
        xc = 0.5 * (lo + hi)
        outside = np.where(ilo, hi, lo)
        hor = B.elev(outside, vr) <= 0
        brn = B.branch(xc, vr)   # which term of a min() is active at the boundary point (its corners: events)
        res = [[] for _ in range(R)]
        # rows starting inside at the box edge
        first_in = ins[:, 0]
        last_in = ins[:, -1]
        cur = [None] * R
        for r in range(R):
            if first_in[r]:
                cur[r] = [self.u0, False, True, -1]
        for r, x, h, il, bb in zip(rr, xc, hor, ilo, brn):
            if not il:   # entering
                cur[r] = [x, bool(h), False, int(bb)]
            else:
                a = cur[r]
                res[r].append([a[0], x, a[1], bool(h), a[2], False, a[3], int(bb)])
                cur[r] = None
        for r in range(R):
            if last_in[r] and cur[r] is not None:
                a = cur[r]
                res[r].append([a[0], self.u1, a[1], False, a[2], True, a[3], -1])
        return [clean_row(x) for x in res]


HORIZON_GAP = 1e-11   # rad: the rounding of we.z (~1e-16) flips the sign of L - T within ~1e-14 of the horizon


def clean_row(ivs):
    # merge intervals split by a horizon-rounding gap, then drop zero-width horizon-horizon slivers
    out = []
    for it in ivs:
        if out and it[0] - out[-1][1] < HORIZON_GAP and (out[-1][3] or it[2]):
            out[-1][1], out[-1][3], out[-1][5], out[-1][7] = it[1], it[3], it[5], it[7]
            out[-1][2] = out[-1][2] or it[2] and out[-1][1] - out[-1][0] < HORIZON_GAP
        else:
            out.append(list(it))
    return [it for it in out if not (it[1] - it[0] < HORIZON_GAP and it[2] and it[3])]


def signature(ivs):
    return tuple((i[2], i[3], i[6], i[7]) for i in ivs)


def moments_of_row(ivs, v):
    m = np.zeros(6)
    for a, b, *_ in ivs:
        m0, m1, m2 = b - a, 0.5 * (b * b - a * a), (b ** 3 - a ** 3) / 3.0
        m += [m0, m1, v * m0, m2, v * m1, v * v * m0]
    return m


def shape(m):
    A = m[0]
    if A <= 0:
        return None
    cu, cv = m[1] / A, m[2] / A
    Cuu, Cuv, Cvv = m[3] / A - cu * cu, m[4] / A - cu * cv, m[5] / A - cv * cv
    tr, det = Cuu + Cvv, Cuu * Cvv - Cuv * Cuv
    disc = math.sqrt(max(0.0, 0.25 * (Cuu - Cvv) ** 2 + Cuv * Cuv))
    lmax, lmin = 0.5 * tr + disc, max(0.0, 0.5 * tr - disc)
    if lmin > 0 and lmax > 0:
        lmin = det / lmax if det > 0 else lmin   # the small eigenvalue without cancellation
    ori = 0.5 * math.degrees(math.atan2(2 * Cuv, Cuu - Cvv))
    if ori <= -90 + 1e-9:
        ori += 180
    return dict(aspect=math.sqrt(lmin / lmax), eccentricity=math.sqrt(max(0.0, 1 - lmin / lmax)),
                major_deg=2 * math.sqrt(lmax) / DEG, minor_deg=2 * math.sqrt(lmin) / DEG, orientation_deg=ori,
                centroid_u_deg=cu / DEG, centroid_v_deg=cv / DEG, area_deg2=A / DEG ** 2)


class UF:
    def __init__(self):
        self.p = {}

    def find(self, x):
        self.p.setdefault(x, x)
        while self.p[x] != x:
            self.p[x] = self.p[self.p[x]]
            x = self.p[x]
        return x

    def union(self, a, b):
        self.p[self.find(a)] = self.find(b)


def measure_region(B, T, samples, res):
    """res: resolution level (1 = default, 0.5 = half). Returns totals, parts, flags."""
    uS, vS, LS, phH, LH, hor, seed_v = samples
    inr = LS >= T
    uin, vin = uS[inr], vS[inr]
    su, sv = uin.max() - uin.min(), vin.max() - vin.min()
    mgu = 0.25 * su + 0.02 * sv + 1e-9
    mgv = 0.25 * sv + 0.02 * su + 1e-9
    ubox = (max(-math.pi, uin.min() - mgu), min(math.pi, uin.max() + mgu))
    vbox = (max(-math.pi, vin.min() - mgv), min(math.pi, vin.max() + mgv))
    S = int(2400 * res)
    rows = Rows(B, T, ubox, S)
    NP = int(500 * res)
    vp = np.linspace(vbox[0], vbox[1], NP)
    # pilot rows also through every local maximum (interior seeds) and at every horizon corner +- a little
    special = list(seed_v)
    eps = 1e-7 * (vbox[1] - vbox[0])
    for vc in horizon_arc_rows(B, T, phH, LH, hor):
        special += [vc - eps, vc, vc + eps]
    special = [x for x in special if vbox[0] < x < vbox[1]]
    vp = np.unique(np.concatenate([vp, special]))
    NP = len(vp)
    ivp = rows.solve(vp)
    sig = [signature(r) for r in ivp]
    flags = set()
    if sig[0] or sig[-1]:
        flags.add("clipped_v")
    # events: bisect between neighbouring pilot rows of different signature (focus samples follow the intervals)
    pend = [j for j in range(NP - 1) if sig[j] != sig[j + 1]]
    lo = np.array([vp[j] for j in pend]); hi = np.array([vp[j + 1] for j in pend])
    slo = [sig[j] for j in pend]
    flo = [ivp[j] for j in pend]; fhi = [ivp[j + 1] for j in pend]
    for _ in range(47 if res >= 1 else 44):
        if len(pend) == 0:
            break
        mid = 0.5 * (lo + hi)
        foc = [[(i[0], i[1]) for i in (a + b)][:6] for a, b in zip(flo, fhi)]
        ivm = rows.solve(mid, foc)
        for e in range(len(pend)):
            if signature(ivm[e]) == slo[e]:
                lo[e] = mid[e]; flo[e] = ivm[e]
            else:
                hi[e] = mid[e]; fhi[e] = ivm[e]
    events = sorted(0.5 * (lo + hi)) if len(pend) else []
    cuts = [vbox[0]] + list(events) + [vbox[1]]
    # quadrature per sub-interval
    # composite Gauss-Legendre in t (v = mid - half cos t), panels graded geometrically towards both ends: the
    # substitution makes a sqrt end smooth, the grading also takes nearly degenerate (flat) tops and merges
    K, m_ = (11, 10) if res >= 1 else (8, 7)
    br = [0.5 * math.pi * 2.0 ** -k for k in range(K, -1, -1)]
    br = [0.0] + br + [math.pi - x for x in br[::-1][1:]] + [math.pi]
    gx, gw = np.polynomial.legendre.leggauss(m_)
    t = np.concatenate([0.5 * (b_ - a_) * gx + 0.5 * (a_ + b_) for a_, b_ in zip(br[:-1], br[1:])])
    w = np.concatenate([0.5 * (b_ - a_) * gw for a_, b_ in zip(br[:-1], br[1:])])
    n = len(t)
    uf = UF()
    missed_bound = 0.0
    nodes = []   # per sub-interval: (rows v, weights, intervals)
    for j in range(len(cuts) - 1):
        a, b = cuts[j], cuts[j + 1]
        if b - a <= 0:
            continue
        mid_, half = 0.5 * (a + b), 0.5 * (b - a)
        vq = mid_ - half * np.cos(t)
        wq = w * half * np.sin(t)
        iv = rows.solve(vq)
        # rows next to a top or bottom may miss their (tiny) interval in the uniform samples: solve them again
        # with dense samples about the intervals of the neighbouring row towards the middle, outwards
        counts = [len(r) for r in iv]
        k = max(set(counts), key=counts.count)
        for _ in range(12):
            bad = [r for r in range(n) if len(iv[r]) != k]
            if not bad:
                break
            nb = [r + 1 if r < n // 2 else r - 1 for r in bad]
            foc = [[(q[0], q[1]) for q in iv[m]][:6] for m in nb]
            again = rows.solve(vq[bad], foc)
            changed = False
            for r, x in zip(bad, again):
                if abs(len(x) - k) < abs(len(iv[r]) - k):
                    iv[r] = x
                    changed = True
            if not changed:
                break
        # what rows still short of intervals can have missed: at most their neighbour's widest interval
        for r in range(n):
            if len(iv[r]) < k:
                m = r + 1 if r < n // 2 else r - 1
                missed_bound += wq[r] * max([q[1] - q[0] for q in iv[m]] + [0.0])
        nodes.append((j, vq, wq, iv))
    total = np.zeros(6)
    parts = {}
    mismatch = 0
    prev = None
    for j, vq, wq, iv in nodes:
        counts = [len(r) for r in iv]
        k = max(set(counts), key=counts.count)
        ref = iv[counts.index(k)]
        for r, (vv, ww) in enumerate(zip(vq, wq)):
            row = iv[r]
            if len(row) != k:
                mismatch += 1
            for it in row:
                if it[4] or it[5]:
                    flags.add("clipped_u")
                if it[2] or it[3]:
                    flags.add("horizon_cuts")
                if len(row) == k:
                    idx = row.index(it)
                else:
                    c = 0.5 * (it[0] + it[1])
                    idx = int(np.argmin([abs(0.5 * (q[0] + q[1]) - c) for q in ref])) if ref else 0
                mm = moments_of_row([it], vv) * ww
                total += mm
                key = (j, idx)
                uf.find(key)
                parts[key] = parts.get(key, 0) + mm
        # link with the previous sub-interval across their shared event (first row here, last row there)
        if prev is not None and prev[0] == j - 1 and k:
            # the rows nearest the shared event that hold all their sub-range's intervals
            pk_ = max(set(len(r) for r in prev[3]), key=[len(r) for r in prev[3]].count)
            last = next((r for r in prev[3][::-1] if len(r) == pk_), prev[3][-1])
            first = next((r for r in iv if len(r) == k), iv[0])
            for i1, a1 in enumerate(last):
                for i2, a2 in enumerate(first):
                    if a1[0] <= a2[1] and a2[0] <= a1[1]:
                        uf.union((j - 1, i1), (j, i2))
        prev = (j, vq, wq, iv)
    comp = {}
    for key, mm in parts.items():
        r = uf.find(key)
        comp[r] = comp.get(r, 0) + mm
    if total[0] > 0 and missed_bound / total[0] > 1e-9:
        flags.add(f"missed_area_rel<{missed_bound / total[0]:.1g}")
    plist = sorted(comp.values(), key=lambda m: -m[0])
    return total, plist, flags, len(events)


def run_case(key, res=1.0, pk=None):
    p = parse_case(key)
    B = Brdf(p)
    if B.unbounded:
        return dict(note="unbounded", components=0)
    peak, pu, pv, on_h, samples = pk if pk is not None else find_peak(B)
    T = p["frac"] * peak
    total, plist, flags, nev = measure_region(B, T, samples, res)
    r = dict(peak=peak, peak_u_deg=pu / DEG, peak_v_deg=pv / DEG, components=len(plist))
    r.update(shape(total))
    if on_h:
        flags.add("peak_on_horizon")
    r["note"] = " ".join(sorted(flags))
    r["events"] = nev
    r["parts"] = [shape(m) for m in plist]
    r["_peak"] = (peak, pu, pv, on_h, samples)
    return r


FIELDS = ["peak", "peak_u_deg", "peak_v_deg", "components", "aspect", "eccentricity", "major_deg", "minor_deg",
          "orientation_deg", "centroid_u_deg", "centroid_v_deg", "area_deg2"]
PFIELDS = ["aspect", "eccentricity", "major_deg", "minor_deg", "orientation_deg", "centroid_u_deg",
           "centroid_v_deg", "area_deg2"]


def full_case(key):
    r = run_case(key, 1.0)
    if r.get("note") == "unbounded":
        r["error_estimate"] = ""
        return r
    h = run_case(key, 0.5, r["_peak"])
    r["error_estimate"] = abs(r["aspect"] - h["aspect"])
    r["error_estimate_major_deg"] = abs(r["major_deg"] - h["major_deg"])
    r["error_estimate_area_rel"] = abs(r["area_deg2"] - h["area_deg2"]) / r["area_deg2"]
    if h["components"] != r["components"]:
        r["note"] = (r["note"] + " components_differ_at_half_resolution").strip()
    return r


def fmt(x):
    if isinstance(x, str):
        return x
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    return f"{x:.12g}"


def root():
    return os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _row(f, cells):
    # the case key is always quoted (it holds spaces and '='), the rest only where CSV needs it
    import io
    buf = io.StringIO()
    csv.writer(buf, lineterminator="").writerow(cells[1:])
    f.write('"' + cells[0].replace('"', '""') + '",' + buf.getvalue() + "\n")


def write(results, path, ppath):
    with open(path, "w", newline="") as f:
        _row(f, ["case"] + FIELDS + ["error_estimate", "error_estimate_area_rel", "note"])
        for key, r in results:
            _row(f, [key] + [fmt(r.get(k, "")) for k in FIELDS] +
                 [fmt(r.get("error_estimate", "")), fmt(r.get("error_estimate_area_rel", "")), r.get("note", "")])
    with open(ppath, "w", newline="") as f:
        _row(f, ["case", "part"] + PFIELDS)
        for key, r in results:
            for i, pr in enumerate(r.get("parts", [])):
                _row(f, [key, str(i)] + [fmt(pr[k]) for k in PFIELDS])


def hilite_args(key):
    args = []
    for tok in key.split():
        k, v = tok.split("=", 1)
        args += ["--" + k, v]
    return args


def compare(exe, path):
    """Markdown table: truth vs hilite measure --reference and GL (the default renderer)."""
    import json
    import subprocess
    with open(path) as f:
        rows = list(csv.DictReader(f))
    print("| case | truth aspect | parts | reference aspect | reference flags | GL aspect | GL flags | disagrees |")
    print("|---|---|---|---|---|---|---|---|")
    for row in rows:
        got = []
        for extra in (["--reference"], []):
            try:
                pr = subprocess.run([exe, "measure", "--json"] + extra + hilite_args(row["case"]),
                                    capture_output=True, text=True, timeout=120)
            except subprocess.TimeoutExpired:
                got.append((None, "timeout 120 s"))
                continue
            try:
                j = json.loads(pr.stdout.strip().splitlines()[-1])
                got.append((j.get("aspect"), ",".join(j.get("flags", [])) or "-"))
            except (ValueError, IndexError):
                got.append((None, f"exit {pr.returncode}: " + (pr.stderr.strip().splitlines() or [""])[-1][:60]))
        ta = float(row["aspect"]) if row["aspect"] else None
        bad = []
        for name, (asp, fl), tol in (("reference", got[0], 1e-5), ("GL", got[1], 1e-3)):
            if ta is None:
                continue
            if asp is None or abs(asp - ta) > tol:
                bad.append(name)
        fa = lambda x: "-" if x is None else f"{x:.6f}"
        print(f"| `{row['case']}` | {fa(ta)} | {row['components']} | {fa(got[0][0])} | {got[0][1]} | "
              f"{fa(got[1][0])} | {got[1][1]} | {' '.join(bad) or '-'} |", flush=True)
    return 0


def update(sel, path):
    """Recompute the cases sel and replace their rows in path and its _parts file (the case order of build_cases)."""
    import tempfile
    ppath = path.replace(".csv", "_parts.csv")
    res = []
    for key in sel:
        t0 = time.time()
        res.append((key, full_case(key)))
        print(f"{time.time() - t0:5.1f} s  {key}: aspect {fmt(res[-1][1].get('aspect', ''))}", flush=True)
    with tempfile.TemporaryDirectory() as d:
        tp = os.path.join(d, "t.csv")
        write(res, tp, tp.replace(".csv", "_parts.csv"))
        for old, new in ((path, tp), (ppath, tp.replace(".csv", "_parts.csv"))):
            keep = [r for r in csv.reader(open(old)) if r[0] not in sel]
            add = list(csv.reader(open(new)))[1:]
            order = {k: i for i, k in enumerate(build_cases())}
            body = sorted(keep[1:] + add, key=lambda r: (order.get(r[0], 1 << 30), r[1] if "parts" in old else ""))
            with open(old, "w", newline="") as f:
                for r in [keep[0]] + body:
                    _row(f, r)
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--only", help="one case: index or substring of its key")
    ap.add_argument("--check", action="store_true", help="recompute 3 cheap cases, compare with the stored CSV")
    ap.add_argument("--out", default=os.path.join(root(), "tests", "data", "highlight_truth.csv"))
    ap.add_argument("--update", action="store_true", help="with --only: recompute those cases and replace their "
                    "rows in both stored CSVs")
    ap.add_argument("--compare", metavar="HILITE", help="run HILITE measure --json (GL and --reference) on every "
                    "stored case and print a markdown table of the aspects (disagreements marked)")
    a = ap.parse_args()
    cases = build_cases()
    if a.compare:
        return compare(a.compare, a.out)
    if a.check:
        stored = {}
        with open(a.out) as f:
            for row in csv.DictReader(f):
                stored[row["case"]] = row
        bad = 0
        for key in CHECK_CASES:
            r = run_case(key, 1.0)
            s = stored.get(key)
            if s is None:
                print(f"missing in {a.out}: {key}"); bad += 1; continue
            for k in ("aspect", "major_deg", "minor_deg", "centroid_u_deg", "area_deg2", "components"):
                d = abs(float(r[k]) - float(s[k]))
                tol = 1e-9 * max(1.0, abs(float(s[k])))
                ok = d <= tol
                bad += not ok
                print(f"{'ok ' if ok else 'BAD'} {key} {k}: {fmt(r[k])} stored {s[k]} (|d| = {d:.2g})")
        return 1 if bad else 0
    if a.only is not None:
        sel = [cases[int(a.only)]] if a.only.isdigit() else [c for c in cases if a.only in c]
        if a.update:
            return update(sel, a.out)
        for key in sel:
            t0 = time.time()
            r = full_case(key)
            print(key)
            for k in FIELDS + ["error_estimate", "error_estimate_area_rel", "note", "events"]:
                print(f"  {k} = {fmt(r.get(k, ''))}")
            for i, pr in enumerate(r.get("parts", [])):
                print(f"  part {i}: " + " ".join(f"{k}={fmt(pr[k])}" for k in PFIELDS))
            print(f"  ({time.time() - t0:.1f} s)")
        return 0
    results = []
    t0 = time.time()
    for i, key in enumerate(cases):
        t1 = time.time()
        r = full_case(key)
        results.append((key, r))
        print(f"[{i + 1}/{len(cases)}] {time.time() - t1:5.1f} s  {key}: aspect {fmt(r.get('aspect', ''))} "
              f"components {r.get('components')} err {fmt(r.get('error_estimate', ''))} {r.get('note', '')}",
              flush=True)
    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    write(results, a.out, a.out.replace(".csv", "_parts.csv"))
    print(f"wrote {a.out} ({time.time() - t0:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
