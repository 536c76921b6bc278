"""hilite.brdf: the BRDF's physics in double precision on the CPU (the CLI's `hilite brdf`), on numpy arrays.

    hilite.brdf.fresnel([0, 45, 80], material="gold")            # (3, 3): F per angle, R G B
    hilite.brdf.albedo(np.arange(0, 90, 5.0), model="ggx", roughness=0.3, geometry="smith")
    hilite.brdf.normalization(model="beckmann", roughness=0.02)  # int D(h) (n.h) dw_h: 1 if normalized
    hilite.brdf.eval(wi, wo, model="ggx", roughness=0.2)         # f(wi, wo), (..., 3)
    hilite.brdf.bounces([0, 60], roughness=0.6, material="gold") # light per bounce order: columns

Keywords are the [material] parameters of the registry (model, roughness, fresnel, f0, eta, k, geometry,
diffuse, ...), checked as on the CLI; angles are degrees; directions are unit vectors in the local frame
(n = +z, the tangent x axis at tangent_angle 0).
"""

import numbers
import os

import numpy as np

from . import _hilite
from ._measure import columns
from ._params import REGISTRY, InputError, items_of, signature_doc

_MATERIAL = {p["name"] for p in REGISTRY if p["table"] == "material" and p["name"] not in ("brdf", "param")}


def _angles(theta_deg, name="theta_deg"):
    if isinstance(theta_deg, bool) or not (isinstance(theta_deg, (numbers.Real, list, tuple, range, np.ndarray))):
        raise TypeError(f"{name}: expected degrees (a number or an array), got {type(theta_deg).__name__}")
    a = np.asarray(theta_deg, dtype=np.float64)
    if a.size == 0:
        raise InputError(f"{name}: no angle given")
    return a


def _incidence_items(a):
    return [("incidence", ",".join(repr(float(t)) for t in a.ravel()), "theta_deg")]


def fresnel(theta_deg, *, spectral=False, **params):
    """F(theta) of the material's Fresnel term, R G B: shape theta_deg.shape + (3,). spectral=True: the
    measured spectra (copper, gold) integrated at 1 nm (CIE 1931, D65)."""
    if not isinstance(spectral, bool):
        raise TypeError(f"spectral: expected True or False, got {type(spectral).__name__}")
    a = _angles(theta_deg)
    out = _hilite.fresnel(items_of(params, _MATERIAL) + _incidence_items(a), spectral)
    return out.reshape(a.shape + (3,))


def albedo(theta_deg, *, azimuth=0.0, **params):
    """Directional-hemispherical reflectance rho(theta_i) = int f cos(theta_o) dw_o, R G B: shape
    theta_deg.shape + (3,); `azimuth` is the light's (degrees, anisotropic BRDFs)."""
    a = _angles(theta_deg)
    items = items_of(params, _MATERIAL) + items_of({"azimuth": azimuth}) + _incidence_items(a)
    return _hilite.albedo(items).reshape(a.shape + (3,))


def bihemispherical_albedo(**params):
    """(1/pi) int rho(wi) cos(theta_i) dwi, R G B: shape (3,)."""
    return _hilite.bihemispherical_albedo(items_of(params, _MATERIAL))[0]


def normalization(**params):
    """int D(h) (n.h) dw_h of the model's NDF (1 when D is normalized); roughness or exponent may be an
    array (a float64 array of the same shape comes back)."""
    for key in ("roughness", "exponent"):
        v = params.get(key)
        if isinstance(v, (list, tuple, np.ndarray)):
            a = np.asarray(v, dtype=np.float64)
            rest = {k: x for k, x in params.items() if k != key}
            flat = [normalization(**rest, **{key: float(x)}) for x in a.ravel()]
            return np.array(flat, dtype=np.float64).reshape(a.shape)
    return _hilite.normalization(items_of(params, _MATERIAL))


def eval(wi, wo, **params):  # noqa: A001 (the issue's name: hilite.brdf.eval)
    """f(wi, wo) = specular + diffuse, R G B, for unit directions in the local frame (n = +z): wi and wo are
    (..., 3) arrays broadcast together; returns (..., 3) float64. Zero where either is below the horizon.
    InputError for a direction that is not a finite unit vector."""
    a, b = np.asarray(wi, dtype=np.float64), np.asarray(wo, dtype=np.float64)
    if a.shape[-1:] != (3,) or b.shape[-1:] != (3,):
        raise InputError(f"eval: wi and wo must be (..., 3) arrays of directions (got {a.shape} and {b.shape})")
    try:
        shape = np.broadcast_shapes(a.shape, b.shape)
    except ValueError:
        raise InputError(f"eval: wi {a.shape} and wo {b.shape} do not broadcast together") from None
    a2 = np.ascontiguousarray(np.broadcast_to(a, shape).reshape(-1, 3))
    b2 = np.ascontiguousarray(np.broadcast_to(b, shape).reshape(-1, 3))
    return _hilite.eval(items_of(params, _MATERIAL), a2, b2).reshape(shape)


def slice(theta_deg, *, curves=None, step=0.5, **params):  # noqa: A001 (the CLI's name: hilite brdf slice)
    """f and f cos(theta_o) in the plane of incidence and across it (`hilite brdf slice`'s slice.csv): the
    keywords' BRDF, and each of `curves` (a dict of material keywords over them, or a (label, dict) pair)
    overlaid, at each incidence, every `step` degrees. Returns columns: curve, incidence_deg, plane ("in": angle
    = signed theta_o, + on the mirror side; "across": the angle from the mirror direction), angle_deg,
    theta_o_deg, wo_x, wo_y, wo_z, f_r, f_g, f_b, f (luminance), f_cos."""
    a = _angles(theta_deg)
    if isinstance(step, bool) or not isinstance(step, (numbers.Real, np.floating)):
        raise TypeError(f"step: expected a number, got {type(step).__name__}")
    base = {k: v for k, v in params.items() if v is not None}
    analytic = {k: v for k, v in base.items() if k != "measured"}
    allowed = _MATERIAL | {"azimuth"}
    todo = []
    # As the CLI: the keywords' model (unless only `measured` names a material), then the measured table.
    if "measured" not in base or set(analytic) - {"azimuth"}:
        label = str(analytic.get("model", "ggx")) + "".join(
            f" {k}={analytic[k]}" for k in ("roughness", "exponent", "roughness_y") if k in analytic)
        todo.append((label, items_of(analytic, allowed) + _incidence_items(a)))
    if "measured" in base:
        table = {k: v for k, v in base.items() if k in ("measured", "azimuth")}
        todo.append((f"measured {os.path.basename(str(base['measured']))}", items_of(table, allowed) +
                     _incidence_items(a)))
    for c in curves or []:
        name, over = c if isinstance(c, tuple) else (" ".join(f"{k}={v}" for k, v in c.items()), c)
        merged = dict(analytic)
        merged.update(over)
        todo.append((str(name), items_of(merged, allowed) + _incidence_items(a)))
    return columns(_hilite.slice(todo, float(step)))


_KEYWORDS = signature_doc(_MATERIAL)
for _f in (fresnel, albedo, bihemispherical_albedo, normalization, eval):
    _f.__doc__ += "\n    Keywords (from the parameter registry):\n" + _KEYWORDS + "\n"


def _whole(name, value, lowest=None):
    if isinstance(value, bool) or not isinstance(value, (numbers.Integral, np.integer)):
        raise TypeError(f"{name}: expected a whole number, got {type(value).__name__}")
    if lowest is not None and value < lowest:
        raise InputError(f"{name}: must be at least {lowest} (got {value})")
    return int(value)


def bounces(theta_deg, *, paths=100000, batches=16, seed=1, texels=1024, bumps_per_tile=64, surface="hermite",
            bump_seed=None, **params):
    """Light per bounce order on a rough Beckmann surface (`hilite brdf bounces --json`, docs/bounces.md): per
    incidence, traced on an explicit height field and walked on Smith's microsurface, beside E(mu) and
    Kulla-Conty. Returns columns (a dict of numpy arrays, one entry per angle): theta_deg and the [bounces]
    row's fields (traced_e1 .. traced_e5plus, traced_multiple, smith_* alike, kc_multiple, colours and C* per
    order, albedos, each estimate with its _err).
    The keywords paths, batches, seed, texels, bumps_per_tile and surface are the [bounces] table's; bump_seed
    is the field's; the rest are [material] parameters (model beckmann unless given; roughness,
    fresnel, material, eta, k, f0). The same settings give the CLI's numbers exactly."""
    a = _angles(theta_deg)
    # Types here; ranges in C++ (experiments::checkBounceSettings, as for an experiment's [bounces] keys).
    counts = [_whole("paths", paths), _whole("batches", batches), _whole("seed", seed, 0), _whole("texels", texels),
              _whole("bumps_per_tile", bumps_per_tile)]
    if not isinstance(surface, str):
        raise TypeError(f"surface: expected 'hermite' or 'bilinear', got {type(surface).__name__}")
    params.setdefault("model", "beckmann")
    items = items_of(params, _MATERIAL) + _incidence_items(a)
    if bump_seed is not None:
        items += items_of({"bump_seed": bump_seed})
    return columns(_hilite.bounces(items, *counts, surface))


bounces.__doc__ += "\n    Keywords (from the parameter registry):\n" + _KEYWORDS + "\n"
