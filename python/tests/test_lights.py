"""Lights with size from Python: the sphere light's limit (examples/sphere_to_point.py) and the disk's keywords
and refusals, as the CLI has them.

    PYTHONPATH=build/python /usr/bin/python3 -m pytest python/tests/test_lights.py
"""

import importlib.util
import os

import pytest

import hilite  # PYTHONPATH=<build>/python (ctest sets it)

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def test_sphere_to_point_example_is_second_order(tmp_path):
    spec = importlib.util.spec_from_file_location("sphere_to_point", os.path.join(ROOT, "examples", "sphere_to_point.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    order = mod.main(str(tmp_path / "plot.png"))
    assert 1.9 < order < 2.1
    assert (tmp_path / "plot.png").stat().st_size > 1000


def test_disk_rows_carry_the_rule():
    row = hilite.measure(model="ggx", roughness=0.02, incidence=80, light="disk", light_angle=0.266, size=128)
    assert row["light"] == "disk"
    assert row["light_rings"] >= 1
    assert 0 <= row["light_rule_error"] <= 1e-3
    assert row["light_visible"] == pytest.approx(1.0)
    assert row["aspect"] > 0.2  # the sun rounds it: cos(80 deg) = 0.17 under a directional light


@pytest.mark.parametrize("kwargs, needle", [
    (dict(light="sphere", light_radius=20.0), "light_radius: a sphere of radius 20"),
    (dict(light="sphere", light_radius=0.0), "light_radius"),
    (dict(light="disk", light_angle=90.0), "light_angle"),
    (dict(light="disk", light_rings=33), "light_rings"),
])
def test_bad_lights_are_refused(kwargs, needle):
    with pytest.raises(hilite.InputError, match=needle):
        hilite.measure(incidence=45, **kwargs)
