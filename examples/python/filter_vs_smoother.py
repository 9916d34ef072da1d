"""Filter against smoother on one log, from Python: velocity with its 2-sd band, the disturbance
and the immobilized flags, against the log's truth where it has one, saved as a PNG.

Usage: python3 filter_vs_smoother.py [LOG] [OUT.png]
(default: the bundled sample and ./filter_vs_smoother.png)
With the package on the path: PYTHONPATH=build/python (a build tree) or an installed module.
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files, not windows: works without a display
import matplotlib.pyplot as plt

import slipgraph

log_path = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).parents[2] / "data/sample"
out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path("filter_vs_smoother.png")

log = slipgraph.read_log(log_path)
runs = {"EKF": slipgraph.filter(log), "smoother": slipgraph.smooth(log)}
truth = log.stream("truth") if log.has_truth else None

fig, (ax_v, ax_d, ax_f) = plt.subplots(3, 1, sharex=True, figsize=(9, 8),
                                       gridspec_kw={"height_ratios": [3, 2, 1]})
for (name, run), colour in zip(runs.items(), ["tab:orange", "tab:blue"]):
    est = run.frame()
    ax_v.plot(est.t, est.v_bx, color=colour, label=name)
    ax_v.fill_between(est.t, est.v_bx - 2 * est.sd_v_bx, est.v_bx + 2 * est.sd_v_bx,
                      color=colour, alpha=0.2, linewidth=0)
    ax_d.plot(est.t, est.a_dist, color=colour, label=name)
    ax_f.step(est.t, est.immobilized + (0.05 if name == "EKF" else 0.0), where="post",
              color=colour, label=name)
    if truth is not None:
        score = slipgraph.evaluate(log, run)
        print(f"{name:9s} velocity RMSE {score['velocity_rmse']:.4f} m/s, "
              f"false immobilized {100 * score['false_immobilized_fraction']:.2f} %, "
              f"trusted {run.trusted}")
    else:
        print(f"{name:9s} trusted {run.trusted}")
if truth is not None:
    ax_v.plot(truth["t"], truth["vx"], "k--", linewidth=1, label="truth")
    ax_d.plot(truth["t"], truth["a_dist"], "k--", linewidth=1, label="truth")
    ax_f.step(truth["t"], truth["immobilized"] - 0.05, "k--", where="post", linewidth=1,
              label="truth")
ax_v.set_ylabel("v_bx, m/s (2-sd band)")
ax_d.set_ylabel("a_dist, m/s²")
ax_f.set_ylabel("immobilized")
ax_f.set_xlabel("t, s")
ax_v.legend(loc="upper right")
ax_v.set_title(f"{log.vehicle['name']}: {log_path.name}")
fig.tight_layout()
fig.savefig(out, dpi=110)
print(f"wrote {out}")
