"""`hilite brdf slice` and hilite.brdf.slice: the slices' values are f(wi, wo) at their directions, as
hilite.brdf.eval gives it, for a built-in model and a measured table overlaid."""

import csv
import os
import shutil

import numpy as np

from conftest import cli


def _rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_cli_slice_writes_png_csv_and_its_values_are_eval(hilite, tmp_path):
    table = tmp_path / "ggx.binary"
    cli("brdf", "tabulate", "--model", "ggx", "--roughness", "0.2", "-o", table)
    out = tmp_path / "slices"
    cli("brdf", "slice", "--model", "ggx", "--roughness", "0.1", "--incidence", "60", "--measured", table,
        "--step", "2", "-o", out)
    for f in ("slice.csv", "slice.json"):
        assert (out / f).exists()
    if shutil.which("gnuplot"):
        assert (out / "slice_in.png").stat().st_size > 0
        assert (out / "slice_across.png").stat().st_size > 0
    rows = _rows(out / "slice.csv")
    curves = {r["curve"] for r in rows}
    assert curves == {"ggx roughness=0.1", "measured ggx.binary"}
    assert len(rows) == 2 * 2 * 89  # 2 curves x 2 planes x -88..88 every 2 deg
    wi = np.array([np.sin(np.radians(60)), 0.0, np.cos(np.radians(60))])
    for curve, params in (("ggx roughness=0.1", dict(model="ggx", roughness=0.1)),
                          ("measured ggx.binary", dict(measured=str(table)))):
        mine = [r for r in rows if r["curve"] == curve]
        wo = np.array([[float(r["wo_x"]), float(r["wo_y"]), float(r["wo_z"])] for r in mine])
        f = np.array([[float(r["f_r"]), float(r["f_g"]), float(r["f_b"])] for r in mine])
        want = hilite.brdf.eval(np.broadcast_to(wi, wo.shape), wo, **params)
        np.testing.assert_allclose(f, want, rtol=1e-8, atol=1e-12)  # the CSV's 10 significant digits
        # The mirror direction is in both planes: +60 deg in the plane, 0 across.
        at_in = next(r for r in mine if r["plane"] == "in" and r["angle_deg"] == "60")
        at_across = next(r for r in mine if r["plane"] == "across" and r["angle_deg"] == "0")
        assert float(at_in["f"]) == float(at_across["f"])
    # The Python function gives the same rows.
    cols = hilite.brdf.slice(60, model="ggx", roughness=0.1, measured=str(table), step=2)
    assert list(cols["curve"]) == [r["curve"] for r in rows]
    np.testing.assert_allclose(cols["f"], [float(r["f"]) for r in rows], rtol=1e-9)


def test_slice_overlays_curves_and_refuses_bad_ones(hilite):
    cols = hilite.brdf.slice([30, 60], model="ggx", roughness=0.1, curves=[dict(model="beckmann")], step=5)
    assert set(cols["curve"]) == {"ggx roughness=0.1", "model=beckmann"}
    assert set(cols["incidence_deg"]) == {30.0, 60.0}
    # Both curves have their peak at the mirror direction (the in-plane angle = theta_i).
    for curve in set(cols["curve"]):
        for inc in (30.0, 60.0):
            m = (cols["curve"] == curve) & (cols["incidence_deg"] == inc) & (cols["plane"] == "in")
            assert cols["angle_deg"][m][np.argmax(cols["f"][m])] == inc
    r = cli("brdf", "slice", "--curve", "roughnes=0.1", "-o", "/tmp/hilite-slice-never", check=False)
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "roughnes" in r.stderr
    assert not os.path.exists("/tmp/hilite-slice-never")
