"""examples/aspect_vs_incidence.py against `hilite run` of the experiment it reproduces
(experiments/eccentricity.toml), on a few angles and two models so that it stays fast (a few seconds).

    PYTHONPATH=build/python /usr/bin/python3 -m pytest python/tests/test_example.py
"""

import csv
import importlib.util
import json
import os
import tomllib

import pytest

import hilite  # PYTHONPATH=<build>/python (ctest sets it)

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
MODELS = ["phong", "ggx"]
ANGLES = [0.0, 40.0, 80.0]


def load_example():
    spec = importlib.util.spec_from_file_location("aspect_vs_incidence",
                                                  os.path.join(ROOT, "examples", "aspect_vs_incidence.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


example = load_example()


def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)  # a TOML basic string for text without control characters
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    raise TypeError(f"no TOML for {type(v).__name__}")


def toml_table(header, table, prefix=""):
    lines = [f"[{header}]"]
    for k, v in table.items():
        if isinstance(v, dict):  # dotted keys (material.model = ...)
            lines += toml_table(header, v, prefix + k + ".")[1:]
        else:
            lines.append(f"{prefix}{k} = {toml_value(v)}")
    return lines


@pytest.fixture(scope="module")
def run_rows(tmp_path_factory):
    """`hilite run` of eccentricity.toml's scene and [match], its sweeps cut to MODELS x ANGLES (no plots)."""
    with open(os.path.join(ROOT, "experiments", "eccentricity.toml"), "rb") as f:
        exp = tomllib.load(f)
    keys = [s["key"] for s in exp["sweep"]]
    assert keys == ["material.model", "light.incidence"], "eccentricity.toml's sweeps changed: update this test"
    assert set(MODELS) <= set(exp["sweep"][0]["values"])
    lines = toml_table("experiment", {"name": "eccentricity_check"})
    for name, table in exp["scene"].items():
        lines += toml_table(f"scene.{name}", table)
    lines += ["[[sweep]]", 'key = "material.model"', f"values = {toml_value(MODELS)}",
              "[[sweep]]", 'key = "light.incidence"', f"values = {toml_value(ANGLES)}"]
    lines += toml_table("match", exp["match"])
    d = tmp_path_factory.mktemp("eccentricity_check")
    (d / "eccentricity_check.toml").write_text("\n".join(lines) + "\n")
    hilite.run(str(d / "eccentricity_check.toml"), str(d / "out"))
    with open(d / "out" / "results.csv", newline="") as f:
        return {(r["model"], float(r["incidence_deg"])): r for r in csv.DictReader(f)}, exp


def test_the_example_uses_the_experiments_scene(run_rows):
    _, exp = run_rows
    assert example.SCENE["fresnel"] == exp["scene"]["material"]["fresnel"]
    assert example.SCENE["geometry"] == exp["scene"]["material"]["geometry"]
    assert str(example.SCENE["size"]) == exp["scene"]["camera"]["size"]
    assert example.TARGET == exp["match"]["material"]
    assert example.MODELS == exp["sweep"][0]["values"]


def test_aspects_equal_hilite_run(run_rows):
    ref, _ = run_rows
    rows = example.aspect_rows(models=MODELS, incidences=ANGLES)
    assert [(r["model"], r["incidence_deg"]) for r in rows] == [(m, t) for m in MODELS for t in ANGLES]
    for r in rows:
        want = ref[(r["model"], r["incidence_deg"])]
        # the example matches on hilite.measure's major axis, the runner on the CPU twin's half-width
        assert r["aspect"] == pytest.approx(float(want["aspect"]), abs=1e-3), r
        assert r["matched_parameter"] == pytest.approx(float(want["matched_parameter"]), rel=1e-3), r
    phong = {r["incidence_deg"]: r["aspect"] for r in rows if r["model"] == "phong"}
    ggx = {r["incidence_deg"]: r["aspect"] for r in rows if r["model"] == "ggx"}
    assert phong[80.0] > 0.99 and ggx[80.0] < 0.3  # the experiment's point: round against narrowed


def test_match_width_hits_the_target():
    target = example.major_at_normal("ggx", 0.1)
    value, evals = example.match_width("blinn", target)
    assert example.major_at_normal("blinn", value) == pytest.approx(target, rel=1e-5)
    assert evals < 40


def test_csv_and_plot_are_written_headless(tmp_path, monkeypatch):
    monkeypatch.delenv("DISPLAY", raising=False)
    rows = [{"model": m, "incidence_deg": t, "aspect": 1.0 - t / 100, "matched_parameter": 2.0}
            for m in MODELS for t in ANGLES]
    example.write_csv(rows, tmp_path / "a.csv")
    with open(tmp_path / "a.csv", newline="") as f:
        back = list(csv.DictReader(f))
    assert [r["model"] for r in back] == [r["model"] for r in rows]
    assert float(back[1]["aspect"]) == pytest.approx(0.6)
    example.plot(rows, tmp_path / "a.png")
    assert (tmp_path / "a.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_bad_output_refused_before_anything_is_measured(tmp_path, capsys):
    (tmp_path / "file").write_text("x")
    with pytest.raises(SystemExit) as e:
        example.main(["-o", str(tmp_path / "file" / "sub" / "a.png")])  # a file where a folder should be
    assert e.value.code == 2
    assert "is a file, not a folder" in capsys.readouterr().err
    with pytest.raises(SystemExit) as e:
        example.main(["-o", str(tmp_path / "new" / "a.svg")])
    assert e.value.code == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]  # nothing made for a refused run


def test_output_folders_are_made(tmp_path):
    # The example makes its output's folders, as hilite does (before: "no folder", and the user made it).
    assert example.folder_problem(str(tmp_path / "new" / "deep" / "a.png")) == ""
