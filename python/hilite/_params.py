"""Keywords -> the CLI's text, from the parameter registry (hilite._hilite.registry()).

Every scene and measurement parameter is a keyword named as its scene-file key (``roughness_y``; the
CLI flag is ``--roughness-y``). A keyword's value is turned into the text the command line would carry
and checked by the same code (scene::check, then scene::resolve), so a value refused by the CLI is
refused here with the same words, naming the keyword. Wrong Python types raise TypeError.
"""

import numbers
import os

import numpy as np

from . import _hilite

InputError = _hilite.InputError

REGISTRY = _hilite.registry()
PARAMS = {p["name"]: p for p in REGISTRY}


def unknown(name, allowed, what="keyword"):
    """The InputError for an unknown keyword, with a did-you-mean."""
    hint = _hilite.did_you_mean(name, list(allowed))
    return InputError(f"{name}: unknown {what}" + (f" (did you mean '{hint}'?)" if hint else "") +
                      "; allowed: " + ", ".join(allowed))


def _real(x):
    return isinstance(x, (numbers.Real, np.floating, np.integer)) and not isinstance(x, (bool, np.bool_))


def _number_text(x):
    if isinstance(x, (numbers.Integral, np.integer)):
        return str(int(x))
    return repr(float(x))  # the shortest text that reads back as the same double (as the CLI's exactText)


def _type_error(name, expected, value):
    return TypeError(f"{name}: expected {expected}, got {type(value).__name__} ({value!r})")


def scalar_text(p, value):
    """The CLI text of one (not swept) value of parameter `p`."""
    name, kind = p["name"], p["kind"]
    if kind == "number":
        if isinstance(value, str):
            if p["automatic"] and value == p["automatic"]:
                return value
            raise _type_error(name, "a number" + (f" or '{p['automatic']}'" if p["automatic"] else ""), value)
        if not _real(value):
            raise _type_error(name, "a number", value)
        return _number_text(value)
    if kind == "integer":
        if not _real(value):
            raise _type_error(name, "an integer", value)
        return _number_text(value)
    if kind == "choice":
        if not isinstance(value, str):
            raise _type_error(name, "a string (one of " + ", ".join(p["choices"]) + ")", value)
        return value
    if kind == "switch":
        if not isinstance(value, (bool, np.bool_)):
            raise _type_error(name, "True or False", value)
        return "true" if value else "false"
    if kind == "text":
        if not isinstance(value, str):
            raise _type_error(name, "a string", value)
        return value
    if kind == "path":
        if not isinstance(value, (str, os.PathLike)):
            raise _type_error(name, "a file name (str or os.PathLike)", value)
        return os.fspath(value)
    if kind == "rgb":
        if _real(value):
            return _number_text(value)
        if isinstance(value, (list, tuple, np.ndarray)) and len(value) == 3 and all(_real(v) for v in value):
            return ",".join(_number_text(v) for v in value)
        raise _type_error(name, "a number or 3 numbers (R, G, B)", value)
    if kind == "angles":
        if _real(value):
            return _number_text(value)
        if isinstance(value, str):  # the CLI's spelling: "60", "0,30,60" or "0:85:5"
            return value
        raise _type_error(name, "a number of degrees (or an array of them)", value)
    if kind == "size":
        if isinstance(value, str):  # "512" or "640x480"
            return value
        if _real(value):
            return _number_text(value)
        if isinstance(value, tuple) and len(value) == 2 and all(_real(v) for v in value):
            return f"{_number_text(value[0])}x{_number_text(value[1])}"
        raise _type_error(name, "an integer, a (width, height) tuple or 'WxH'", value)
    raise _type_error(name, "a value", value)


def list_texts(p, value):
    """A List parameter (the .brdf `param`): {name: value}, a list of "NAME=VALUE" or one such string."""
    name = p["name"]
    if isinstance(value, str):
        return [value]
    if isinstance(value, dict):
        out = []
        for k, v in value.items():
            if not isinstance(k, str):
                raise _type_error(name, "a dict of str keys", k)
            if _real(v):
                out.append(f"{k}={_number_text(v)}")
            elif isinstance(v, (list, tuple)) and all(_real(x) for x in v):
                out.append(f"{k}=" + ",".join(_number_text(x) for x in v))
            elif isinstance(v, str):
                out.append(f"{k}={v}")
            else:
                raise _type_error(f"{name}['{k}']", "a number, numbers or a string", v)
        return out
    if isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value):
        return list(value)
    raise _type_error(name, "a dict {name: value} or a list of 'NAME=VALUE' strings", value)


def is_sweep(p, value):
    """Whether `value` is an array of values of `p` (a sweep) rather than one value."""
    if isinstance(value, np.ndarray):
        return value.ndim >= 1 and not (p["kind"] == "rgb" and value.shape == (3,))
    if p["kind"] in ("rgb", "list"):
        return False
    if p["kind"] == "size" and isinstance(value, tuple):
        return False
    return isinstance(value, (list, tuple, range))


def lookup(name, allowed=None):
    p = PARAMS.get(name)
    if p is None or (allowed is not None and name not in allowed):
        raise unknown(name, sorted(allowed if allowed is not None else PARAMS))
    return p


def items_of(params, allowed=None):
    """(name, text, origin) items of scalar keyword values; None values are left out (the default)."""
    out = []
    for name, value in params.items():
        p = lookup(name, allowed)
        if value is None:
            continue
        if p["kind"] == "list":
            out.extend((name, t, "") for t in list_texts(p, value))
        else:
            if is_sweep(p, value):
                raise TypeError(f"{name}: one value expected here, got an array ({type(value).__name__})")
            out.append((name, scalar_text(p, value), ""))
    return out


def signature_doc(allowed=None):
    """The keywords' lines for a docstring: name, allowed values, unit, default, help."""
    lines = []
    for p in REGISTRY:
        if allowed is not None and p["name"] not in allowed:
            continue
        default = p["default"] if p["default"] != "" else "unset"
        unit = f" {p['unit']}" if p["unit"] else ""
        lines.append(f"    {p['name']} : {p['kind']}, {p['allowed']}{unit}, default {default}\n"
                     f"        {p['help']} (applies to: {p['applies_to']})")
    return "\n".join(lines)
