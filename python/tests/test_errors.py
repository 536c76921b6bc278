"""Bad values, wrong types, NaN and unknown keywords: InputError (a ValueError) with the CLI's message naming
the keyword, or TypeError; nothing is written."""

import math
import os

import numpy as np
import pytest

from conftest import cli


def cli_message(*args):
    r = cli("measure", *args, check=False)
    assert r.returncode == 2
    return r.stderr.strip().splitlines()[-1]


@pytest.mark.parametrize("kw, flag", [
    (dict(roughness=-3), ["--roughness", "-3"]),
    (dict(roughness=math.nan), ["--roughness", "nan"]),
    (dict(incidence=95), ["--incidence", "95"]),
    (dict(threshold=1.5), ["--threshold", "1.5"]),
    (dict(model="ggxx"), ["--model", "ggxx"]),
    (dict(size=0), ["--size", "0"]),
    (dict(exponent=math.inf, model="phong"), ["--exponent", "inf", "--model", "phong"]),
    (dict(f0=(0.1, 2, 0.1), fresnel="schlick"), ["--f0", "0.1,2,0.1", "--fresnel", "schlick"]),
])
def test_bad_values_name_the_keyword(hilite, kw, flag):
    with pytest.raises(hilite.InputError) as e:
        hilite.measure(**kw)
    assert isinstance(e.value, ValueError)
    msg = str(e.value)
    name = next(iter(kw))
    assert msg.startswith(name + ":"), msg
    # the same words as the CLI, with the keyword where the CLI names the flag
    expected = cli_message(*flag)
    assert msg.split(":", 1)[1].strip() in expected, (msg, expected)


def test_nan_in_an_array(hilite):
    with pytest.raises(hilite.InputError, match=r"^incidence: .*nan"):
        hilite.measure(incidence=np.array([10.0, np.nan]))


@pytest.mark.parametrize("kw", [dict(roughness="0.1"), dict(model=3), dict(reference=1), dict(size=[1.5j]),
                                dict(f0="x"), dict(incidence=object()), dict(param=5), dict(ndf_table=3.0)])
def test_wrong_types(hilite, kw):
    with pytest.raises(TypeError) as e:
        hilite.measure(**kw)
    assert str(e.value).startswith(next(iter(kw)) + ":")


def test_unknown_keyword(hilite):
    with pytest.raises(hilite.InputError, match=r"^rougness: unknown keyword \(did you mean 'roughness'\?\)"):
        hilite.measure(rougness=0.1)
    with pytest.raises(hilite.InputError, match="unknown keyword"):
        hilite.render(colour="red")
    with pytest.raises(hilite.InputError, match=r"^size: unknown keyword"):
        hilite.brdf.albedo(30, size=64)


def test_combination_refused_like_cli(hilite):
    with pytest.raises(hilite.InputError) as e:
        hilite.measure(model="phong", roughness_y=0.2)
    assert "roughness_y" in str(e.value)


def test_every_scene_checked_before_any_is_measured(hilite):
    with pytest.raises(hilite.InputError, match="roughness"):
        hilite.measure(roughness=[0.1, 0.2, -1.0], incidence=30, size=64)


def test_nothing_written(hilite, tmp_path):
    out = tmp_path / "res"
    bad = tmp_path / "bad.toml"
    bad.write_text('[experiment]\nname = "x"\n[scene.material]\nroughness = -1\n')
    with pytest.raises(hilite.InputError, match="roughness"):
        hilite.run(str(bad), str(out))
    assert not out.exists()
    target = tmp_path / "scene.toml"
    target.write_text("keep")
    with pytest.raises(hilite.InputError):
        hilite.Scene(roughness=0.1).write(tmp_path / "missing" / "x.toml")
    os.mkdir(tmp_path / "adir")
    with pytest.raises(hilite.InputError, match="path"):
        hilite.Scene(roughness=0.1).write(tmp_path / "adir")
    assert target.read_text() == "keep"


def test_scene_file_errors_name_file_and_line(hilite, tmp_path):
    p = tmp_path / "s.toml"
    p.write_text("[material]\nmodel = \"ggx\"\nroughness = 42\n")
    s = hilite.Scene.read(p)
    with pytest.raises(hilite.InputError, match=r"s\.toml:3: material\.roughness: "):
        hilite.measure(s)
    with pytest.raises(hilite.InputError, match=r"^s2\.toml:2: material\.rougness: unknown key \(did you mean"):
        hilite.Scene.from_toml("[material]\nrougness = 1\n", "s2.toml")


def test_eval_refuses_non_unit(hilite):
    with pytest.raises(hilite.InputError, match=r"wi\[1\]"):
        hilite.brdf.eval([[0, 0, 1], [0, 0, 2]], [0, 0, 1])


def test_nul_in_a_file_name_is_refused(hilite, tmp_path):
    # A C string ends at the NUL: "a\0b.toml" would write a, "x.binary\0zz" read x.binary.
    (tmp_path / "x.binary").write_bytes(b"")
    with pytest.raises(hilite.InputError, match=r"measured\b.*: a file name cannot contain a NUL character"):
        hilite.measure(measured=str(tmp_path / "x.binary") + "\0zz")
    with pytest.raises(hilite.InputError, match="path: a file name cannot contain a NUL character"):
        hilite.Scene(roughness=0.1).write(str(tmp_path / "a") + "\0b.toml")
    assert not (tmp_path / "a").exists()
    (tmp_path / "s.toml").write_text("[material]\nroughness = 0.2\n")
    with pytest.raises(hilite.InputError, match="a file name cannot contain a NUL character"):
        hilite.Scene.read(str(tmp_path / "s.toml") + "\0x")


def test_a_sweep_larger_than_the_cli_allows_is_refused_at_once(hilite):
    import numpy as np
    r = np.linspace(0.05, 0.5, 10000)[:, None]
    t = np.linspace(0.0, 80.0, 10000)[None, :]  # 10^8 scenes, never made: refused from the arrays' shapes
    with pytest.raises(hilite.InputError, match=r"give 100000000 scenes, more than 1000000"):
        hilite.measure(roughness=r, incidence=t)
