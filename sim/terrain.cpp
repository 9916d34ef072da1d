#include "sim/terrain.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "sim/random.h"

namespace slipgraph {
namespace sim {
namespace {

// Raised-cosine bump shape in [0, 1] over [0, 1], zero with zero slope at both ends.
double Bump(double u) {
  if (u <= 0.0 || u >= 1.0) return 0.0;
  return 0.5 * (1.0 - std::cos(2.0 * M_PI * u));
}

constexpr int kWavelengths = 20;
constexpr double kLongestWavelengthM = 1.9;
constexpr double kWavelengthRatio = 1.3;

double Sinc(double x) { return std::abs(x) < 1e-12 ? 1.0 : std::sin(M_PI * x) / (M_PI * x); }

}  // namespace

const std::vector<TerrainType>& TerrainCatalogue() {
  // Coefficients of plausible soils for a 117 kg pneumatic-tire robot; grass is set so that the
  // LAGR robot held back with its wheels spinning at 1 m/s pulls 325 N (Ward Sec. III-B).
  // Tracked-vehicle slip (alpha layout of factors/ipd_kinematics.h): forward slip grows with
  // speed and turning, the vehicle turns less than its tracks say (alpha[9] < 0), skids outward
  // in turns (alpha[6] < 0) and slides with gravity. Softer ground, more slip and more noise.
  const auto ipd = [](double fwd, double turn_fwd, double yaw_gain, double lateral, double noise) {
    return IpdSlip{{fwd, turn_fwd, -0.03, 0.010,  //
                    0.0, 0.01, lateral, 0.012,    //
                    0.005, yaw_gain, 0.02, 0.004, -0.003},
                   {noise * 0.0004, noise * 0.0003, noise * 0.0008}};
  };
  static const std::vector<TerrainType> kCatalogue = {
      {"asphalt",
       {0.85, 30.0, 0.02},
       {0.015, 20.0, 0.005},
       false,
       ipd(-0.02, -0.03, -0.08, -0.02, 0.5),
       std::nullopt,
       std::nullopt},
      {"gravel",
       {0.60, 15.0, 0.05},
       {0.040, 20.0, 0.010},
       false,
       ipd(-0.05, -0.05, -0.15, -0.04, 1.0),
       std::nullopt,
       std::nullopt},
      {"grass",
       {0.42, 20.0, 0.0435},
       {0.050, 20.0, 0.020},
       false,
       ipd(-0.05, -0.06, -0.18, -0.05, 1.0),
       std::nullopt,
       std::nullopt},
      {"mulch",
       {0.50, 10.0, 0.08},
       {0.070, 15.0, 0.020},
       true,
       ipd(-0.08, -0.07, -0.20, -0.06, 1.5),
       std::nullopt,
       std::nullopt},
      {"mud",
       {0.38, 8.0, 0.10},
       {0.090, 10.0, 0.030},
       true,
       ipd(-0.15, -0.10, -0.25, -0.08, 2.0),
       std::nullopt,
       std::nullopt},
      {"soft_dirt",
       {0.55, 12.0, 0.06},
       {0.060, 15.0, 0.020},
       true,
       ipd(-0.10, -0.08, -0.20, -0.07, 1.5),
       std::nullopt,
       std::nullopt},
      {"loose_rock",
       {0.65, 18.0, 0.03},
       {0.050, 20.0, 0.010},
       false,
       ipd(-0.07, -0.09, -0.25, -0.06, 2.0),
       std::nullopt,
       std::nullopt},
  };
  return kCatalogue;
}

const TerrainType& FindTerrain(const std::string& name) {
  for (const TerrainType& terrain : TerrainCatalogue()) {
    if (terrain.name == name) return terrain;
  }
  throw std::invalid_argument("unknown terrain '" + name + "'");
}

const TerrainPatch& Course::PatchAt(double s_m) const {
  size_t index = 0;
  for (size_t i = 1; i < patches.size(); ++i) {
    if (patches[i].s_start_m <= s_m) index = i;
  }
  return patches.at(index);
}

double Course::DistanceIntoPatch(double s_m) const { return s_m - PatchAt(s_m).s_start_m; }

double Course::GradeRad(double s_m) const {
  double grade = 0.0;
  for (const Hill& hill : hills) {
    grade += hill.peak_grade_rad * Bump((s_m - hill.s_start_m) / hill.length_m);
  }
  return grade;
}

double Course::CrossSlopeRad(double s_m) const {
  double cross = 0.0;
  for (const Hill& hill : hills) {
    cross += hill.peak_cross_slope_rad * Bump((s_m - hill.s_start_m) / hill.length_m);
  }
  return cross;
}

double TerrainProfile::Elevation(double x_m) const {
  double y = 0.0;
  for (size_t k = 0; k < wavelength_m.size(); ++k) {
    y += amplitude_m[k] * std::sin(2.0 * M_PI * x_m / wavelength_m[k] + phase_rad[k]);
  }
  return y;
}

double TerrainProfile::WheelElevation(double x_m, double patch_m) const {
  double y = 0.0;
  for (size_t k = 0; k < wavelength_m.size(); ++k) {
    y += amplitude_m[k] * Sinc(patch_m / wavelength_m[k]) *
         std::sin(2.0 * M_PI * x_m / wavelength_m[k] + phase_rad[k]);
  }
  return y;
}

TerrainProfile MakeTerrainProfile(double roughness_rms_m, double length_m, uint64_t seed) {
  std::mt19937_64 rng(seed);
  UniformReal u(0.0, 1.0);
  TerrainProfile p;
  for (int k = 0; k < kWavelengths; ++k) {
    const double lambda = kLongestWavelengthM / std::pow(kWavelengthRatio, kWavelengths - 1 - k);
    p.wavelength_m.push_back(lambda);
    p.amplitude_m.push_back(lambda * u(rng));  // uniform up to a multiple of the wavelength
    p.phase_rad.push_back(2.0 * M_PI * u(rng));
  }
  // Scale to the requested RMS over the course (1 mm sampling).
  double sum = 0.0, sum_sq = 0.0;
  const int n = std::max(1000, static_cast<int>(length_m / 0.001));
  for (int i = 0; i < n; ++i) {
    const double y = p.Elevation(length_m * i / n);
    sum += y, sum_sq += y * y;
  }
  const double mean = sum / n;
  const double rms = std::sqrt(std::max(sum_sq / n - mean * mean, 1e-30));
  for (double& a : p.amplitude_m) a *= roughness_rms_m / rms;
  return p;
}

}  // namespace sim
}  // namespace slipgraph
