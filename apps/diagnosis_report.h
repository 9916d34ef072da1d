// What `diagnose` prints, writes as JSON and renders as an HTML page (evaluation/html_report's
// builder, as `compare` uses it): presentation of a workbench Diagnosis, kept out of the
// workbench.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>

#include "evaluation/html_report.h"
#include "workbench/diagnosis.h"

namespace slipgraph {

// The terminal summary: streams, failures, ranked candidates, the verdict.
void PrintDiagnosis(const Diagnosis& diagnosis, std::ostream& out);
// Before/after lines for `--with`: truth errors and stream statistics side by side.
void PrintComparison(const Diagnosis& before, const Diagnosis& after, std::ostream& out);
nlohmann::json ToJson(const Diagnosis& diagnosis);
// The page: residual plots per stream with the failure segments shaded, the force balance, the
// candidates' table and the summary; with `after`, the comparison and the same after adding the
// effects.
HtmlReport DiagnosisReport(const Diagnosis& before, const Diagnosis* after);

}  // namespace slipgraph
