// Terrain the simulated vehicle drives over: soil/tire patches and slopes, both as functions of
// the distance travelled along the path (s, m), so a course is independent of the steering.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "model/vehicle.h"
#include "sim/peaked_tire.h"
#include "sim/track_soil.h"

namespace slipgraph {
namespace sim {

// Rogers-Marcovitz et al.'s generative slip model on this terrain: slip velocities
// u_s = C(u_n, g) alpha + w, w white with spectral densities q (eqs. 14, 16-17).
struct IpdSlip {
  std::array<double, 13> alpha{};     // factors/ipd_kinematics.h for the layout
  std::array<double, 3> q_density{};  // (m/s)^2/Hz, (m/s)^2/Hz, (rad/s)^2/Hz
};

struct TerrainType {
  std::string name;
  TireParams tire;        // true traction/braking coefficients on this soil (eq. 8)
  RollingParams rolling;  // true rolling resistance (eq. 9)
  bool soft = false;      // compaction possible (sinkage_resistance effect)
  IpdSlip ipd;            // tracked vehicle slip on this soil
  // Set in the mismatch suites: the true traction and rolling resistance follow this law
  // (sim/peaked_tire.h), not eq. (8) and (9); `tire` and `rolling` are then unused.
  std::optional<PeakedSoil> peaked;
  // Set in ipd35m: the tracked robot's slip follows this soil (sim/track_soil.h), not `ipd`.
  std::optional<TrackSoil> track_soil;
};

// grass, mulch, gravel (loose gravel over hard soil), mud, asphalt, soft_dirt, loose_rock.
const std::vector<TerrainType>& TerrainCatalogue();
// Throws std::invalid_argument for an unknown name (a programmer error in a scenario).
const TerrainType& FindTerrain(const std::string& name);

struct TerrainPatch {
  double s_start_m = 0.0;  // the patch extends to the next patch's start
  TerrainType terrain;
};

// A smooth hill along the path: grade angle rises and falls as a raised cosine from s_start_m
// over length_m, peaking at peak_grade_rad (uphill positive, Ward's phi), with a cross slope
// (roll, right side down positive) scaled the same way.
struct Hill {
  double s_start_m = 0.0;
  double length_m = 1.0;
  double peak_grade_rad = 0.0;
  double peak_cross_slope_rad = 0.0;
};

struct Course {
  std::vector<TerrainPatch> patches;  // sorted by s_start_m; the first should start at 0
  std::vector<Hill> hills;

  // The patch in force at path distance s (the first patch before any start).
  const TerrainPatch& PatchAt(double s_m) const;
  // Grade angle (uphill positive) and cross slope at s.
  double GradeRad(double s_m) const;
  double CrossSlopeRad(double s_m) const;
  // Distance into the current patch (for effects that build up, e.g. sinkage).
  double DistanceIntoPatch(double s_m) const;
};

// One side's synthetic terrain profile for the articulated rover (Wilcox Sec. 3):
// y(x) = sum_k a_k sin(2 pi x / lambda_k + phase_k).
struct TerrainProfile {
  std::vector<double> wavelength_m, amplitude_m, phase_rad;
  // Raw elevation, and the elevation averaged over a contact patch of length patch_m.
  double Elevation(double x_m) const;
  double WheelElevation(double x_m, double patch_m) const;
};

// 20 wavelengths from 1.3 cm to 1.9 m, each 30 % longer than the last, amplitude uniform up to
// the wavelength, random phase; scaled so the RMS over [0, length_m] is roughness_rms_m.
TerrainProfile MakeTerrainProfile(double roughness_rms_m, double length_m, uint64_t seed);

}  // namespace sim
}  // namespace slipgraph
