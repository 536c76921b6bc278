"""hilite.Scene: build, repr, resolve, read and write the TOML scene file."""

import pytest

from conftest import cli_rows, without_times


def test_build_repr_roundtrip(hilite, tmp_path):
    s = hilite.Scene(model="ggx", roughness=0.1, f0=(0.9, 0.6, 0.3), fresnel="schlick", incidence=60, size=(128, 96))
    assert repr(s) == "Scene(model='ggx', roughness=0.1, fresnel='schlick', f0=(0.9, 0.6, 0.3), incidence=60.0, size='128x96')"
    p = tmp_path / "s.toml"
    s.write(p)
    text = p.read_text()
    assert "[material]" in text and "roughness = 0.1" in text and "f0 = [0.9, 0.6, 0.3]" in text
    back = hilite.Scene.read(p)
    assert back == s and back.resolve() == s.resolve()
    assert hilite.Scene.from_toml(s.to_toml()) == s
    assert s["roughness"] == 0.1 and "model" in s and "exponent" not in s


def test_resolve(hilite):
    r = hilite.Scene(model="ggx", roughness=0.1, geometry="smith", fresnel="schlick", f0=0.04).resolve()
    assert r["roughness"] == 0.1 and r["geometry"] == "smith" and r["f0"] == [0.04, 0.04, 0.04]
    assert "exponent" not in r  # GGX does not use it
    assert r["angles"] == [45.0]
    assert {"D_GGX", "F_Schlick", "G2_SmithCorrelated"} <= set(r["effects"])
    with pytest.raises(hilite.InputError):
        hilite.Scene(roughness=-1).resolve()


def test_replace_and_paths(hilite, tmp_path):
    s = hilite.Scene(model="ggx", roughness=0.1)
    t = s.replace(roughness=0.3, incidence=20)
    assert s["roughness"] == 0.1 and t["roughness"] == 0.3 and t["incidence"] == 20.0
    with pytest.raises(TypeError, match="one value"):
        hilite.Scene(roughness=[0.1, 0.2])


def test_written_file_measures_like_cli(hilite, tmp_path):
    s = hilite.Scene(model="beckmann", roughness=0.2, incidence="0,40", size=64)
    s.write(tmp_path / "b.toml")
    cols = hilite.measure(s)
    rows = cli_rows("measure", "--scene", tmp_path / "b.toml")
    assert cols["aspect"].tolist() == [r["aspect"] for r in rows]
    assert [without_times(r)["model"] for r in rows] == cols["model"].tolist()
