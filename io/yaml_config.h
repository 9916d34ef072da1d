// All YAML of slipgraph is parsed here, and strictly.
//
// vehicle.yaml (shared/log-format.md) is a contract other programs write: a key the vehicle type
// needs and that is missing is an error naming it; an unknown key is a warning (extensions are
// allowed by the format). A model file is ours: every key is optional (it overrides the vehicle's
// nominal values and the in-class defaults of ModelConfig), and an unknown key is an error.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "io/drive_log.h"
#include "model/model_config.h"
#include "model/vehicle.h"

namespace slipgraph {

// Throws InputError (file, line, column, key) on a missing needed key, a non-numeric value, an
// unknown vehicle type or a non-positive physical dimension. Unknown keys and sensor sections
// left to defaults are appended to `warnings`.
Vehicle ReadVehicleYaml(const std::string& path, std::vector<std::string>* warnings);
// The same from the text of a vehicle.yaml held in memory; `name` stands for its path in errors.
Vehicle ParseVehicleYaml(const std::string& name, const std::string& text,
                         std::vector<std::string>* warnings);

// The vehicle's nominal values, then the in-class defaults, overridden by the keys of `path`.
// Throws InputError on an unknown key or bad value, and when the result fails IsValid().
ModelConfig ReadModelYaml(const std::string& path, const Vehicle& vehicle);
// The same from the text of a model file held in memory; `name` stands for its path in errors.
ModelConfig ParseModelYaml(const std::string& name, const std::string& text,
                           const Vehicle& vehicle);

// The vehicle's nominal model, or, when `model_path` is not empty, the model file over it.
ModelConfig ReadModelOrNominal(const std::string& model_path, const Vehicle& vehicle);
// The same for a log, with the model's calibration (wheel radii, effective track, the IMU's time
// offset) applied to it.
ModelConfig ModelForLog(DriveLog* log, const std::string& model_path);

void WriteVehicleYaml(const Vehicle& vehicle, std::ostream& out);
// The effective configuration, in the model-file schema (loadable by ReadModelYaml).
void WriteModelYaml(const ModelConfig& model, std::ostream& out);

}  // namespace slipgraph
