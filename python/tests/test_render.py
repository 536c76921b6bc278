"""hilite.render equals `hilite render --float` pixel for pixel; the measurement view's maps."""

import numpy as np
import pytest

from conftest import cli, read_pfm


@pytest.mark.parametrize("scene", [
    dict(model="ggx", roughness=0.1, incidence=60, size=96),
    dict(model="phong", exponent=100, incidence=30, view="photo", size="120x80"),
    dict(material="copper", model="beckmann", roughness=0.3, diffuse="lambert", incidence=45, view="photo", size=64),
])
def test_render_equals_pfm(hilite, tmp_path, scene):
    img = hilite.render(**scene)
    args = []
    for k, v in scene.items():
        args += [f"--{k.replace('_', '-')}", str(v)]
    cli("render", *args, "--float", tmp_path / "a.pfm")
    ref = read_pfm(tmp_path / "a.pfm")
    assert img.dtype == np.float32 and img.shape == ref.shape
    assert np.array_equal(img, ref)  # bit for bit
    assert img.max() > 0


def test_maps(hilite):
    img, maps = hilite.render(model="ggx", roughness=0.1, incidence=30, size=64, maps=True)
    assert set(maps) == {"u_deg", "v_deg", "area_deg2", "luminance"}
    for m in maps.values():
        assert m.shape == (64, 64)
    assert np.all(maps["area_deg2"] > 0)
    # the view is centred on the mirror direction: (u, v) ~ 0 at the centre, growing outwards
    c = maps["u_deg"][31:33, 31:33]
    assert np.abs(c).max() < 0.5
    # the luminance is the Rec. 709 luminance of the radiance image
    lum = 0.2126 * img[..., 0] + 0.7152 * img[..., 1] + 0.0722 * img[..., 2]
    np.testing.assert_allclose(maps["luminance"], lum, rtol=1e-5, atol=1e-7)
    # total (u, v) area ~ the frame's chart area (30 deg field of view)
    assert 600 < maps["area_deg2"].sum() < 1200


def test_maps_photo_refused(hilite):
    with pytest.raises(hilite.InputError, match="maps"):
        hilite.render(view="photo", maps=True, size=32)
