#include "apps/diagnosis_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "apps/estimate_plots.h"
#include "workbench/imu_calibration.h"

namespace slipgraph {
namespace {

// The verdict lines: significant candidates not offered (implausible), then the missing
// effect, or why none explains the misfit, or that the model is consistent.
std::string Verdict(const Diagnosis& d) {
  std::ostringstream out;
  for (const CandidateScore& c : d.candidates) {
    if (c.significant && !c.implausible.empty()) {
      out << "  " << c.effect << " is significant but " << c.implausible
          << ": not offered as the fix\n";
    }
  }
  const CandidateScore* best = BestExplanation(d.candidates);
  if (best != nullptr && d.explained) {
    out << "  most likely missing: " << best->effect << " (" << best->magnitude << " +- "
        << best->magnitude_sd << ")\n";
  } else if (!d.explained) {
    out << (best != nullptr ? "  no candidate explains it: the best, " + best->effect +
                                  ", leaves a significant force along the path\n"
                            : std::string("  no candidate explains it: the failures above are "
                                          "outside the catalogue's tests\n"));
  } else {
    const bool any = std::any_of(d.candidates.begin(), d.candidates.end(),
                                 [](const CandidateScore& c) { return c.significant; });
    out << (any ? "  no plausible candidate is significant" : "  no candidate is significant")
        << ", and the model is consistent with the measurements\n";
  }
  return out.str();
}

}  // namespace

void PrintDiagnosis(const Diagnosis& d, std::ostream& out) {
  out << "diagnose: " << d.log << " (model effects: ";
  if (d.model_effects.empty()) out << "none";
  for (size_t i = 0; i < d.model_effects.size(); ++i) out << (i ? ", " : "") << d.model_effects[i];
  out << ")\n";
  for (const std::string& note : d.notes) out << "  note: " << note << "\n";
  out << "  " << DescribeTrust(d.trust);
  for (const EffectEstimate& e : d.fitted_effects) {
    out << "  fitted " << e.name << " = " << e.value << " +- " << e.sd << "\n";
  }
  for (const EffectEstimate& e : d.corrected) {
    out << "  corrected in the measurements: " << e.name << " = " << e.value << " +- " << e.sd
        << "\n";
    for (const ImuCalibrationEffect& calibration : ImuCalibrationEffects()) {
      if (e.name != calibration.effect) continue;
      out << "    (for every estimator, the front end too: add it to the model file's "
             "`calibration: {"
          << calibration.key << ": " << e.value << "}` (" << calibration.unit
          << "), on top of any it has)\n";
    }
  }
  out << "  streams (normalized residuals):\n";
  out << "    stream          samples   rms    chi2 p    consistent  Ljung-Box Q  p        white\n";
  for (const StreamReport& s : d.streams) {
    char line[200];
    std::snprintf(line, sizeof(line), "    %-15s %7zu  %6.3f  %8.2g  %-10s  %11.1f  %8.2g %s\n",
                  s.name.c_str(), s.samples, s.rms, s.chi_square_p, s.consistent ? "yes" : "NO",
                  s.whiteness.q, s.whiteness.p_value, s.white ? "yes" : "NO");
    out << line;
  }
  out << "  filter consistency (EKF innovations, normalized):\n";
  out << "    measurement     updates  NIS mean  inside 95 %  Ljung-Box Q  p        white\n";
  for (const InnovationReport& f : d.filter) {
    char line[200];
    std::snprintf(line, sizeof(line), "    %-15s %7zu  %8.3f  %10.1f %%  %11.1f  %8.2g %s\n",
                  f.name.c_str(), f.updates, f.nis_mean, 100.0 * f.inside_95, f.whiteness.q,
                  f.whiteness.p_value, f.white ? "yes" : "NO");
    out << line;
  }
  for (const NoiseScaleFinding& f : d.noise_scales) {
    if (!f.significant) continue;
    char line[480];
    std::snprintf(
        line, sizeof(line),
        "  NOISE STATED TOO SMALL? %s%s: the ML noise sd is x%.3g the stated (NIS mean "
        "%.3g over %zu innovations, p %.2g): the stated sd is too small, or the model misses "
        "what this sensor sees (`slipgraph identify` estimates the sd from the signal "
        "alone); settle it before reading the effects below\n",
        f.key.c_str(), f.key == "measurement_noise.gps_sd_v" ? " (or the log's sd_v column)" : "",
        f.sd_scale(), f.nis_mean, f.updates, f.p_value);
    out << line;
  }
  out << "  where it fails (" << d.failures.size() << " segments):\n";
  for (const FailureSegment& f : d.failures) {
    char line[200];
    std::snprintf(line, sizeof(line),
                  "    %7.1f - %7.1f s  speed %.2f m/s  |pitch| %.3f rad  |yaw rate| %.2f rad/s  ",
                  f.t_start, f.t_end, f.speed_mps, f.abs_pitch_rad, f.abs_yaw_rate_radps);
    out << line;
    for (size_t i = 0; i < f.streams.size(); ++i) out << (i ? ", " : "") << f.streams[i];
    out << "\n";
  }
  out << "  candidate effects (robust score tests, Bonferroni-adjusted p; the best with a smoother "
         "term fitted: quasi-likelihood ratio):\n";
  for (const CandidateScore& c : d.candidates) {
    char line[240];
    std::snprintf(line, sizeof(line),
                  "    %-24s stat %8.1f (dof %d)  p %8.2g  %-3s  magnitude %.4g +- %.2g",
                  c.effect.c_str(), c.statistic, c.dof, c.p_value, c.significant ? "YES" : "no",
                  c.magnitude, c.magnitude_sd);
    out << line;
    if (std::isfinite(c.detectable)) {
      std::snprintf(line, sizeof(line), ", detectable above %.2g", c.detectable);
      out << line;
    }
    if (!c.where.empty()) out << "  (" << c.where << ")";
    out << "  [" << (c.added_as.empty() ? "cannot be added yet" : "added as " + c.added_as) << "]";
    if (!c.implausible.empty()) out << "\n      IMPLAUSIBLE: " << c.implausible;
    if (c.fitted) {
      std::snprintf(
          line, sizeof(line),
          "\n      fitted (likelihood ratio %.1f, dispersion %.2f); score test: stat %.1f, "
          "p %.2g, magnitude %.4g +- %.2g",
          c.likelihood_ratio, c.dispersion, c.score_statistic, c.score_p_value, c.score_magnitude,
          c.score_magnitude_sd);
      out << line;
    }
    out << "\n";
  }
  if (d.path_force.tested) {
    char line[240];
    std::snprintf(line, sizeof(line),
                  "  any force along the path (omnibus, %g m cells): X2 %.1f on %g dof, p %.2g",
                  d.path_force.metre, d.path_force.statistic, d.path_force.dof,
                  d.path_force.p_value);
    out << line;
    if (!d.path_force.after_effect.empty()) {
      std::snprintf(line, sizeof(line), "; left after %s: X2 %.1f on %g dof, p %.2g",
                    d.path_force.after_effect.c_str(), d.path_force.after_statistic,
                    d.path_force.after_dof, d.path_force.after_p_value);
      out << line;
    }
    out << "\n";
  }
  out << Verdict(d);
  if (d.truth.available) {
    out << "  against truth: velocity RMSE " << d.truth.velocity_rmse << " m/s, disturbance RMSE "
        << d.truth.disturbance_rmse << " m/s^2\n";
  }
}

void PrintComparison(const Diagnosis& before, const Diagnosis& after, std::ostream& out) {
  out << "before -> after adding";
  for (const std::string& e : after.model_effects) {
    if (std::find(before.model_effects.begin(), before.model_effects.end(), e) ==
        before.model_effects.end())
      out << " " << e;
  }
  for (size_t i = before.corrected.size(); i < after.corrected.size(); ++i) {
    out << " " << after.corrected[i].name << " (corrected)";
  }
  out << ":\n";
  if (before.truth.available && after.truth.available) {
    char line[200];
    std::snprintf(line, sizeof(line),
                  "  velocity RMSE %.4f -> %.4f m/s (%+.0f %%), disturbance RMSE %.3f -> %.3f\n",
                  before.truth.velocity_rmse, after.truth.velocity_rmse,
                  100.0 * (after.truth.velocity_rmse / before.truth.velocity_rmse - 1.0),
                  before.truth.disturbance_rmse, after.truth.disturbance_rmse);
    out << line;
  }
  for (size_t i = 0; i < before.streams.size() && i < after.streams.size(); ++i) {
    char line[200];
    std::snprintf(line, sizeof(line), "  %-15s rms %.3f -> %.3f   Ljung-Box Q %.0f -> %.0f\n",
                  before.streams[i].name.c_str(), before.streams[i].rms, after.streams[i].rms,
                  before.streams[i].whiteness.q, after.streams[i].whiteness.q);
    out << line;
  }
  out << "  failure segments " << before.failures.size() << " -> " << after.failures.size() << "\n";
  // Each added effect's own signature: what is left of it once it is in the model.
  for (const CandidateScore& b : before.candidates) {
    const bool added = std::find(after.model_effects.begin(), after.model_effects.end(),
                                 b.effect) != after.model_effects.end() ||
                       std::any_of(after.corrected.begin(), after.corrected.end(),
                                   [&](const EffectEstimate& e) { return e.name == b.effect; });
    if (!added) continue;
    const auto it = std::find_if(after.in_model.begin(), after.in_model.end(),
                                 [&](const CandidateScore& c) { return c.effect == b.effect; });
    if (it == after.in_model.end()) continue;
    const CandidateScore& left = *it;
    char line[240];
    if (left.dof == 0) {
      // A smoother term's score is zero at its own estimate: nothing left to test.
      std::snprintf(line, sizeof(line),
                    "  %s signature: statistic %.1f, magnitude seen in the residuals %.4g -> "
                    "estimated with the states\n",
                    b.effect.c_str(), b.statistic, b.magnitude);
    } else {
      std::snprintf(line, sizeof(line),
                    "  %s signature: statistic %.1f -> %.1f, magnitude seen in the residuals %.4g "
                    "-> %.4g +- %.2g\n",
                    b.effect.c_str(), b.statistic, left.statistic, b.magnitude, left.magnitude,
                    left.magnitude_sd);
    }
    out << line;
  }
}

namespace {

// A table cell: four significant digits.
std::string Figure(double value) {
  std::ostringstream s;
  s << std::setprecision(4) << value;
  return s.str();
}

void AddSection(const DriveLog& log, const Diagnosis& d, const std::string& heading,
                HtmlReport* report) {
  report->Heading(heading);
  report->Preformatted(Verdict(d));
  report->Heading("estimates: the front end's and the smoother's", 3);
  AddEstimatePlots(log,
                   {{"EKF", &d.solution.ekf.estimates, "#d62728"},
                    {"smoother", &d.solution.estimates, "#1f77b4"}},
                   report);
  std::vector<std::vector<std::string>> streams;
  for (const StreamReport& r : d.streams) {
    streams.push_back({r.name, std::to_string(r.samples), Figure(r.rms),
                       r.consistent ? "yes" : "no", Figure(r.whiteness.q), r.white ? "yes" : "no"});
  }
  report->Heading("measurements against the model", 3);
  report->Table({"stream", "samples", "rms (normalized)", "consistent", "Ljung-Box Q", "white"},
                streams);
  std::vector<std::pair<double, double>> shaded;
  for (const FailureSegment& f : d.failures) shaded.push_back({f.t_start, f.t_end});
  for (const StreamResiduals& s : d.residuals.streams) {
    Plot plot;
    plot.title = s.name + ": normalized residual (z - h(x)) / sd; failure segments shaded";
    plot.y_label = "r";
    plot.shaded = shaded;
    PlotSeries p = NewSeries(s.name, "#1f77b4");
    p.t = s.t, p.y = s.normalized, p.points = true;
    plot.series.push_back(p);
    report->Figure(plot);
  }
  Plot force;
  force.title = "force balance the model does not explain, u = a_x - f_tire(x) - c - b (m/s^2)";
  force.y_label = "m/s^2";
  force.shaded = shaded;
  PlotSeries u = NewSeries("u", "#1f77b4");
  for (const StateContext& c : d.residuals.states) {
    u.t.push_back(c.t), u.y.push_back(c.unexplained_force);
  }
  force.series.push_back(u);
  report->Figure(force);
  std::vector<std::vector<std::string>> rows;
  for (const CandidateScore& c : d.candidates) {
    rows.push_back(
        {c.effect, Figure(c.statistic), std::to_string(c.dof), Figure(c.p_value),
         c.significant ? "yes" : "no", Figure(c.magnitude), Figure(c.magnitude_sd),
         Figure(c.detectable), c.implausible.empty() ? "yes" : c.implausible,
         c.test + (c.where.empty() ? "" : " (" + c.where + ")") +
             (c.fitted ? "; fitted: likelihood ratio " + Figure(c.likelihood_ratio) : "")});
  }
  report->Heading("candidate effects", 3);
  report->Table({"effect", "statistic", "dof", "p", "significant", "magnitude", "sd",
                 "detectable above", "plausible", "test"},
                rows);
}

}  // namespace

HtmlReport DiagnosisReport(const DriveLog& log, const Diagnosis& before, const DriveLog* after_log,
                           const Diagnosis* after) {
  HtmlReport report("slipgraph diagnose: " + before.log);
  AddSection(log, before, after != nullptr ? "before" : "model vs measurements", &report);
  if (after != nullptr) {
    std::ostringstream text;
    PrintComparison(before, *after, text);
    report.Heading("before -> after");
    report.Preformatted(text.str());
    AddSection(after_log != nullptr ? *after_log : log, *after, "after", &report);
  }
  return report;
}

}  // namespace slipgraph
