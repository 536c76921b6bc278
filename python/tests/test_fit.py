"""hilite.fit: the CLI's `hilite fit --json` in process, field for field; its refusals."""

import pytest

from conftest import cli, cli_rows, stub_typed_dicts, typed_dict_mismatches


SWEEP = dict(incidence="0:80:20", size=128)
OPTS = dict(models=["phong", "ggx"], thresholds=[0.25, 0.5, 0.75])


def test_fit_equals_the_cli(hilite):
    got = hilite.fit(model="ggx", roughness=0.1, **SWEEP, **OPTS)
    rows = cli_rows("fit", "--model", "ggx", "--roughness", "0.1", "--incidence", "0:80:20", "--size", "128",
                    "--models", "phong,ggx", "--thresholds", "0.25,0.5,0.75")
    assert [g["model"] for g in got] == ["phong", "ggx"]
    for g, c in zip(got, rows):
        for k in c:
            if k != "time_ms":
                assert g[k] == c[k], k
    ggx = got[1]
    assert ggx["rank"] == 1
    assert abs(ggx["params"]["roughness"] / 0.1 - 1) < 0.01
    assert got[0]["aspect_residual"][-1] > 0.5  # phong stays round at 80 deg while ggx narrows
    dicts = stub_typed_dicts(hilite)  # each object is the stubs' FitRow, every field present
    for g in got:
        assert set(g) == set(dicts["FitRow"]) and typed_dict_mismatches(g, "FitRow", dicts) == []


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
    with pytest.raises(TypeError, match="models: expected a list"):
        hilite.fit(model="ggx", models="ggx")
    with pytest.raises(hilite.InputError, match="roughness"):
        hilite.fit(model="ggx", roughness=-1)
