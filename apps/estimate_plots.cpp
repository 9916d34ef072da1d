#include "apps/estimate_plots.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "io/measurement_stream.h"

namespace slipgraph {

void AddEstimatePlots(const DriveLog& log, const std::vector<NamedEstimates>& runs,
                      HtmlReport* html) {
  std::vector<std::pair<double, double>> shaded;
  for (const Event& e : log.events) shaded.emplace_back(e.t_start, e.t_end);
  Plot v{"body velocity v_bx and the driven wheels' mean rim speed r w", "m/s", {}, shaded};
  Plot a{"disturbance a_dist", "m/s^2", {}, shaded};
  Plot slip{
      "mean driven slip (EKF: its EMA; clipped to [-1, 2]) and immobilized flags", "-", {}, shaded};
  PlotSeries rim = NewSeries("wheels r w", "#9467bd", true);
  for (const WheelSample& w : log.wheels) {
    const SideSpeeds s = DrivenSideSpeeds(w, log.vehicle.type);
    rim.t.push_back(w.t);
    rim.y.push_back(0.5 * log.vehicle.wheel_radius_m * (s.left_radps + s.right_radps));
  }
  v.series.push_back(rim);
  if (!log.truth.empty()) {
    PlotSeries tv = NewSeries("truth", "#000000"), ta = tv, ts = tv;
    for (const TruthSample& s : log.truth) {
      tv.t.push_back(s.t);
      tv.y.push_back(s.vx);
      ta.t.push_back(s.t);
      ta.y.push_back(s.a_dist);
      double sum = 0.0;
      int count = 0;
      for (double value : s.slip) {
        if (std::isfinite(value)) sum += value, ++count;
      }
      ts.t.push_back(s.t);
      ts.y.push_back(count > 0 ? std::clamp(sum / count, -1.0, 2.0) : std::nan(""));
    }
    v.series.push_back(tv);
    a.series.push_back(ta);
    slip.series.push_back(ts);
  }
  for (size_t r = 0; r < runs.size(); ++r) {
    const bool last = r + 1 == runs.size();
    PlotSeries sv = NewSeries(runs[r].name, runs[r].color, !last);
    PlotSeries sa = sv, ss = sv,
               flag = NewSeries(runs[r].name + " immobilized", runs[r].color, true);
    for (const WardEstimate& e : *runs[r].estimates) {
      sv.t.push_back(e.t);
      sv.y.push_back(e.x[ward::kVbx]);
      sa.t.push_back(e.t);
      sa.y.push_back(e.x[ward::kAdist]);
      ss.t.push_back(e.t);
      // Slip at walking pace and below is encoder noise over a tiny speed: clipped for display.
      ss.y.push_back(std::clamp(e.slip.slip_ema, -1.0, 2.0));
      flag.t.push_back(e.t);
      flag.y.push_back(e.slip.immobilized ? 1.1 + 0.05 * static_cast<double>(r) : std::nan(""));
      if (last) {
        sv.sd.push_back(e.sd[ward::kVbx]);
        sa.sd.push_back(e.sd[ward::kAdist]);
      }
    }
    v.series.push_back(sv);
    a.series.push_back(sa);
    slip.series.push_back(ss);
    slip.series.push_back(flag);
  }
  html->Figure(v);
  html->Figure(a);
  html->Figure(slip);
}

}  // namespace slipgraph
