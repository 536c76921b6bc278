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
    assert public == {"fresnel", "albedo", "bihemispherical_albedo", "normalization", "eval", "bounces", "slice"}
    assert names == public
    assert os.path.exists(os.path.join(here, "py.typed"))


def test_docstrings_carry_ranges_and_defaults(hilite):
    doc = hilite.measure.__doc__
    for p in hilite.REGISTRY:
        assert f"    {p['name']} : " in doc
    assert "    roughness : number, [0, 10], default 0.1\n" in doc


def test_rows_match_their_typed_dicts(hilite):
    from conftest import stub_typed_dicts, typed_dict_mismatches
    dicts = stub_typed_dicts(hilite)
    assert {"Row", "Part", "FitRow", "RunSummary", "MergeSummary"} <= set(dicts)
    # the registry's columns and the module's measurement columns are all typed fields of Row
    for c in [p["column"] for p in hilite.REGISTRY if p["column"]] + hilite._hilite.measurement_columns():
        assert c in dicts["Row"], c
    rows = [hilite.measure(model="ggx", geometry="smith", fresnel="schlick", f0=0.04, incidence=60, size=128),
            hilite.measure(model="ggx", incidence=40, tolerance=0.01, renderer="cpu"),
            hilite.measure(model="ggx", incidence=85, light="disk", reference=True),
            hilite.measure(model="beckmann", bumps="explicit", incidence=30, size=128),
            hilite.measure(model="ggx", fresnel="schlick", f0=(0.04, 0.05, 0.06), roughness=0, size=64)]
    assert rows[0]["parts"] and rows[1]["settings"] and rows[3]["analytic_aspect"] > 0
    assert rows[4]["flags"] == ["mirror"]
    for row in rows:
        assert typed_dict_mismatches(row, "Row", dicts) == []
    # the check can fail: a field of another type, a field the stub does not know
    bad = dict(rows[0], aspect="0.5", parts=[dict(rows[0]["parts"][0], holds_peak=1)], surprise=1)
    assert sorted(m.split(":")[0] for m in typed_dict_mismatches(bad, "Row", dicts)) == ["aspect", "parts", "surprise"]
