// --json [FILE] on every subcommand, with one meaning: the subcommand's results as one JSON
// object, written to FILE, or to stdout when FILE is '-' or left out (the text the subcommand
// prints then goes to stderr, so that stdout is one JSON document). Every object carries
// "slipgraph": the program's version, the subcommand and the options it was given (the HTML
// pages carry the same record at their foot).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "io/plausibility.h"
#include "model/model_config.h"

namespace slipgraph {

class JsonOutput {
 public:
  // Registers --json on `cmd` (the object must outlive the parse: hold it in the subcommand's
  // options).
  void Add(CLI::App* cmd);
  bool enabled() const;
  // Where the subcommand's text goes: stderr when the JSON takes stdout, else stdout (as a
  // stream, and as a FILE for printf-style tables).
  std::ostream& text() const;
  std::FILE* text_file() const;
  // Adds the "slipgraph" record to `result` and writes it (a file write is checked).
  void Write(nlohmann::json result) const;
  // The record: the version, the subcommand and the options given (by name, as typed); and as a
  // line for the foot of an HTML page the subcommand writes.
  nlohmann::json Record() const;
  std::string RecordText() const;

 private:
  bool to_stdout() const;

  std::string path_;  // empty or "-": stdout
  CLI::App* cmd_ = nullptr;
  CLI::Option* option_ = nullptr;
};

// The model a run used, for its record: the file given (null: the vehicle's nominal model) and
// a fingerprint of the effective model (FNV-1a 64 of its model-file text, hex): two runs with
// the same fingerprint ran the same model.
nlohmann::json ModelRecord(const std::string& model_path, const ModelConfig& model);

// A log's plausibility figures (io/plausibility.h) by name, null where not measured (`info` and
// `import`).
nlohmann::json PlausibilityRecord(const PlausibilityFigures& figures);

}  // namespace slipgraph
