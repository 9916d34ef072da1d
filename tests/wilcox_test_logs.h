// A hand-made rover log for Wilcox's estimators: two sine terrains, 40 cycles of 5 cm advance at
// 20 % slip, noise-free point-contact measurements, a chosen sinkage per side beyond 0.3 m.
#pragma once

#include <cmath>

#include "io/drive_log.h"
#include "sim/scenarios.h"
#include "solvers/wilcox_baseline.h"

namespace slipgraph {
namespace testing {

inline double Terrain(double x) {
  return 0.01 * std::sin(2.0 * M_PI * x / 0.3) + 0.005 * std::sin(2.0 * M_PI * x / 0.11 + 1.0);
}

// 40 cycles of 5 cm advance (rim 6.25 cm: 20 % slip); sinkage per side.
inline DriveLog HandMadeLog(double sinkage_left_m, double sinkage_right_m) {
  DriveLog log;
  log.directory = "hand-made";
  log.vehicle = sim::RockerVehicle();
  const double A = log.vehicle.axle_spacing_m, r = log.vehicle.wheel_radius_m;
  const double rim_per_s = 0.0625, advance_per_s = 0.05;
  for (int k = 0; k <= 400; ++k) {  // wheels at 10 Hz
    WheelSample w;
    w.t = 0.1 * k;
    w.omega_radps.fill(std::nan(""));
    for (int i = 0; i < 6; ++i) w.omega_radps[i] = rim_per_s / r;
    log.wheels.push_back(w);
  }
  for (int c = 0; c <= 40; ++c) {
    const double t = c, x = advance_per_s * t;
    for (Side side : {Side::kLeft, Side::kRight}) {
      const double s = side == Side::kLeft ? sinkage_left_m : sinkage_right_m;
      const auto ride = [&](double at) { return Terrain(at) - (at > 0.3 ? s : 0.0); };
      log.articulation.push_back({t, side, ride(x + A) - ride(x), ride(x + 2 * A) - ride(x)});
      for (int i = 0; i < 30; ++i) {
        const double d = 2 * A + 0.02 + 0.02 * i;
        log.range.push_back({t, side, d, Terrain(x + d) - ride(x)});
      }
    }
    TruthSample truth;
    truth.t = t;
    truth.x = x;
    truth.sinkage.fill(std::nan(""));
    truth.sinkage[0] = sinkage_left_m;
    truth.sinkage[3] = sinkage_right_m;
    log.truth.push_back(truth);
  }
  return log;
}

inline WilcoxOptions PointContact() {
  WilcoxOptions o;
  o.contact_patch_fraction = 0.0;
  return o;
}

}  // namespace testing
}  // namespace slipgraph
