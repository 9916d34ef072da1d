// What `diagnose` prints and renders as an HTML page (evaluation/html_report's
// builder, as `compare` uses it): presentation of a workbench Diagnosis, kept out of the
// workbench.
#pragma once

#include <ostream>

#include "evaluation/html_report.h"
#include "workbench/diagnosis.h"
#include "workbench/diagnosis_json.h"

namespace slipgraph {

// The terminal summary: streams, failures, ranked candidates, the verdict.
void PrintDiagnosis(const Diagnosis& diagnosis, std::ostream& out);
// Before/after lines for `--with`: truth errors and stream statistics side by side.
void PrintComparison(const Diagnosis& before, const Diagnosis& after, std::ostream& out);
// The page, per diagnosis: the verdict, the estimates (the front end's and the smoother's velocity
// against the wheels' rim speed, disturbance, slip and immobilized flags), the streams' table,
// residual plots per stream with the failure segments shaded, the force balance and the
// candidates' table; with `after` (on `after_log`, the log with any measurement corrections),
// the comparison and the same after adding the effects.
HtmlReport DiagnosisReport(const DriveLog& log, const Diagnosis& before,
                           const DriveLog* after_log = nullptr, const Diagnosis* after = nullptr);

}  // namespace slipgraph
