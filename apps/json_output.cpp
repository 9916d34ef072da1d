#include "apps/json_output.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "io/text_file.h"
#include "io/yaml_config.h"

namespace slipgraph {

void JsonOutput::Add(CLI::App* cmd) {
  cmd_ = cmd;
  // A directory is a log that --json took for its FILE ("--json LOG"): an error, not a run on
  // the bundled sample.
  const CLI::Validator not_a_directory(
      [](std::string& path) {
        std::error_code error;
        return std::filesystem::is_directory(path, error)
                   ? "'" + path +
                         "' is a directory: put --json after the log, or write "
                         "--json=FILE"
                   : std::string();
      },
      "FILE");
  option_ = cmd->add_option("--json", path_,
                            "Write the results as one JSON object to FILE, or to stdout with no "
                            "FILE or '-' (the text then goes to stderr); put it last or write "
                            "--json=FILE")
                ->expected(0, 1)
                ->check(not_a_directory)
                ->type_name("[FILE]");
}

bool JsonOutput::enabled() const { return option_ != nullptr && option_->count() > 0; }

bool JsonOutput::to_stdout() const { return enabled() && (path_.empty() || path_ == "-"); }

std::ostream& JsonOutput::text() const { return to_stdout() ? std::cerr : std::cout; }

std::FILE* JsonOutput::text_file() const { return to_stdout() ? stderr : stdout; }

nlohmann::json JsonOutput::Record() const {
  nlohmann::json options = nlohmann::json::object();
  if (cmd_ != nullptr) {
    for (const CLI::Option* option : cmd_->get_options()) {
      if (option->count() == 0 || option->get_name() == "--json") continue;
      const std::vector<std::string>& values = option->results();
      const std::string name = option->get_name();
      if (values.size() == 1) {
        options[name] = values.front();
      } else {
        options[name] = values;
      }
    }
  }
  return {{"version", SLIPGRAPH_VERSION},
          {"command", cmd_ != nullptr ? cmd_->get_name() : ""},
          {"options", options}};
}

std::string JsonOutput::RecordText() const {
  const nlohmann::json record = Record();
  std::string text = "Written by slipgraph " + record["version"].get<std::string>() + ": " +
                     record["command"].get<std::string>();
  for (const auto& [name, value] : record["options"].items()) {
    text += " " + name + "=" + (value.is_string() ? value.get<std::string>() : value.dump());
  }
  return text + ".";
}

void JsonOutput::Write(nlohmann::json result) const {
  result["slipgraph"] = Record();
  const std::string text = result.dump(2) + "\n";
  if (to_stdout()) {
    std::cout << text << std::flush;
  } else {
    WriteTextFile(path_, text);
  }
}

nlohmann::json ModelRecord(const std::string& model_path, const ModelConfig& model) {
  std::ostringstream yaml;
  WriteModelYaml(model, yaml);
  uint64_t hash = 1469598103934665603ull;  // FNV-1a 64: offset basis, then xor and multiply
  for (const unsigned char c : yaml.str()) hash = (hash ^ c) * 1099511628211ull;
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(hash));
  return {{"file", model_path.empty() ? nlohmann::json(nullptr) : nlohmann::json(model_path)},
          {"fingerprint", hex}};
}

nlohmann::json PlausibilityRecord(const PlausibilityFigures& figures) {
  const auto value = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nullptr; };
  return {{"rest_seconds", figures.rest_seconds},
          {"gravity_at_rest", figures.gravity_at_rest},
          {"rest_az_mps2", value(figures.rest_az_mps2)},
          {"rest_norm_mps2", value(figures.rest_norm_mps2)},
          {"wheel_over_gnss_speed", value(figures.wheel_over_gnss_speed)},
          {"wheel_gyro_yaw_correlation", value(figures.wheel_gyro_yaw_correlation)},
          {"wheel_over_gyro_yaw", value(figures.wheel_over_gyro_yaw)}};
}

}  // namespace slipgraph
