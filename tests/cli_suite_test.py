"""Suites through the program: --jobs runs logs at once with the same outputs as one at a time;
--keep-going reports a bad log and runs the rest (exit status 4); without it the first bad log
ends the run (exit status 2, the error naming file, line and column)."""

import json
import os
import shutil
import subprocess

import pytest

CLI = os.environ["SLIPGRAPH_CLI"]


@pytest.fixture(scope="module")
def suite(tmp_path_factory):
    """ward21 (seed 3) runs 1-4 and, third by name, a copy of run 1 whose wheels.csv has a bad
    cell."""
    root = tmp_path_factory.mktemp("suite")
    subprocess.run([CLI, "simulate", "--scenario", "ward21", "--seed", "3", "--out",
                    root / "ward21"], check=True, capture_output=True)
    logs = root / "logs"
    for k in range(1, 5):
        shutil.copytree(root / "ward21" / f"run_{k:02d}", logs / f"run_{k:02d}")
    shutil.copytree(logs / "run_01", logs / "run_02_bad")  # between run_02 and run_03
    lines = (logs / "run_02_bad" / "wheels.csv").read_text().splitlines()
    lines[4] = lines[4].replace(",", ",x", 1)
    (logs / "run_02_bad" / "wheels.csv").write_text("\n".join(lines) + "\n")
    return logs


def run(*args):
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)


def test_keep_going_runs_the_rest_and_lists_the_failure(suite, tmp_path):
    done = run("filter", suite, "--out", tmp_path / "two", "--jobs", "2", "--keep-going",
               "--json", tmp_path / "two.json")
    assert done.returncode == 4, done.stderr
    assert "filter: 1 of 5 log(s) failed:" in done.stderr
    assert "run_02_bad/wheels.csv:5: column 'left'" in done.stderr
    written = sorted(p.name for p in (tmp_path / "two").iterdir())
    assert written == [f"run_{k:02d}.csv" for k in range(1, 5)]
    records = json.loads((tmp_path / "two.json").read_text())
    assert records["failed"] == 1 and "wheels.csv:5" in records["logs"][2]["error"]
    assert [r.get("trusted") for r in records["logs"]] == [True, True, None, True, True]
    # The suite's text reads in its order whatever the threads did.
    runs = [line.split()[0] for line in done.stdout.splitlines() if "against truth" in line]
    assert runs == [str(suite / f"run_{k:02d}") for k in range(1, 5)]

    good = tmp_path / "good"
    for k in range(1, 5):
        shutil.copytree(suite / f"run_{k:02d}", good / f"run_{k:02d}")
    one = run("filter", good, "--out", tmp_path / "one")
    assert one.returncode == 0, one.stderr
    for k in range(1, 5):
        name = f"run_{k:02d}.csv"
        assert (tmp_path / "one" / name).read_bytes() == (tmp_path / "two" / name).read_bytes()


def test_json_on_stdout_is_one_document_with_jobs(suite):
    done = run("diagnose", suite, "--jobs", "2", "--keep-going", "--threads", "1", "--json")
    assert done.returncode == 4, done.stderr
    result = json.loads(done.stdout)
    assert result["total"]["logs"] == 5 and result["total"]["failed"] == 1
    assert [log["log"] for log in result["logs"]] == sorted(log["log"] for log in result["logs"])
    assert "diagnose: 1 of 5 log(s) failed:" in done.stderr


def test_json_before_the_log_is_an_error_not_a_run_on_the_sample(suite):
    done = run("filter", "--json", suite / "run_01")
    assert done.returncode != 0 and "is a directory" in done.stderr


def test_without_keep_going_the_first_bad_log_ends_the_run(tmp_path_factory, suite):
    logs = tmp_path_factory.mktemp("bad")
    shutil.copytree(suite / "run_01", logs / "run_00_bad")
    shutil.copytree(suite / "run_02", logs / "run_02")
    (logs / "run_00_bad" / "imu.csv").write_text("t,ax\n")
    done = run("filter", logs, "--out", logs.parent / "out", "--jobs", "2")
    assert done.returncode == 2 and "run_00_bad/imu.csv" in done.stderr
    assert "run_02 against truth" not in done.stdout
