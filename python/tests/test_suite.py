"""slipgraph.suite: a suite through a Dask LocalCluster of 2 workers gives the CLI's evaluations,
and a bad log is a failed record, not the end of the suite."""

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

from slipgraph import suite

CLI = os.environ.get("SLIPGRAPH_CLI", "slipgraph")


@pytest.fixture(scope="module")
def good(tmp_path_factory):
    """ward21 (seed 1) runs 1-6."""
    root = tmp_path_factory.mktemp("suite")
    subprocess.run([CLI, "simulate", "--scenario", "ward21", "--seed", "1", "--out",
                    root / "ward21"], check=True, capture_output=True)
    for k in range(1, 7):
        shutil.copytree(root / "ward21" / f"run_{k:02d}", root / "good" / f"run_{k:02d}")
    return root / "good"


@pytest.fixture(scope="module")
def logs(good):
    """The good runs and a copy of run 1 with a bad IMU row."""
    logs = good.parent / "logs"
    shutil.copytree(good, logs)
    bad = logs / "run_00_bad"
    shutil.copytree(logs / "run_01", bad)
    lines = (bad / "imu.csv").read_text().splitlines()
    lines[10] = lines[10].replace(",", ",x", 1)
    (bad / "imu.csv").write_text("\n".join(lines) + "\n")
    return logs


def test_two_workers_give_the_clis_evaluations_and_keep_going(good, logs, tmp_path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        records = suite.run_suite(logs, estimator="filter", out_dir=str(tmp_path / "est"),
                                  client=client)
    assert [Path(r["log"]).name for r in records] == \
        ["run_00_bad"] + [f"run_{k:02d}" for k in range(1, 7)]
    bad, ran = records[0], records[1:]
    assert not bad["ok"] and "imu.csv:11" in bad["error"]
    assert all(r["ok"] and r["trusted"] for r in ran)
    assert "failed: " + str(logs / "run_00_bad") in suite.summary(records)

    subprocess.run([CLI, "filter", good, "--out", tmp_path / "cli"], check=True,
                   capture_output=True)
    cli = json.loads(subprocess.run([CLI, "evaluate", good, tmp_path / "cli", "--json"],
                                    check=True, capture_output=True, text=True).stdout)
    by_log = {Path(run["name"]).name: run for run in cli["runs"]}
    for record in ran:
        name = Path(record["log"]).name
        assert record["evaluation"]["velocity_rmse"] == by_log[name]["velocity_rmse"]
        assert record["evaluation"]["false_immobilized_samples"] == \
            by_log[name]["false_immobilized_samples"]
        assert Path(record["estimates"]).read_bytes() == \
            (tmp_path / "cli" / f"{name}.csv").read_bytes()


def test_without_a_client_the_same_records_in_order(logs):
    here = suite.run_suite([str(logs / "run_02"), str(logs / "run_01")], estimator="filter")
    assert [Path(r["log"]).name for r in here] == ["run_02", "run_01"]
    assert all(r["ok"] for r in here)
    with pytest.raises(ValueError, match="vehicle.yaml"):
        suite.list_logs(logs.parent / "nothing_here")


def test_the_command_line_names_what_failed(logs, tmp_path, capsys):
    status = suite.main([str(logs), "--estimator", "filter", "--json",
                         str(tmp_path / "records.json")])
    out = capsys.readouterr().out
    assert status == 1 and "1 failed" in out and "run_00_bad" in out
    assert len(json.loads((tmp_path / "records.json").read_text())) == 7
