"""The type stubs are generated from the registry: every keyword, typed; they parse."""

import ast
import os


def test_stubs_cover_the_registry(hilite):
    here = os.path.dirname(hilite.__file__)
    init = open(os.path.join(here, "__init__.pyi")).read()
    tree = ast.parse(init)
    funcs = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
    kws = [a.arg for a in funcs["measure"].args.kwonlyargs]
    assert kws == [p["name"] for p in hilite.REGISTRY]
    models = "Literal[" + ", ".join(repr(m) for m in next(p for p in hilite.REGISTRY if p["name"] == "model")["choices"])
    assert f"model: {models}] | None = None" in init
    brdf = ast.parse(open(os.path.join(here, "brdf.pyi")).read())
    names = {n.name for n in brdf.body if isinstance(n, ast.FunctionDef)}
    public = {n for n in dir(hilite.brdf) if not n.startswith("_") and callable(getattr(hilite.brdf, n))
              and getattr(getattr(hilite.brdf, n), "__module__", "") == "hilite.brdf"}
    assert public == {"fresnel", "albedo", "bihemispherical_albedo", "normalization", "eval", "bounces"}
    assert names == public
    assert os.path.exists(os.path.join(here, "py.typed"))


def test_docstrings_carry_ranges_and_defaults(hilite):
    doc = hilite.measure.__doc__
    for p in hilite.REGISTRY:
        assert f"    {p['name']} : " in doc
    assert "    roughness : number, [0, 10], default 0.1\n" in doc
