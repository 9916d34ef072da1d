"""--json on every subcommand, with one meaning: one JSON object on stdout (the text on stderr)
with no FILE or '-', in FILE otherwise; each carries the version, the subcommand and its options.
Run from ctest (cli.pytest) with SLIPGRAPH_CLI, SLIPGRAPH_SOURCE_DIR and, for the
import, SLIPGRAPH_TINY_BAG (a bag the suite writes)."""

import json
import os
import subprocess
from pathlib import Path

import pytest

CLI = os.environ["SLIPGRAPH_CLI"]
SOURCE = Path(os.environ["SLIPGRAPH_SOURCE_DIR"])
SAMPLE = SOURCE / "data" / "sample"


def run_json(*args):
    """The subcommand's stdout as JSON (it must be one document), and its stderr."""
    done = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    record = result["slipgraph"]
    assert record["version"] and record["command"] == str(args[0])
    return result, done.stderr


@pytest.fixture(scope="module")
def estimates(tmp_path_factory):
    path = tmp_path_factory.mktemp("json") / "ekf.csv"
    result, _ = run_json("filter", SAMPLE, "--out", path, "--json")
    return path, result


def test_filter_lists_each_logs_estimates_model_trust_and_evaluation(estimates):
    path, result = estimates
    (log,) = result["logs"]
    assert log["estimates"] == str(path) and log["trusted"] and result["untrusted"] == 0
    assert log["model"]["file"] is None and len(log["model"]["fingerprint"]) == 16
    assert 0 < log["evaluation"]["velocity_rmse"] < 0.05
    assert "streams used" in log["report"]
    assert result["slipgraph"]["options"]["--out"] == str(path)


def test_a_file_takes_the_json_and_the_text_stays_on_stdout(tmp_path):
    done = subprocess.run([CLI, "filter", SAMPLE, "--out", tmp_path / "f.csv",
                           f"--json={tmp_path / 'f.json'}"], capture_output=True, text=True)
    assert done.returncode == 0 and "against truth" in done.stdout
    assert json.loads((tmp_path / "f.json").read_text())["logs"][0]["trusted"]


def test_a_model_file_changes_the_fingerprint(tmp_path, estimates):
    _, nominal = estimates
    model = tmp_path / "model.yaml"
    model.write_text("tire:\n  C1: 0.6\n")
    result, _ = run_json("filter", SAMPLE, "--out", tmp_path / "f.csv", "--model", model,
                         "--json")
    record = result["logs"][0]["model"]
    assert record["file"] == str(model)
    assert record["fingerprint"] != nominal["logs"][0]["model"]["fingerprint"]


@pytest.mark.parametrize("command", ["smooth", "online"])
def test_the_smoothers(command, tmp_path):
    result, _ = run_json(command, SAMPLE, "--out", tmp_path / "s.csv", "--json")
    assert result["logs"][0]["evaluation"]["velocity_rmse"] < 0.05


def test_evaluate(estimates):
    path, filtered = estimates
    result, text = run_json("evaluate", SAMPLE, path, "--json", "-")
    assert result["velocity_rmse"] == filtered["logs"][0]["evaluation"]["velocity_rmse"]
    assert "detected" in text


def test_info_and_effects():
    info, _ = run_json("info", SAMPLE, "--json")
    assert [s["name"] for s in info["streams"]][:2] == ["imu", "wheels"]
    assert info["vehicle"]["wheels"] == ["left", "right"]
    effects, text = run_json("effects", "--json")
    names = [e["name"] for e in effects["effects"]]
    assert "clock_offset" in names and "clock_offset" in text
    assert any(e["can_add"] for e in effects["effects"])


def test_simulate_compare_and_sinkage(tmp_path):
    sim, _ = run_json("simulate", "--scenario", "wilcox/1.0", "--out", tmp_path / "w", "--json")
    (log,) = sim["logs"]
    assert Path(log["log"]).is_dir() and log["imu_samples"] > 0
    sinkage, _ = run_json("sinkage", log["log"], "--out", tmp_path / "sk", "--json")
    assert sinkage["odometry_error_fraction"] < 0.1 and Path(sinkage["cycles"]).is_file()
    compare, _ = run_json("compare", SAMPLE, "--report", tmp_path / "c.html", "--no-plots",
                          "--json")
    assert [t["estimator"] for t in compare["total"]] == ["EKF", "window", "batch"]
    assert compare["logs"][0]["runs"][2]["evaluation"]["velocity_rmse"] < 0.05


def test_diagnose_writes_its_series_and_identify_its_model(tmp_path):
    diagnosis, _ = run_json("diagnose", "--series", tmp_path / "series", "--json")
    assert diagnosis["explained"]
    files = {Path(p).name for p in diagnosis["series"]}
    assert {"residual_gnss.csv", "innovation_gnss.csv"} <= files
    with open(tmp_path / "series" / "residual_gnss.csv") as f:
        header, *rows = f.read().splitlines()
    assert header == "t,normalized,sd"
    assert len(rows) == diagnosis["streams"]["gnss"]["samples"]
    identified, _ = run_json("identify", SAMPLE, "--train", "1", "--out", tmp_path / "m.yaml",
                             "--json")
    assert identified["converged"] and identified["model"]["file"] is None


def test_import_list():
    bag = os.environ.get("SLIPGRAPH_TINY_BAG")
    if not bag or not Path(bag).exists():
        pytest.skip("no tiny bag")
    listed, _ = run_json("import", "--list", bag, "--json")
    assert any(e["name"] == "/imu/data" and e["messages"] == 100 for e in listed["entries"])
