"""hilite.fit: the CLI's `hilite fit --json` in process, field for field; its refusals."""

import pytest

from conftest import cli, cli_rows, stub_typed_dicts, typed_dict_mismatches


SWEEP = dict(incidence="0:60:20", size=128)
OPTS = dict(models=["phong", "ggx"], thresholds=[0.25, 0.5, 0.75])


def test_fit_equals_the_cli(hilite):
    got = hilite.fit(model="ggx", roughness=0.1, **SWEEP, **OPTS)
    rows = cli_rows("fit", "--model", "ggx", "--roughness", "0.1", "--incidence", "0:60:20", "--size", "128",
                    "--models", "phong,ggx", "--thresholds", "0.25,0.5,0.75")
    assert [g["model"] for g in got] == ["ggx", "phong"]  # ranked, as the CLI prints them
    assert [g["rank"] for g in got] == [1, 2]
    for g, c in zip(got, rows):
        for k in c:
            if k != "time_ms":
                assert g[k] == c[k], k
    ggx = got[0]
    assert abs(ggx["params"]["roughness"] / 0.1 - 1) < 0.01
    assert got[1]["aspect_residual"][-1] > 0.3  # phong stays round at 60 deg while ggx narrows
    dicts = stub_typed_dicts(hilite)  # each object is the stubs' FitRow, every field present
    for g in got:
        assert set(g) == set(dicts["FitRow"]) and typed_dict_mismatches(g, "FitRow", dicts) == []


def test_fit_defaults_are_the_cli_s(hilite, tmp_path):
    # One set of defaults (experiments::FitOptions): hilite.fit with none given equals `hilite fit --json` with
    # none given, field for field, in rank order.
    table = tmp_path / "plastic.binary"
    cli("brdf", "tabulate", "--model", "beckmann", "--roughness", "0.15", "--geometry", "smith", "--f0", "0.04",
        "--diffuse", "lambert", "--albedo", "0.1", "-o", table)
    got = hilite.fit(table, incidence="0:60:30", size=96)
    rows = cli_rows("fit", "--target", table, "--incidence", "0:60:30", "--size", "96")
    assert len(got) == len(rows) == 4
    for g, c in zip(got, rows):
        assert {k: v for k, v in g.items() if k != "time_ms"} == {k: v for k, v in c.items() if k != "time_ms"}
    assert got[0]["model"] == "beckmann" and got[0]["params"]["geometry"] == "smith"
    d = hilite._hilite.fit_defaults()
    assert d["fit_geometry"] == "auto" and d["fit_f0"] is True and d["fit_diffuse"] == "auto"


def test_fit_of_a_table_file(hilite, tmp_path):
    table = tmp_path / "blinn.binary"
    cli("brdf", "tabulate", "--model", "blinn", "--exponent", "300", "-o", table)
    got = hilite.fit(table, models=["blinn"], thresholds=[0.5], incidence="0:60:30", size=128)
    assert got[0]["target"] == "measured:" + str(table)
    assert abs(got[0]["params"]["exponent"] / 300 - 1) < 0.01


def test_fit_refusals(hilite, tmp_path):
    with pytest.raises(hilite.InputError, match="--models: 'foo' is not a model"):
        hilite.fit(model="ggx", models=["foo"])
    with pytest.raises(hilite.InputError, match="--thresholds: each must be in"):
        hilite.fit(model="ggx", thresholds=[1.5])
    with pytest.raises(hilite.InputError, match="target: .* must be a MERL"):
        hilite.fit(tmp_path / "x.txt")
    with pytest.raises(hilite.InputError, match="--fit-geometry: 'bogus'"):
        hilite.fit(model="ggx", fit_geometry="bogus")
    with pytest.raises(hilite.InputError, match="--rank-by: 'both'"):
        hilite.fit(model="ggx", rank_by="both")
    with pytest.raises(hilite.InputError, match="--fit-diffuse: 'yes'"):
        hilite.fit(model="ggx", fit_diffuse="yes")
    with pytest.raises(TypeError, match="models: expected a list"):
        hilite.fit(model="ggx", models="ggx")
    with pytest.raises(hilite.InputError, match="roughness"):
        hilite.fit(model="ggx", roughness=-1)
