"""hilite.measure equals `hilite measure --json` field for field; arrays give columns."""

import numpy as np
import pytest

from conftest import cli_rows, without_times

SCENES = [
    dict(model="ggx", roughness=0.1, incidence=60),
    dict(model="phong", exponent=200, incidence=30, size=256),
    dict(model="beckmann", roughness=0.2, geometry="smith", fresnel="schlick", f0=0.04, incidence=75),
    # a region in two parts (the main lobe and a strip on the horizon): the `parts` array
    dict(model="ggx", roughness=0.1, geometry="smith", fresnel="schlick", f0=0.04, incidence=60),
    dict(model="ggx", roughness=0.3, incidence=40, reference=True),
    dict(model="ggx", roughness=0.2, roughness_y=0.05, tangent_angle=30, incidence=50, renderer="cpu", size=128),
    dict(model="blinn", exponent=500, incidence=20, tolerance=0.01),
    dict(material="gold", model="ggx", roughness=0.15, incidence=70, threshold=0.25),
]


def flags(d):
    out = []
    for k, v in d.items():
        if v is True:
            out.append(f"--{k.replace('_', '-')}")
        else:
            out += [f"--{k.replace('_', '-')}", str(v)]
    return out


@pytest.mark.parametrize("scene", SCENES, ids=lambda s: ",".join(f"{k}={v}" for k, v in s.items()))
def test_row_equals_cli(hilite, scene):
    row = hilite.measure(**scene)
    assert isinstance(row, dict)
    [expected] = cli_rows("measure", *flags(scene))
    assert without_times(row) == without_times(expected)
    assert list(row) == list(expected)  # the same fields in the same order


def test_two_parts_have_parts(hilite):
    row = hilite.measure(**SCENES[3])
    assert row["components"] == 2 and len(row["parts"]) == 2


def test_angles_give_columns(hilite):
    angles = np.arange(0.0, 86.0, 5.0)
    cols = hilite.measure(model="ggx", roughness=0.1, incidence=angles, size=128)
    assert isinstance(cols, dict)
    assert all(isinstance(v, np.ndarray) and v.shape == (len(angles),) for v in cols.values())
    assert cols["aspect"].dtype == np.float64 and cols["flags"].dtype == object
    np.testing.assert_array_equal(cols["incidence_deg"], angles)
    rows = cli_rows("measure", "--model", "ggx", "--roughness", "0.1", "--incidence", "0:85:5", "--size", "128")
    for i, r in enumerate(rows):
        for k, v in without_times(r).items():
            got = cols[k][i]
            if isinstance(v, float):
                assert got == v, k
            else:
                assert got == v, k
    # a CLI range spelling gives the same columns
    again = hilite.measure(model="ggx", roughness=0.1, incidence="0:85:5", size=128)
    np.testing.assert_array_equal(again["aspect"], cols["aspect"])


def test_parameter_arrays_broadcast(hilite):
    cols = hilite.measure(model="ggx", roughness=np.array([0.05, 0.1, 0.2])[:, None],
                          incidence=np.array([0.0, 60.0])[None, :], size=128)
    assert cols["roughness"].tolist() == [0.05, 0.05, 0.1, 0.1, 0.2, 0.2]
    assert cols["incidence_deg"].tolist() == [0, 60, 0, 60, 0, 60]
    one = hilite.measure(model="ggx", roughness=0.2, incidence=60, size=128)
    assert cols["aspect"][5] == one["aspect"]
    models = hilite.measure(model=["phong", "ggx"], incidence=45, size=128)
    assert models["model"].tolist() == ["phong", "ggx"]


def test_columns_for_dataframe(hilite):
    cols = hilite.measure(model="ggx", roughness=0.1, geometry="smith", fresnel="schlick", f0=0.04,
                          incidence=[50, 60], size=128)
    n = {len(v) for v in cols.values()}
    assert n == {2}
    # `parts` exists only for the two-part row: None in the other
    assert cols["parts"][0] is None and len(cols["parts"][1]) == 2
    try:
        import pandas
    except ImportError:
        return
    df = pandas.DataFrame(cols)
    assert df.shape[0] == 2


def test_scene_and_keywords(hilite, tmp_path):
    s = hilite.Scene(model="ggx", roughness=0.1, incidence=60, size=128)
    a = hilite.measure(s)
    b = hilite.measure(s, roughness=0.2)
    c = hilite.measure(model="ggx", roughness=0.2, incidence=60, size=128)
    assert without_times(b) == without_times(c) and a["aspect"] != b["aspect"]
    s.write(tmp_path / "s.toml")
    assert without_times(hilite.measure(str(tmp_path / "s.toml"))) == without_times(a)
    assert without_times(cli_rows("measure", "--scene", tmp_path / "s.toml")[0]) == without_times(a)


def test_a_list_of_tables_is_held_a_few_at_a_time(hilite, tmp_path):
    # Every scene is checked first, then each table read again as it is measured: 6 tables, at most 3 alive at
    # once (the 2 load() keeps and the one measured); all 6 stayed alive before (4 real ones peaked at 1.6 GB).
    files = []
    for i in range(6):
        path = tmp_path / f"constant{i}.binary"
        with open(path, "wb") as f:  # a MERL file: 3 int32 dimensions, then 3 channels of doubles
            np.array([90, 90, 180], dtype="<i4").tofile(f)
            for scale in (1 / 1500, 1.15 / 1500, 1.66 / 1500):
                np.full(90 * 90 * 180, (0.1 + 0.02 * i) / scale, dtype="<f8").tofile(f)
        files.append(str(path))
    hilite._hilite._measured_tables_held()  # resets the peak
    rows = hilite.measure(measured=files, incidence=30, size=32)
    now, peak = hilite._hilite._measured_tables_held()
    assert list(rows["measured"]) == files
    assert peak <= 3 and now <= 2
