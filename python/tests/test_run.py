"""hilite.run writes what `hilite run` writes; resume and merge keep their proofs."""

import pytest

from conftest import cli, stub_typed_dicts, typed_dict_mismatches, rows

EXPERIMENT = """[experiment]
name = "tiny"
[scene.camera]
size = "64"
[[sweep]]
key = "material.model"
values = ["phong", "ggx"]
[[sweep]]
key = "light.incidence"
values = [0, 60]
[[plot]]
file = "aspect.png"
x = "incidence_deg"
y = "aspect"
series = "model"
"""


def test_run_equals_cli(hilite, tmp_path):
    exp = tmp_path / "tiny.toml"
    exp.write_text(EXPERIMENT)
    s = hilite.run(exp, tmp_path / "py")
    assert s["configurations"] == 4 and s["measured"] == 4 and s["finalized"]
    dicts = stub_typed_dicts(hilite)
    assert set(s) == set(dicts["RunSummary"]) and typed_dict_mismatches(s, "RunSummary", dicts) == []
    cli("run", exp, "-o", tmp_path / "cli")
    assert rows(tmp_path / "py/results.jsonl") == rows(tmp_path / "cli/results.jsonl")
    assert (tmp_path / "py/summary.md").exists() and (tmp_path / "py/aspect.png").exists()
    again = hilite.run(exp, tmp_path / "py", resume=True)
    assert again["measured"] == 0
    # the module's own GL context still works after the run made (and released) its own
    assert hilite.measure(model="ggx", size=64)["aspect"] > 0


def test_shards_and_merge(hilite, tmp_path):
    exp = tmp_path / "tiny.toml"
    exp.write_text(EXPERIMENT)
    a = hilite.run(exp, tmp_path / "s1", shard="1/2")
    b = hilite.run(exp, tmp_path / "s2", shard="2/2")
    assert a["measured"] + b["measured"] == 4 and not a["finalized"]
    m = hilite.merge([tmp_path / "s1", tmp_path / "s2"], tmp_path / "all")
    assert m["rows"] == m["expected"] == 4
    dicts = stub_typed_dicts(hilite)
    assert set(m) == set(dicts["MergeSummary"]) and typed_dict_mismatches(m, "MergeSummary", dicts) == []
    with pytest.raises(hilite.InputError, match="shard"):
        hilite.run(exp, tmp_path / "s3", shard="3/2")


def test_resume_refuses_another_experiment(hilite, tmp_path):
    exp = tmp_path / "tiny.toml"
    exp.write_text(EXPERIMENT)
    hilite.run(exp, tmp_path / "r")
    exp.write_text(EXPERIMENT.replace('values = [0, 60]', 'values = [0, 30]'))
    before = (tmp_path / "r/results.jsonl").read_text()
    with pytest.raises(hilite.InputError):
        hilite.run(exp, tmp_path / "r", resume=True)
    assert (tmp_path / "r/results.jsonl").read_text() == before
