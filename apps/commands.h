// Each subcommand of the slipgraph CLI registers itself on the app and returns the callback's
// exit status through `*status`. Subcommands stay thin: parse flags, call the library, print.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace slipgraph {

// The bundled sample log, used when a subcommand's LOG is omitted.
std::string DefaultLogPath();
// The bundled hidden-effect log, the default of `diagnose`.
std::string DefaultHiddenEffectLogPath();

void RegisterInfoCommand(CLI::App* app, int* status);
void RegisterSimulateCommand(CLI::App* app, int* status);
void RegisterFilterCommand(CLI::App* app, int* status);
void RegisterEvaluateCommand(CLI::App* app, int* status);
void RegisterSmoothCommand(CLI::App* app, int* status);
void RegisterOnlineCommand(CLI::App* app, int* status);
void RegisterCompareCommand(CLI::App* app, int* status);
void RegisterCalibrateCommand(CLI::App* app, int* status);
void RegisterSinkageCommand(CLI::App* app, int* status);
void RegisterImportCommand(CLI::App* app, int* status);
void RegisterDiagnoseCommand(CLI::App* app, int* status);
void RegisterIdentifyCommand(CLI::App* app, int* status);
void RegisterEffectsCommand(CLI::App* app, int* status);

}  // namespace slipgraph
