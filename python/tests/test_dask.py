"""hilite.run(..., client=) on a dask.distributed LocalCluster: the rows a single run writes, row for row."""

import pytest

from conftest import is_time, rows

distributed = pytest.importorskip("distributed", reason="Dask's python3-distributed is not installed "
                                  "(the quick start installs it)")

EXPERIMENT = """[experiment]
name = "spread"
[scene.camera]
size = "64"
[[sweep]]
key = "material.model"
values = ["phong", "ggx", "beckmann"]
[[sweep]]
key = "light.incidence"
values = [0, 30, 50, 70]
[[plot]]
file = "aspect.png"
x = "incidence_deg"
y = "aspect"
series = "model"
"""


def csv_rows(path):  # the CSV without its timing columns
    lines = [line.rstrip("\n").split(",") for line in open(path)]
    keep = [i for i, c in enumerate(lines[0]) if not is_time(c)]
    return [[r[i] for i in keep] for r in lines]


@pytest.fixture(scope="module")
def client():
    # Two worker processes, one thread each: each imports hilite and makes its own GL context.
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address="127.0.0.1:0",
                                       host="127.0.0.1")
    c = distributed.Client(cluster)
    try:
        yield c
    finally:
        c.close()
        cluster.close()


def test_dask_rows_equal_a_single_run(hilite, tmp_path, client):
    exp = tmp_path / "spread.toml"
    exp.write_text(EXPERIMENT)
    single = hilite.run(exp, tmp_path / "single")
    s = hilite.run(exp, tmp_path / "dask", client=client, chunk_size=2)
    assert s["configurations"] == 12 and s["measured"] == 12 and s["finalized"]
    assert rows(tmp_path / "dask/results.jsonl") == rows(tmp_path / "single/results.jsonl")
    assert [r["config"] for r in rows(tmp_path / "dask/results.jsonl")] == list(range(12))
    assert csv_rows(tmp_path / "dask/results.csv") == csv_rows(tmp_path / "single/results.csv")
    assert (tmp_path / "dask/summary.md").exists() and (tmp_path / "dask/aspect.png").exists()
    assert single["measured"] == 12
    # Both worker processes measured, each with the experiment loaded once (and its own GL context).
    held = client.run(lambda: len(__import__("hilite._dask", fromlist=["_measurers"])._measurers))
    assert sorted(held.values()) == [1, 1]


def test_dask_resume_measures_only_the_missing_rows(hilite, tmp_path, client):
    exp = tmp_path / "spread.toml"
    exp.write_text(EXPERIMENT)
    hilite.run(exp, tmp_path / "single")
    (tmp_path / "part").mkdir()
    lines = open(tmp_path / "single/results.jsonl").readlines()
    (tmp_path / "part/results.jsonl").write_text("".join(lines[:5]) + lines[5][:40])  # a torn last line too
    s = hilite.run(exp, tmp_path / "part", client=client, resume=True)
    assert s["measured"] == 7
    assert rows(tmp_path / "part/results.jsonl") == rows(tmp_path / "single/results.jsonl")


def test_dask_shard_then_merge(hilite, tmp_path, client):
    exp = tmp_path / "spread.toml"
    exp.write_text(EXPERIMENT)
    hilite.run(exp, tmp_path / "single")
    for k in (1, 2):
        s = hilite.run(exp, tmp_path / f"s{k}", client=client, shard=f"{k}/2")
        assert s["measured"] == 6 and not s["finalized"]
    hilite.merge([tmp_path / "s1", tmp_path / "s2"], tmp_path / "merged")
    assert rows(tmp_path / "merged/results.jsonl") == rows(tmp_path / "single/results.jsonl")


def test_rows_of_another_experiment_are_refused(hilite, tmp_path):
    exp = tmp_path / "spread.toml"
    exp.write_text(EXPERIMENT)
    other = tmp_path / "other.toml"
    other.write_text(EXPERIMENT.replace('values = [0, 30, 50, 70]', 'values = [0, 30, 50, 71]'))
    hilite.run(other, tmp_path / "other")
    foreign = open(tmp_path / "other/results.jsonl").readlines()
    run = hilite._hilite._DistributedRun(str(exp), str(tmp_path / "d"), False, "", "", False)
    assert run.todo() == list(range(12))
    run.append([foreign[0]])  # configuration 0: incidence 0 in both, the same fingerprint
    with pytest.raises(hilite.InputError, match=r"configuration 3\).*incidence = 71, the experiment now says 70"):
        run.append([foreign[3]])
    with pytest.raises(hilite.InputError, match="configuration 0 has its row already"):
        run.append([foreign[0]])
    with pytest.raises(hilite.InputError, match="a row from a worker"):
        run.append(["not json"])
    with pytest.raises(hilite.InputError, match=r"11 of 12 configurations have no row yet"):
        run.finish()
    assert run.close() == 1
    assert len(open(tmp_path / "d/results.jsonl").readlines()) == 1  # what was appended stays, durable


def test_client_and_chunk_size_checked(hilite, tmp_path):
    with pytest.raises(TypeError, match="client: expected a dask.distributed.Client"):
        hilite.run("eccentricity", tmp_path / "x", client=object())
    with pytest.raises(hilite.InputError, match="chunk_size: expected 1 to 1000000"):
        hilite.run("eccentricity", tmp_path / "x", client=object(), chunk_size=0)
    with pytest.raises(hilite.InputError, match="chunk_size: only with client="):
        hilite.run("eccentricity", tmp_path / "x", chunk_size=4)
    assert not (tmp_path / "x").exists()
