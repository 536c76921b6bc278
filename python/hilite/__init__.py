"""hilite: what shape is a specular highlight, and which BRDF gets it right? In-process, from Python.

    >>> import hilite, numpy as np
    >>> hilite.measure(model="ggx", roughness=0.1, incidence=60)["aspect"]        # one measurement: a dict
    >>> cols = hilite.measure(model="ggx", incidence=np.arange(0, 86.0))          # arrays: columns
    >>> import pandas; pandas.DataFrame(cols)
    >>> img = hilite.render(model="ggx", incidence=60, view="photo")              # (H, W, 3) float32
    >>> hilite.fit("gold-metallic-paint.binary")                                   # which model fits: ranked

Every scene and measurement parameter of the CLI is a keyword (its scene-file key: ``roughness_y`` is
``--roughness-y``), read and checked by the same code as the CLI's flags: a refused value raises
:class:`InputError` (a ValueError) with the CLI's one-line message naming the keyword; a value of the
wrong Python type raises TypeError. ``help(hilite.measure)`` lists every keyword with its range, default
and help, from the parameter registry.

Threading: the module owns one GL context, made on the first call that renders, on a thread of its own;
every call runs there, one at a time, in the order the calls arrive. Call from any thread; the GIL is
released while hilite works, so other Python threads run meanwhile. The context's backend is fixed by
the first GL call (gl_backend=, else $HILITE_GL_BACKEND, else auto).
"""

import os as _os

_here = _os.path.dirname(_os.path.abspath(__file__))
# In the build tree (<build>/python/hilite) the shaders, data and the probe helper hilite-probe (which runs a
# .brdf shader's probe) are <build>/share/hilite and <build>/bin/hilite-probe; installed (pip or cmake), the
# package carries them (share/, libexec/) and the module finds them beside itself.
_build_share = _os.path.join(_here, "..", "..", "share", "hilite")
if ("HILITE_SHARE_DIR" not in _os.environ and not _os.path.isdir(_os.path.join(_here, "share"))
        and _os.path.isdir(_os.path.join(_build_share, "shaders"))):
    _os.environ["HILITE_SHARE_DIR"] = _os.path.normpath(_build_share)

from . import _hilite  # noqa: E402
from ._params import InputError, REGISTRY, PARAMS  # noqa: E402,F401
from ._measure import measure, render, columns, fit  # noqa: E402,F401
from ._scene import Scene  # noqa: E402,F401
from . import brdf  # noqa: E402,F401

MachineError = _hilite.MachineError
__version__ = _hilite.version

_build_probe = _os.path.join(_here, "..", "..", "bin", "hilite-probe")
if not _os.path.isdir(_os.path.join(_here, "libexec")) and _os.path.isfile(_build_probe):
    _hilite.set_probe_executable(_os.path.normpath(_build_probe))


def run(experiment, out=None, *, resume=False, shard=None, gl_backend=None, fsync_each_row=False, client=None,
        chunk_size=None):
    """Runs an experiment file (or one shipped in experiments/, by name) into the folder `out`
    (default results/<name>), as ``hilite run`` does: every configuration is checked and every .brdf probed
    before anything is written; the folder is locked while it is written; ``resume=True`` keeps the rows of
    the same experiment already there. ``shard="K/N"`` runs configurations i with i mod N = K - 1.
    Rows are made durable together, at most every 100 ms and at the end; ``fsync_each_row=True`` after each.
    ``client=`` a ``dask.distributed.Client``: the configurations are measured on its workers (each in process,
    with its own GL context), ``chunk_size`` at a time (default: about four chunks per worker, at most 256),
    and their rows written here into `out` as they come back; the folder ends as a single run's, row for row.
    Workers read the experiment and its data files at this process's paths (on several machines: a shared
    file system). Returns {name, dir, configurations, measured, seconds, finalized}."""
    for name, v in (("experiment", experiment), ("out", out)):
        if v is not None and not isinstance(v, (str, _os.PathLike)):
            raise TypeError(f"{name}: expected a file or folder name (str or os.PathLike), got {type(v).__name__}")
    if not isinstance(resume, bool):
        raise TypeError(f"resume: expected True or False, got {type(resume).__name__}")
    if shard is not None and not isinstance(shard, str):
        raise TypeError(f"shard: expected 'K/N', got {type(shard).__name__}")
    if gl_backend is not None and not isinstance(gl_backend, str):
        raise TypeError(f"gl_backend: expected 'auto', 'osmesa', 'egl' or 'egl-device', got {type(gl_backend).__name__}")
    if not isinstance(fsync_each_row, bool):
        raise TypeError(f"fsync_each_row: expected True or False, got {type(fsync_each_row).__name__}")
    if chunk_size is not None and (isinstance(chunk_size, bool) or not isinstance(chunk_size, int)):
        raise TypeError(f"chunk_size: expected a whole number of configurations, got {type(chunk_size).__name__}")
    if chunk_size is not None and not 1 <= chunk_size <= 1000000:
        raise InputError(f"chunk_size: expected 1 to 1000000 configurations a task (got {chunk_size})")
    if chunk_size is not None and client is None:
        raise InputError("chunk_size: only with client= (a Dask run)")
    exp, dest = _os.fspath(experiment), "" if out is None else _os.fspath(out)
    if client is not None:
        if not all(hasattr(client, a) for a in ("map", "cancel", "scheduler_info")):
            raise TypeError(f"client: expected a dask.distributed.Client, got {type(client).__name__}")
        from ._dask import run_on_client
        return run_on_client(client, exp, dest, resume, shard or "", gl_backend or "", fsync_each_row, chunk_size)
    return _hilite.run(exp, dest, resume, shard or "", gl_backend or "", fsync_each_row)


def merge(shards, out, *, gl_backend=None):
    """Joins the folders of ``run(..., shard="K/N")`` into `out`, as ``hilite merge`` does (the shards must
    be of the same experiment, row by row). Returns {dir, rows, expected, shards}."""
    if isinstance(shards, (str, _os.PathLike)):
        raise TypeError("shards: expected a list of folders, got one name")
    return _hilite.merge([_os.fspath(s) for s in shards], _os.fspath(out), gl_backend or "")


def gl_renderer():
    """The GL renderer's description ("llvmpipe (LLVM 15.0.6, 256 bits)"); "" before the first GL call."""
    return _hilite.gl_renderer()


def parameters():
    """The parameter registry: one dict per keyword (name, table, kind, default, allowed, unit, help, ...)."""
    return [dict(p) for p in REGISTRY]


import atexit as _atexit  # noqa: E402

# The GL thread ends (and its context is released on it) before the interpreter tears down.
_atexit.register(_hilite._shutdown)
