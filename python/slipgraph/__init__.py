"""slipgraph from Python: wheel slip, immobilization and sinkage estimation for ground robots.

Read a drive log, run the EKF front end or the batch smoother, diagnose the model, identify a
robot's model from its logs, score estimates against truth. Streams and estimates are dicts of
numpy arrays (``pandas.DataFrame(columns)`` makes a table of them); the diagnosis, the
identification and the evaluation are the dicts the CLI writes as JSON.

    import slipgraph
    log = slipgraph.read_log("data/sample")
    ekf = slipgraph.filter(log)
    smoothed = slipgraph.smooth(log)
    print(ekf.frame()[["t", "v_bx", "sd_v_bx"]].head())
    print(slipgraph.evaluate(log, smoothed)["velocity_rmse"])
"""

import json as _json
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence

import numpy as _np

from . import _core
from ._core import InputError, Log

__version__ = _core.__version__

__all__ = [
    "InputError",
    "Log",
    "Run",
    "read_log",
    "filter",
    "smooth",
    "online",
    "diagnose",
    "identify",
    "score_model",
    "evaluate",
    "write_estimates",
    "effects",
]


@dataclass
class Run:
    """An estimator's run over one log.

    columns: the estimate file's columns (docs/estimate-file.md) as numpy arrays, ``suspect``
    last; report: what the CLI prints about the run; trusted and trust_warnings: the check of
    the estimates against the log's own wheels and GNSS; used_fallback: the smoother failed and
    the estimates are the front end's. Smoother runs also give converged, final_cost, iterations;
    online runs update_ms_p50, update_ms_p99 and rejected_updates.
    """

    columns: Dict[str, _np.ndarray]
    report: str
    trusted: bool
    trust_warnings: List[str] = field(default_factory=list)
    used_fallback: bool = False
    converged: Optional[bool] = None
    final_cost: Optional[float] = None
    iterations: Optional[int] = None
    update_ms_p50: Optional[float] = None
    update_ms_p99: Optional[float] = None
    rejected_updates: Optional[int] = None

    def __getitem__(self, name: str) -> _np.ndarray:
        return self.columns[name]

    def frame(self):
        """The columns as a pandas DataFrame (pandas imported only here)."""
        import pandas

        return pandas.DataFrame(self.columns)


def _model(model) -> str:
    return "" if model is None else str(model)


def _log(log) -> Log:
    """A Log as it is, a path read as one."""
    return log if isinstance(log, Log) else read_log(log)


def read_log(path, skip_bad: bool = False, max_bad_fraction: float = 0.01) -> Log:
    """A drive log directory (shared/log-format.md). A bad row is an InputError naming file,
    line and column; skip_bad drops bad rows (listed in ``log.warnings``) up to
    max_bad_fraction of a file."""
    return _core.read_log(str(path), skip_bad, max_bad_fraction)


def filter(log, model=None, use_gps: bool = True, single_law: bool = False,
           gnss_fading: bool = True, disturbance_modes: bool = False) -> Run:
    """The streaming EKF front end (Ward & Iagnemma), as ``slipgraph filter``; model: a model
    YAML over the vehicle's nominal one."""
    return Run(**_core.filter(_log(log), _model(model), use_gps, single_law, gnss_fading,
                              disturbance_modes))


def smooth(log, model=None, use_gps: bool = True, stiffness_sd: Optional[float] = None,
           threads: int = 1) -> Run:
    """The batch smoother over the whole log, started from the EKF, as ``slipgraph smooth``
    (stiffness_sd: its prior on the tire law's slip stiffness, the CLI's default when None)."""
    kwargs = {} if stiffness_sd is None else {"stiffness_sd": stiffness_sd}
    return Run(**_core.smooth(_log(log), _model(model), use_gps, threads=threads, **kwargs))


def online(log, model=None, use_gps: bool = True, **window) -> Run:
    """The EKF at every sample and the sliding-window smoother behind it, as ``slipgraph
    online``: the window's estimates with the front end's beside them (ekf_* columns), lag_s and
    from_filter; window: window_s, update_every, iterations, stiffness_sd, covariance,
    reject_distance (the CLI's defaults). The run also gives update_ms_p50 and update_ms_p99, the
    window's latency, and rejected_updates, its solves rejected for leaving the front end."""
    result = _core.online(_log(log), _model(model), use_gps, **window)
    extra = {k: result.pop(k) for k in ("update_ms_p50", "update_ms_p99", "rejected_updates")}
    run = Run(**result)
    run.update_ms_p50, run.update_ms_p99 = extra["update_ms_p50"], extra["update_ms_p99"]
    run.rejected_updates = extra["rejected_updates"]
    return run


def diagnose(log, model=None, use_gps: bool = True,
             with_effects: Sequence[str] = (), threads: int = 2, parameters: bool = False) -> dict:
    """The model workbench, as ``slipgraph diagnose --json``: streams, failures, candidates;
    with_effects adds those effects and diagnoses again (the result's "after"); parameters also
    tests whether a parameter of the model is off (``--parameters``). "series" holds
    the series behind the statistics, as ``diagnose --series`` writes them: per stream the
    smoother's normalized residuals ("residual_gnss.csv": t, normalized, sd) and the front
    end's normalized innovations ("innovation_gnss.csv": t, normalized), as arrays."""
    text, series = _core.diagnose(_log(log), _model(model), use_gps, list(with_effects), threads,
                                  parameters)
    result = _json.loads(text)
    result["series"] = series
    return result


def identify(logs: Sequence, model=None, use_gps: bool = True, fit_radius: bool = False,
             threads: int = 1) -> dict:
    """The robot's model fitted on the logs (all of each; ``log.slice`` holds part out), as
    ``slipgraph identify --train 1 --json``; "model_yaml" is the model file's text."""
    return _json.loads(
        _core.identify([_log(x) for x in logs], _model(model), use_gps, fit_radius, threads))


def score_model(log, model=None, use_gps: bool = True) -> dict:
    """How a model does on a log: GNSS NIS, flagged fraction, and against truth when it has
    one (what ``identify`` reports on held-out data)."""
    return _json.loads(_core.score_model(_log(log), _model(model), use_gps))


def evaluate(log, estimates) -> dict:
    """Estimates (a Run, or a dict or DataFrame with t, v_bx, sd_v_bx, a_dist, immobilized)
    scored against the log's truth, as ``slipgraph evaluate --json``.

    Every function that takes a log also takes a log directory's path."""
    columns = estimates.columns if isinstance(estimates, Run) else estimates
    arrays = {str(k): _np.asarray(columns[k], dtype=float) for k in columns.keys()}
    return _json.loads(_core.evaluate(_log(log), arrays))


def write_estimates(estimates, path) -> None:
    """Estimates (a Run, or a dict or DataFrame of columns) as the CLI writes an estimate file:
    the same header and the same numbers, byte for byte."""
    columns = estimates.columns if isinstance(estimates, Run) else estimates
    _core.write_table({str(k): _np.asarray(columns[k], dtype=float) for k in columns.keys()},
                      str(path))


def effects() -> List[dict]:
    """The catalogue of physical effects: name, default value and unit, physics, evidence,
    whether it is a diagnose candidate and whether ``with_effects`` can add it."""
    return _json.loads(_core.effects())
