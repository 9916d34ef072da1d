// Runs the Ward EKF over a whole drive log: the streams merged in time order, one estimate per
// wheel cycle, and an account of which streams were used and what was rejected.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "io/drive_log.h"
#include "io/estimate_file.h"
#include "model/model_config.h"
#include "solvers/disturbance_imm.h"
#include "solvers/multiple_model_ekf.h"
#include "solvers/ward_ekf.h"

namespace slipgraph {

struct FilterRunOptions {
  bool use_gps = true;       // --no-gps clears it
  bool use_attitude = true;  // without attitude.csv the ground is taken as flat (and said so)
  EkfOptions ekf;
  // With the law's soils in the model (vehicle.yaml law_samples): a bank of filters, one per
  // soil law and the user's, weighed by their GNSS likelihood (solvers/multiple_model_ekf.h).
  // false, or no law samples: the paper's single filter.
  bool multiple_model = true;
  MultipleModelOptions multiple_model_options;
  // The single filter as disturbance modes: quiet, changing, held (solvers/disturbance_imm.h),
  // with their options. Where the law samples make a bank, the bank runs.
  bool disturbance_modes = false;
  DisturbanceImmOptions disturbance_modes_options;
  // The paper's accelerometer bias whatever the model says (UsePapersAccelBias: no attitude
  // error walk, no wheels' check; the workbench and identify start from the paper's filter, on
  // which their figures were measured).
  bool papers_accel_bias = false;
  // The EKF's options valid, and the bank's when it runs.
  bool IsValid(std::string* error) const;
};

struct FilterResult {
  std::vector<WardEstimate> estimates;  // one per wheel sample, after its cycle
  // Per estimate, the tire law's share of the sd (the window smoother adds it to its own): the
  // bank's (solvers/multiple_model_ekf.h) sd of the soils' estimates about its mean, or the single
  // front end's shift with the law's slope (ModelConfig::tire_slip_stiffness_relative_sd). Else
  // empty.
  std::vector<std::array<double, ward::kStateSize>> law_spread_sd;
  // The bank: per estimate, its filters' laws weighed as the estimate is (MultipleModelEkf::Law),
  // the law a smoother behind it takes at that state. Empty for one filter.
  std::vector<LawSample> law;
  // Per estimate, the disturbance's random-walk density the filter's next prediction takes (its
  // adaptive w3; the bank's filters' and the disturbance modes' weighed), for a smoother behind
  // it.
  std::vector<double> disturbance_density;
  EkfStats stats;
  std::vector<std::string> streams_used;
  std::vector<std::string> notes;  // assumptions and problems, one line each
};

FilterResult RunEkf(const DriveLog& log, const ModelConfig& model,
                    const FilterRunOptions& options = {});

// One paragraph for the terminal: streams used, counts, rejections, weak constraints.
std::string DescribeFilterRun(const FilterResult& result);

}  // namespace slipgraph
