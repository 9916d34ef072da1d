#include "solvers/ekf_runner.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "io/estimate_file.h"
#include "io/measurement_stream.h"

namespace slipgraph {

bool FilterRunOptions::IsValid(std::string* error) const {
  return ekf.IsValid(error) && (!multiple_model || multiple_model_options.IsValid(error)) &&
         (!disturbance_modes || disturbance_modes_options.IsValid(error));
}

namespace {

// The streams merged in time order into any filter with the WardEkf interface.
template <typename Filter>
void Feed(const DriveLog& log, const StreamSelection& selection, Filter* filter,
          FilterResult* result) {
  result->estimates.reserve(log.wheels.size());
  result->disturbance_density.reserve(log.wheels.size());
  if constexpr (std::is_same_v<Filter, MultipleModelEkf>) {
    result->law_spread_sd.reserve(log.wheels.size());
    result->law.reserve(log.wheels.size());
  }
  for (const StreamEntry& entry : MergeStreams(log, selection)) {
    switch (entry.stream) {
      case Stream::kImu:
        filter->AddImu(log.imu[entry.index]);
        break;
      case Stream::kAttitude:
        filter->AddAttitude(log.attitude[entry.index]);
        break;
      case Stream::kGps:
        filter->AddGps(log.gps[entry.index]);
        break;
      case Stream::kWheels: {
        const WheelSample& w = log.wheels[entry.index];
        const SideSpeeds sides = DrivenSideSpeeds(w, log.vehicle.type);
        filter->AddWheels(w.t, sides.left_radps, sides.right_radps);
        if constexpr (std::is_same_v<Filter, MultipleModelEkf>) {
          result->law_spread_sd.emplace_back();
          result->estimates.push_back(filter->Estimate(&result->law_spread_sd.back()));
          result->law.push_back(filter->Law());
        } else {
          result->estimates.push_back(filter->Estimate());
        }
        result->disturbance_density.push_back(filter->DisturbanceDensity());
        break;
      }
      default:
        break;
    }
  }
  result->stats = filter->stats();
}

// The filter the options and the model choose (a bank where the model lists soils, else the
// disturbance modes or the paper's single filter) fed the selected streams.
void RunChosenFilter(const DriveLog& log, const ModelConfig& model, const FilterRunOptions& options,
                     const StreamSelection& selection, FilterResult* result) {
  if (options.multiple_model && model.ListsSoils()) {
    MultipleModelEkf filters(log.vehicle, model, options.ekf, options.multiple_model_options);
    Feed(log, selection, &filters, result);
    result->notes.push_back(
        "a bank of " + std::to_string(filters.size()) + " filters: the user's tire law and the " +
        std::to_string(model.law_samples.size()) +
        " it was fitted over, weighed by their GNSS likelihood (--single-law: one filter)");
    if (options.disturbance_modes) {
      result->notes.push_back(
          "the disturbance modes apply to the single filter: the bank ran (--single-law for them)");
    }
  } else if (options.disturbance_modes) {
    DisturbanceImm imm(log.vehicle, model, options.ekf, options.disturbance_modes_options);
    Feed(log, selection, &imm, result);
    result->notes.push_back(
        "three filters as disturbance modes (quiet, changing, held), mixed as an interacting "
        "multiple model (--disturbance-modes)");
  } else {
    WardEkf ekf(log.vehicle, model, options.ekf);
    Feed(log, selection, &ekf, result);
  }
}

// ModelConfig::tire_slip_stiffness_relative_sd, a consider covariance for the single front end: the
// same filter run again with the law's slope at small slip (At and C2) scaled by exp(-sd) and by
// exp(+sd) (SlipStiffnessSdScales), each state's variance increased by the mean of the two squared
// shifts. A slope that is off moves the velocity where the law holds it (the slip the force needs)
// and hardly where it does not (a hold-back, where the slip is the wheels' and GNSS's): the shift
// goes through the filter's own gains. The estimates are unchanged; the shift's sd is the law's
// share (FilterResult::law_spread_sd). Left out, with a note, when a moved run diverged.
void AddLawSlopeConsider(const DriveLog& log, const ModelConfig& model,
                         const FilterRunOptions& options, const StreamSelection& selection,
                         FilterResult* result) {
  const double sd = model.tire_slip_stiffness_relative_sd;
  std::vector<std::array<double, ward::kStateSize>> added(result->estimates.size());
  for (double scale : SlipStiffnessSdScales(sd)) {
    ModelConfig moved = model;
    ScaleSlipStiffness(scale, &moved.tire);
    FilterResult other;
    RunChosenFilter(log, moved, options, selection, &other);
    if (other.estimates.size() != result->estimates.size()) {
      throw std::logic_error("RunEkf: the run with the law's slope moved has other samples");
    }
    if (other.stats.divergence_resets > 0) {
      result->notes.push_back(
          "the tire law's slope uncertainty is not in the sd: the run with the slope moved "
          "diverged");
      return;
    }
    for (size_t k = 0; k < added.size(); ++k) {
      for (int i = 0; i < ward::kStateSize; ++i) {
        const double shift = other.estimates[k].x[i] - result->estimates[k].x[i];
        added[k][i] += 0.5 * shift * shift;
      }
    }
  }
  result->law_spread_sd.resize(added.size());
  for (size_t k = 0; k < added.size(); ++k) {
    std::array<double, ward::kStateSize>& sd_k = result->estimates[k].sd;
    for (int i = 0; i < ward::kStateSize; ++i) {
      sd_k[i] = std::sqrt(sd_k[i] * sd_k[i] + added[k][i]);
      result->law_spread_sd[k][i] = std::sqrt(added[k][i]);
    }
  }
  std::ostringstream note;
  note << "the sd include the tire law's slope uncertainty (tire_sd.slip_stiffness " << sd
       << ": the estimate's mean squared shift with At and C2 scaled by exp(-" << sd
       << ") and exp(+" << sd << "))";
  result->notes.push_back(note.str());
}

}  // namespace

FilterResult RunEkf(const DriveLog& log, const ModelConfig& given,
                    const FilterRunOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  ModelConfig model = given;
  if (options.papers_accel_bias) UsePapersAccelBias(&model);
  const double slope_sd = model.tire_slip_stiffness_relative_sd;
  if (!(slope_sd >= 0.0 && slope_sd <= kMaxSlipStiffnessRelativeSd)) {
    throw std::invalid_argument("RunEkf: tire_sd.slip_stiffness " + std::to_string(slope_sd) +
                                " must lie in [0, 2]");
  }
  FilterResult result;
  StreamSelection selection;
  selection.Set(Stream::kGps, options.use_gps);
  selection.Set(Stream::kAttitude, options.use_attitude);
  for (Stream s : {Stream::kImu, Stream::kWheels, Stream::kAttitude, Stream::kGps}) {
    if (!selection.Uses(s)) continue;
    const bool present = (s == Stream::kImu && !log.imu.empty()) ||
                         (s == Stream::kWheels && !log.wheels.empty()) ||
                         (s == Stream::kAttitude && !log.attitude.empty()) ||
                         (s == Stream::kGps && !log.gps.empty());
    if (present) result.streams_used.push_back(StreamName(s));
  }
  if (log.attitude.empty() || !options.use_attitude) {
    result.notes.push_back("no attitude: ground taken as flat (roll = pitch = 0)");
  }
  if (log.gps.empty() || !options.use_gps) result.notes.push_back("no GNSS velocity used");
  for (const std::string& effect : model.effects) {
    result.notes.push_back("effect '" + effect +
                           "' is named in the model but has no estimator term yet: ignored");
  }
  for (Stream s : {Stream::kPose, Stream::kArticulation, Stream::kRange, Stream::kCommands}) {
    selection.Set(s, false);
  }
  RunChosenFilter(log, model, options, selection, &result);
  const bool bank = options.multiple_model && model.ListsSoils();
  if (slope_sd > 0.0) {
    if (bank) {
      result.notes.push_back(
          "tire_sd.slip_stiffness is not added to the sd: the bank's spread over its soils "
          "carries the law's uncertainty");
    } else {
      AddLawSlopeConsider(log, model, options, selection, &result);
    }
  }
  if (result.stats.gps.used == 0 && result.stats.gps.rejected > 0) {
    result.notes.push_back("every GNSS fix was rejected by the gate");
  }
  return result;
}

std::string DescribeFilterRun(const FilterResult& result) {
  std::ostringstream out;
  out << "streams used:";
  for (const std::string& s : result.streams_used) out << " " << s;
  out << "\n";
  const auto line = [&out](const char* name, const StreamCounters& c) {
    out << "  " << name << ": " << c.used << " used, " << c.rejected << " rejected by the gate, "
        << c.forced << " re-admitted, " << c.dropped_components << " NaN components dropped\n";
  };
  line("imu", result.stats.imu);
  line("wheels", result.stats.wheels);
  line("gps", result.stats.gps);
  line("attitude", result.stats.attitude);
  if (result.stats.gnss_fading > 0) {
    out << "  GNSS fading memory: the covariance widened before " << result.stats.gnss_fading
        << " of the " << result.stats.gps.used
        << " GNSS fixes used, their innovations having kept one sign (--no-gnss-fading: off)\n";
  }
  if (result.stats.gnss_heading_corrected > 0) {
    out << "  GNSS heading: the attitude's yaw is off the fixes' course; "
        << result.stats.gnss_heading_corrected << " of the GNSS fixes were projected on it "
        << "corrected (the last by "
        << std::round(result.stats.gnss_heading_offset_rad * 1800.0 / M_PI) / 10.0 << " deg)\n";
  }
  const StreamCounters& check = result.stats.slip_persistence;
  if (check.used + check.rejected > 0) {
    out << "  the wheels' check on the accelerometer bias: " << check.used << " intervals applied ("
        << result.stats.slip_persistence_lasting
        << " of them a lasting error, with the velocity it moved), " << check.rejected
        << " left out (a force the accelerometer felt; model file "
        << "slip_persistence: {interval: 0}: off)\n";
  }
  out << "  weak constraints applied:";
  for (int i = 0; i < kWeakConstraintCount; ++i) {
    out << " " << WeakConstraintName(static_cast<WeakConstraint>(i)) << "="
        << result.stats.weak_constraints[i];
  }
  out << "\n  IMU samples for offset initialisation: " << result.stats.offset_init_samples
      << (result.stats.offset_implausible_start
              ? " (moving, the wheels' acceleration not the body's: accelerometer offset from 0)"
          : result.stats.offset_moving_start ? " (moving: offsets compensated by the wheels)"
                                             : "")
      << ", late measurements: " << result.stats.late_measurements << "\n";
  if (result.stats.divergence_resets > 0) {
    out << "  DIVERGED " << result.stats.divergence_resets
        << " time(s) (first at t=" << result.stats.first_divergence_t
        << " s): the state went non-finite and was reset to the last finite one, covariance "
           "x100; the model is far from these data\n";
  }
  for (const std::string& note : result.notes) out << "  note: " << note << "\n";
  return out.str();
}

}  // namespace slipgraph
