"""A suite of logs through slipgraph.suite on a Dask LocalCluster of 1 and of 2 worker
processes, side by side in one run: wall time of each, the ratio, and whether the two gave the
same evaluations (they must: one task per log, each log's run is deterministic).

Usage: PYTHONPATH=build/python python3 bench/dask_suite_bench.py [--logs 40] [--estimator smooth]
The logs are ward21 runs of seeds 1, 2, ... (build/apps/slipgraph simulate), in a temp directory.
"""

import argparse
import os
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

from distributed import Client, LocalCluster

from slipgraph import suite


def make_suite(cli, root, count):
    logs = root / "logs"
    logs.mkdir()
    seed = 1
    while len(list(logs.iterdir())) < count:
        out = root / f"ward21_{seed}"
        subprocess.run([cli, "simulate", "--scenario", "ward21", "--seed", str(seed), "--out",
                        out], check=True, capture_output=True)
        for run in sorted(out.iterdir()):
            if len(list(logs.iterdir())) < count:
                shutil.move(str(run), logs / f"s{seed}_{run.name}")
        seed += 1
    return logs


def timed(logs, estimator, workers):
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        client.run(lambda: __import__("slipgraph"))  # the module loaded before the clock
        start = time.perf_counter()
        records = suite.run_suite(logs, estimator=estimator, client=client)
        return time.perf_counter() - start, records


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--logs", type=int, default=40)
    parser.add_argument("--estimator", choices=suite.ESTIMATORS, default="smooth")
    parser.add_argument("--cli", default=str(Path(__file__).parents[1] / "build/apps/slipgraph"))
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        logs = make_suite(args.cli, Path(tmp), args.logs)
        one_s, one = timed(logs, args.estimator, 1)
        two_s, two = timed(logs, args.estimator, 2)
    strip = [{k: v for k, v in r.items() if k != "seconds"} for r in one]
    same = strip == [{k: v for k, v in r.items() if k != "seconds"} for r in two]
    failed = sum(not r["ok"] for r in one + two)
    print(f"{args.logs} logs, {args.estimator}, {os.cpu_count()} cores: 1 worker {one_s:.1f} s, "
          f"2 workers {two_s:.1f} s, speed-up {one_s / two_s:.2f}x; "
          f"same evaluations: {same}; failed runs: {failed}")
    print(suite.summary(two))


if __name__ == "__main__":
    main()
