"""hilite.Scene: one scene's parameter values, as a scene file (TOML) holds them."""

import os

from . import _hilite
from ._params import PARAMS, REGISTRY, items_of, lookup


def _python_value(p, text):
    """A value's text as the Python value a keyword would give (for repr and scene[key])."""
    kind = p["kind"]
    try:
        if kind == "number":
            return text if text == p["automatic"] else float(text)
        if kind == "integer":
            return int(float(text))
        if kind == "switch":
            return text == "true"
        if kind == "rgb" and "," in text:
            return tuple(float(v) for v in text.split(","))
        if kind == "rgb":
            return float(text)
        if kind == "angles" and "," not in text and ":" not in text:
            return float(text)
    except ValueError:
        pass
    return text


class Scene:
    """One scene: parameter values by keyword, checked when it is resolved, measured or rendered.

        s = hilite.Scene(model="ggx", roughness=0.1, incidence=60)
        s2 = s.replace(roughness=0.2)           # a copy with other values
        s.write("ggx.toml"); hilite.Scene.read("ggx.toml") == s
        s.resolve()                             # the parameters as they would be rendered (a dict)
        hilite.measure(s, incidence=[30, 60])   # keywords override the scene

    A scene file's values remember their file and line, so a refused value names "scene.toml:4:
    material.roughness" as the CLI does."""

    def __init__(self, **params):
        self._items = items_of(params)

    @classmethod
    def _of_items(cls, items):
        s = cls.__new__(cls)
        s._items = [tuple(i) for i in items]
        return s

    @classmethod
    def read(cls, path):
        """The scene of a scene file (TOML); InputError naming file:line: key for a bad one."""
        if not isinstance(path, (str, os.PathLike)):
            raise TypeError(f"path: expected a file name, got {type(path).__name__}")
        return cls._of_items(_hilite.load_scene(os.fspath(path)))

    @classmethod
    def from_toml(cls, text, name="<string>"):
        """The scene of a scene file's text; `name` stands for the file in messages."""
        if not isinstance(text, str):
            raise TypeError(f"text: expected str, got {type(text).__name__}")
        return cls._of_items(_hilite.parse_scene(text, name))

    def to_toml(self):
        """The scene file's text (file names made absolute)."""
        return _hilite.scene_toml(self._items)

    def write(self, path):
        """Writes the scene file (replacing only a regular file, through a temporary file)."""
        if not isinstance(path, (str, os.PathLike)):
            raise TypeError(f"path: expected a file name, got {type(path).__name__}")
        _hilite.write_scene(os.fspath(path), self._items)

    def replace(self, **params):
        """A copy with these keywords set (later values win; `param` assignments add up)."""
        out = Scene._of_items(self._items)
        new = items_of(params)
        names = {n for n, _, _ in new if PARAMS[n]["kind"] != "list"}
        out._items = [i for i in out._items if i[0] not in names] + new
        return out

    def resolve(self, purpose="measure"):
        """The parameters as resolved for `purpose` ('measure', 'render' or 'brdf'): the row columns
        (every parameter that applies, as rendered), 'angles' and the 'effects' that run; InputError if
        the scene is refused."""
        if purpose not in ("measure", "render", "brdf"):
            raise TypeError(f"purpose: expected 'measure', 'render' or 'brdf', got {purpose!r}")
        return _hilite.resolve(self._items, purpose)

    def items(self):
        """(keyword, text, origin) of every value given, as the library reads them."""
        return list(self._items)

    def to_dict(self):
        """The values given, as Python values (a `param` list as a list of 'NAME=VALUE')."""
        out = {}
        for name, text, _ in self._items:
            p = PARAMS[name]
            if p["kind"] == "list":
                out.setdefault(name, []).append(text)
            else:
                out[name] = _python_value(p, text)
        return out

    def __getitem__(self, name):
        lookup(name)
        d = self.to_dict()
        if name not in d:
            raise KeyError(name)
        return d[name]

    def __contains__(self, name):
        return name in self.to_dict()

    def __eq__(self, other):
        return isinstance(other, Scene) and self.to_dict() == other.to_dict()

    def __repr__(self):
        order = {p["name"]: i for i, p in enumerate(REGISTRY)}
        d = self.to_dict()
        return "Scene(" + ", ".join(f"{k}={d[k]!r}" for k in sorted(d, key=order.get)) + ")"
