// A long LAGR drive for benchmarks: gravel, grass and mud, two hills, 20 s command segments of
// varying speed and turn, and a 4 s hold-back every 200 s; at least `minutes` long (whole
// segments).
#pragma once

#include "sim/scenarios.h"

namespace slipgraph {

inline sim::Scenario LongDrive(double minutes) {
  sim::Scenario sc;
  sc.name = "bench";
  sc.vehicle = sim::LagrVehicle();
  sc.course.patches = {{0.0, sim::FindTerrain("gravel")},
                       {300.0, sim::FindTerrain("grass")},
                       {700.0, sim::FindTerrain("mud")}};
  sc.course.hills = {{100.0, 40.0, 0.08, 0.02}, {500.0, 30.0, -0.06, 0.0}};
  sc.rest_start_s = 3.0;
  double total = sc.rest_start_s;
  for (int i = 0; total < minutes * 60.0; ++i) {
    const sim::CommandSegment segment{20.0, 0.3 + 0.1 * (i % 8), 0.2 * ((i % 5) - 2)};
    sc.commands.push_back(segment);
    total += segment.duration_s;
    if (i % 10 == 9) sc.holdbacks.push_back({total - 8.0, total - 4.0});
  }
  return sc;
}

}  // namespace slipgraph
