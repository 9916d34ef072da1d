// slipgraph: wheel slip, immobilization and sinkage estimation for ground robots.
// Thin command-line front end; the work is done by the libraries.
#include <glog/logging.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>

#include "apps/commands.h"
#include "io/input_error.h"

namespace slipgraph {

std::string DefaultLogPath() { return SLIPGRAPH_DEFAULT_LOG; }
std::string DefaultHiddenEffectLogPath() { return SLIPGRAPH_DEFAULT_HIDDEN_LOG; }

}  // namespace slipgraph

int main(int argc, char** argv) {
  // Ceres' own log lines (e.g. "Jacobian matrix is rank deficient" from its covariance) are left
  // out: each command says in its own words what failed (a covariance not recovered, a solve
  // that did not converge). Errors still print.
  google::InitGoogleLogging(argv[0]);
  FLAGS_logtostderr = true;
  FLAGS_minloglevel = google::GLOG_ERROR;
  CLI::App app{"slipgraph: wheel slip, immobilization and sinkage estimation for ground robots"};
  app.set_version_flag("--version", std::string("slipgraph ") + SLIPGRAPH_VERSION);
  app.require_subcommand(1);
  int status = 0;
  slipgraph::RegisterInfoCommand(&app, &status);
  slipgraph::RegisterSimulateCommand(&app, &status);
  slipgraph::RegisterFilterCommand(&app, &status);
  slipgraph::RegisterSmoothCommand(&app, &status);
  slipgraph::RegisterOnlineCommand(&app, &status);
  slipgraph::RegisterCompareCommand(&app, &status);
  slipgraph::RegisterCalibrateCommand(&app, &status);
  slipgraph::RegisterSinkageCommand(&app, &status);
  slipgraph::RegisterImportCommand(&app, &status);
  slipgraph::RegisterDiagnoseCommand(&app, &status);
  slipgraph::RegisterIdentifyCommand(&app, &status);
  slipgraph::RegisterEvaluateCommand(&app, &status);
  slipgraph::RegisterEffectsCommand(&app, &status);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const slipgraph::InputError& e) {
    std::cerr << "slipgraph: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "slipgraph: error: " << e.what() << "\n";
    return 1;
  }
  return status;
}
