// The estimates over time as `compare` and `diagnose` draw them: body velocity against the
// wheels' rim speed (and truth when the log has it), the disturbance, and the mean driven slip
// with the immobilized flags; the log's events shaded. The last estimator drawn solid with its
// +-2 sd band, the others dashed.
#pragma once

#include <string>
#include <vector>

#include "evaluation/html_report.h"
#include "io/drive_log.h"
#include "io/state_estimate.h"

namespace slipgraph {

struct NamedEstimates {
  std::string name;
  const std::vector<WardEstimate>* estimates;
  std::string color;
};

void AddEstimatePlots(const DriveLog& log, const std::vector<NamedEstimates>& runs,
                      HtmlReport* html);

}  // namespace slipgraph
