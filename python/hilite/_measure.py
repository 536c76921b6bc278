"""hilite.measure and hilite.render: keywords -> scenes -> the library (hilite._hilite)."""

import os

import numpy as np

from . import _hilite
from ._params import PARAMS, InputError, is_sweep, items_of, lookup, scalar_text, signature_doc


def _scene_items(scene):
    from ._scene import Scene
    if scene is None:
        return []
    if isinstance(scene, Scene):
        return scene.items()
    if isinstance(scene, (str, os.PathLike)):
        return Scene.read(scene).items()
    raise TypeError(f"scene: expected a hilite.Scene or a scene file name, got {type(scene).__name__}")


def columns(rows):
    """Rows (dicts) as columns: {field: numpy array}, one entry per row in every column, in the order the
    fields first appear; pandas.DataFrame accepts it as is. Numbers are float64 (NaN where a row has null or
    lacks the field), whole numbers int64, booleans bool; strings, lists (flags) and objects (parts) are
    object arrays (None where a row lacks the field)."""
    keys = []
    seen = set()
    for r in rows:
        for k in r:
            if k not in seen:
                seen.add(k)
                keys.append(k)
    out = {}
    n = len(rows)
    for k in keys:
        vals = [r.get(k) for r in rows]
        present = [v for v in vals if v is not None]
        if present and all(isinstance(v, bool) for v in present) and len(present) == n:
            out[k] = np.array(vals, dtype=bool)
        elif present and all(isinstance(v, int) and not isinstance(v, bool) for v in present) and len(present) == n:
            out[k] = np.array(vals, dtype=np.int64)
        elif present and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in present):
            out[k] = np.array([np.nan if v is None else float(v) for v in vals], dtype=np.float64)
        else:
            a = np.empty(n, dtype=object)
            for i, v in enumerate(vals):
                a[i] = v
            out[k] = a
    return out


def _sweep_scenes(base, scalars, sweeps):
    """One scene per element of the broadcast of the swept keywords (row-major order)."""
    arrays = {}
    for name, v in sweeps.items():
        a = np.asarray(v) if not isinstance(v, range) else np.arange(v.start, v.stop, v.step)
        if a.size == 0:
            raise InputError(f"{name}: an empty array gives nothing to measure")
        arrays[name] = a
    try:
        shape = np.broadcast_shapes(*(a.shape for a in arrays.values()))
    except ValueError:
        raise InputError("the swept keywords' arrays do not broadcast together: " +
                         ", ".join(f"{k} {a.shape}" for k, a in arrays.items())) from None
    n = int(np.prod(shape, dtype=object)) if shape else 1  # exact: a float product could round a huge grid down
    if n > _hilite.max_scenes:  # refused before any scene is made, as `hilite run` refuses such an experiment
        raise InputError(f"the swept keywords give {n} scenes, more than {_hilite.max_scenes} "
                         "(sweep fewer values, or run an experiment in shards)")
    flat = {k: np.broadcast_to(a, shape).ravel() for k, a in arrays.items()}
    texts = {k: [scalar_text(PARAMS[k], e.item() if hasattr(e, "item") else e) for e in f] for k, f in flat.items()}
    if list(texts) == ["incidence"]:  # one scene, its angles a list: resolved once
        return [base + scalars + [("incidence", ",".join(texts["incidence"]), "")]]
    return [base + scalars + [(k, t[i], "") for k, t in texts.items()] for i in range(n)]


def measure(scene=None, **params):
    sweeps = {}
    scalars = {}
    for name, value in params.items():
        p = lookup(name)
        if value is not None and is_sweep(p, value):
            sweeps[name] = value
        else:
            scalars[name] = value
    base = _scene_items(scene)
    items = items_of(scalars)
    if not sweeps:
        rows = _hilite.measure([base + items])
        angles = [t for (n, t, _) in base + items if n == "incidence"]
        if len(rows) == 1 and not (angles and any(c in angles[-1] for c in ",:")):
            return rows[0]
        return columns(rows)
    return columns(_hilite.measure(_sweep_scenes(base, items, sweeps)))


def render(scene=None, *, maps=False, **params):
    if not isinstance(maps, bool):
        raise TypeError(f"maps: expected True or False, got {type(maps).__name__}")
    img, m = _hilite.render(_scene_items(scene) + items_of(params), maps)
    return (img, m) if maps else img


def fit(target=None, *, models=None, thresholds=None, weights=None, fit_anisotropy=None, fit_f0=None,
        fit_geometry=None, fit_fresnel=None, fit_diffuse=None, rank_by=None, fit_color=None, max_evaluations=None,
        scene=None, **params):
    """Fits analytic models to a target's BRDF and ranks them: the CLI's `hilite fit --json` in process.

    `target`: a MERL .binary table, an RGL .bsdf file or a BRDF Explorer .brdf file (str or os.PathLike), or
    None for a target given by the material keywords (model="ggx", roughness=0.1, ...); `scene` and the other
    keywords (light, camera, measurement: incidence defaults to "0:85:5", size to 256) apply to the target and
    every model. `models`, `thresholds`, `weights`, `fit_anisotropy`, `fit_f0`, `fit_geometry`, `fit_fresnel`,
    `fit_diffuse`, `rank_by`, `fit_color` and `max_evaluations` are the CLI's --models, --thresholds, ...; None
    takes the library's default, the CLI's (`hilite._hilite.fit_defaults()`). Returns one dict per model, ranked (rank 1
    first): model, params (by registry name), residual (by `rank_by`), shape_residual, values_residual, rank,
    rank_by, tie, verdict ("fits", "tie", "no_model_fits" or "target_unresolved"), resolution, tolerance, target,
    evaluations, value_evaluations, time_ms, stop, thresholds, weights, incidence_deg, aspect_threshold, target_aspect, aspect
    and aspect_residual (per angle; None where a sample has no shape). Raises InputError as the CLI refuses."""
    d = _hilite.fit_defaults()
    models = d["models"] if models is None else models
    thresholds = d["thresholds"] if thresholds is None else thresholds
    fit_anisotropy = d["fit_anisotropy"] if fit_anisotropy is None else fit_anisotropy
    fit_f0 = d["fit_f0"] if fit_f0 is None else fit_f0
    fit_color = d["fit_color"] if fit_color is None else fit_color
    max_evaluations = d["max_evaluations"] if max_evaluations is None else max_evaluations
    if target is not None:
        if not isinstance(target, (str, os.PathLike)):
            raise TypeError(f"target: expected a .binary or .brdf file name, got {type(target).__name__}")
        t = os.fspath(target)
        ext = os.path.splitext(t)[1]
        if ext not in (".binary", ".bsdf", ".brdf"):
            raise InputError(f"target: '{t}' must be a MERL .binary table, an RGL .bsdf file or a BRDF Explorer "
                             ".brdf file (or give the target by its material keywords)")
        key = "brdf" if ext == ".brdf" else "measured"
        if params.get(key) is not None:
            raise InputError(f"{key}: not with target (give one)")
        params = dict(params, **{key: t})
    for name, v in (("models", models), ("thresholds", thresholds)):
        if isinstance(v, (str, bytes)) or not hasattr(v, "__iter__"):
            raise TypeError(f"{name}: expected a list, got {type(v).__name__}")
    for name, v in (("fit_anisotropy", fit_anisotropy), ("fit_f0", fit_f0), ("fit_color", fit_color)):
        if not isinstance(v, bool):
            raise TypeError(f"{name}: expected True or False, got {type(v).__name__}")
    if isinstance(max_evaluations, bool) or not isinstance(max_evaluations, int) or not 1 <= max_evaluations <= 10000:
        raise InputError(f"max_evaluations: an integer in [1, 10000] (got {max_evaluations!r})")
    base = _scene_items(scene)
    items = items_of(params)
    given = {n for (n, _, _) in base + items}
    defaults = [(n, t, "") for n, t in (("incidence", "0:85:5"), ("size", "256")) if n not in given]
    return _hilite.fit(defaults + base + items, [str(m) for m in models], [float(x) for x in thresholds],
                       [] if weights is None else [float(x) for x in weights], fit_anisotropy, fit_f0,
                       d["fit_geometry"] if fit_geometry is None else str(fit_geometry),
                       d["fit_fresnel"] if fit_fresnel is None else str(fit_fresnel),
                       d["fit_diffuse"] if fit_diffuse is None else str(fit_diffuse),
                       d["rank_by"] if rank_by is None else str(rank_by), fit_color, max_evaluations)


_KEYWORDS = signature_doc()

measure.__doc__ = f"""Measures the highlight of a scene: the CLI's `hilite measure --json` in process.

    measure(scene=None, *, incidence=45, model='ggx', roughness=0.1, ..., reference=False, tolerance=None, ...)

`scene`: a hilite.Scene or a scene file (TOML); keywords override it. Returns one measurement as a dict
(the fields of the JSON row: aspect, eccentricity, major_deg, ..., flags, and every parameter as rendered)
when every keyword is one value; when a keyword is an array or list (incidence=np.arange(0, 86.0),
roughness=[0.05, 0.1]) or the incidence is a list or range ("0:85:5"), the measurements of every
combination (numpy broadcasting, row-major) as columns: a dict of numpy arrays, one per field, which
pandas.DataFrame accepts as is. Every scene is checked before the first is measured.

Raises InputError (a ValueError) with the CLI's message naming the keyword for a refused value (NaN, out of
range, unknown keyword, a parameter that does not apply), TypeError for a value of the wrong type,
MachineError (a RuntimeError) when GL fails. Nothing is written.

Keywords (from the parameter registry):
{_KEYWORDS}
"""

render.__doc__ = f"""Renders the scene's view: (H, W, 3) float32 numpy array of radiance, row 0 the top of the picture
(the CLI's `hilite render --float` PFM, which stores row 0 at the bottom, flipped).

    render(scene=None, *, maps=False, view='measure', size=512, ...)

With maps=True (view='measure' only), returns (image, maps), maps a dict of (H, W) float64 arrays of the same
render's pixels: 'u_deg', 'v_deg' (the chart coordinates about the mirror direction, notes/measurement.md),
'area_deg2' (each pixel's area in the (u, v) plane) and 'luminance' (the lobe value the measurement reads).
Takes one value per keyword (one angle). Errors as measure().

Keywords (from the parameter registry):
{_KEYWORDS}
"""
