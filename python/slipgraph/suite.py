"""Many logs at once, on one machine or a Dask cluster: each log read, estimated and scored
against its truth on a worker, the records gathered here.

    from distributed import Client
    from slipgraph.suite import run_suite
    records = run_suite("suite_dir", estimator="smooth", client=Client("scheduler:8786"))

or from a shell, on a local cluster of two worker processes:

    python3 -m slipgraph.suite SUITE_DIR --workers 2 --json records.json

A log that fails (a bad file, a solver error, a worker lost) is a record with ok False and its
error, not the end of the suite; the command exits 1 when one did. The workers need the slipgraph package on their path, and the logs at the same
paths (a shared file system), as a Slurm or Dask-jobqueue cluster has them.
"""

import argparse
import json
import os
import sys
import time
from pathlib import Path
from typing import Iterable, List, Optional, Union

ESTIMATORS = ("filter", "smooth")


def list_logs(path: Union[str, Path]) -> List[str]:
    """The logs at `path`: itself when it is a log (has vehicle.yaml), else its sub-directories
    that are logs, sorted: the CLI's list. A directory without one is an InputError."""
    from . import _core

    return _core.list_logs(str(path))


def run_log(path: str, estimator: str = "smooth", model: Optional[str] = None,
            use_gps: bool = True, out_dir: Optional[str] = None) -> dict:
    """One log: read it, run the estimator, score the estimates against the log's truth when it
    has one, write them to out_dir/<log>.csv when asked. Never raises: a failure is a record."""
    import slipgraph  # on the worker

    record = {"log": path, "estimator": estimator, "model": model, "use_gps": use_gps,
              "version": slipgraph.__version__, "ok": False, "error": None}
    start = time.perf_counter()
    try:
        if estimator not in ESTIMATORS:
            raise ValueError(f"estimator '{estimator}': one of {', '.join(ESTIMATORS)}")
        log = slipgraph.read_log(path)
        run = getattr(slipgraph, estimator)(log, model=model, use_gps=use_gps)
        record["trusted"] = run.trusted
        record["trust_warnings"] = run.trust_warnings
        record["used_fallback"] = run.used_fallback
        if out_dir is not None:
            os.makedirs(out_dir, exist_ok=True)
            record["estimates"] = str(Path(out_dir) / (Path(path).name + ".csv"))
            slipgraph.write_estimates(run, record["estimates"])
        record["evaluation"] = slipgraph.evaluate(log, run) if log.has_truth else None
        record["ok"] = True
    except Exception as error:  # noqa: BLE001: every failure is the log's record
        record["error"] = f"{type(error).__name__}: {error}"
    record["seconds"] = time.perf_counter() - start
    return record


def run_suite(logs: Union[str, Path, Iterable[str]], estimator: str = "smooth",
              model: Optional[str] = None, use_gps: bool = True,
              out_dir: Optional[str] = None, client=None) -> List[dict]:
    """run_log over a suite directory or a list of logs, in the logs' order: on the Dask
    client's workers (one task per log), or here one after another without a client."""
    paths = list_logs(logs) if isinstance(logs, (str, Path)) else [str(p) for p in logs]
    if client is None:
        return [run_log(p, estimator, model, use_gps, out_dir) for p in paths]
    futures = client.map(run_log, paths, estimator=estimator, model=model, use_gps=use_gps,
                         out_dir=out_dir, pure=False)
    records = []
    for path, future in zip(paths, futures):
        try:
            records.append(future.result())
        except Exception as error:  # noqa: BLE001: a worker lost (killed, out of memory)
            records.append({"log": path, "estimator": estimator, "model": model,
                            "use_gps": use_gps, "ok": False,
                            "error": f"the task failed: {type(error).__name__}: {error}"})
    return records


def summary(records: List[dict]) -> str:
    """Lines for a terminal: the failures with their errors, the untrusted, the pooled
    velocity RMSE and false-alarm share over the logs with truth."""
    failed = [r for r in records if not r["ok"]]
    scored = [r for r in records if r["ok"] and r.get("evaluation")
              and r["evaluation"]["samples"] > 0 and r["evaluation"]["velocity_rmse"] is not None]
    lines = [f"{len(records)} log(s): {len(records) - len(failed)} ran, {len(failed)} failed"]
    lines += [f"  failed: {r['log']}: {r['error']}" for r in failed]
    lines += [f"  not trusted: {r['log']}" for r in records if r["ok"] and not r.get("trusted")]
    if scored:
        samples = sum(r["evaluation"]["samples"] for r in scored)
        rmse = (sum(r["evaluation"]["velocity_rmse"] ** 2 * r["evaluation"]["samples"]
                    for r in scored) / samples) ** 0.5
        false = sum(r["evaluation"]["false_immobilized_samples"] for r in scored)
        lines.append(f"  against truth ({len(scored)} logs): velocity RMSE {rmse:.4f} m/s, "
                     f"false immobilized {100.0 * false / samples:.2f} % of samples")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m slipgraph.suite", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("suite", help="a suite directory (one log per sub-directory) or a log")
    parser.add_argument("--estimator", choices=ESTIMATORS, default="smooth")
    parser.add_argument("--model", help="model YAML over each vehicle's nominal model")
    parser.add_argument("--no-gps", action="store_true", help="leave GNSS out")
    parser.add_argument("--out", help="write each log's estimates to OUT/<log>.csv")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--scheduler", help="a running Dask scheduler's address (host:port)")
    where.add_argument("--workers", type=int, default=0,
                       help="a local Dask cluster of this many single-threaded worker processes "
                            "(0: no Dask, one log after another here)")
    parser.add_argument("--json", help="write the records as a JSON list to this file")
    args = parser.parse_args(argv)
    cluster = client = None
    if args.scheduler or args.workers > 0:
        from distributed import Client, LocalCluster

        if args.scheduler:
            client = Client(args.scheduler)
        else:
            cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1,
                                   processes=True, dashboard_address=None)
            client = Client(cluster)
    try:
        records = run_suite(args.suite, args.estimator, args.model, not args.no_gps, args.out,
                            client)
    finally:
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()
    if args.json:
        Path(args.json).write_text(json.dumps(records, indent=2) + "\n")
    print(summary(records))
    return 0 if all(r["ok"] for r in records) else 1


if __name__ == "__main__":
    sys.exit(main())
