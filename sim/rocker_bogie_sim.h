// The articulated 6-wheel rover of Wilcox (rocker_bogie6), driving straight.
//
// Each side has its own synthetic scale-invariant terrain profile: 20 sine waves with
// wavelengths from 1.3 cm to 1.9 m, each 30 % longer than the last, random phase, amplitude
// uniform up to a fixed multiple of the wavelength, scaled to the scenario's RMS roughness. The
// front wheel sinks by s(x) (base sinkage plus soft patches); the middle and rear wheels follow
// its ruts, so every wheel rides on y(x) - s(x). Wheels average the terrain over their contact
// patch (a third of the radius by default: each sine is attenuated by sinc(L / lambda)); the
// ranging sensor samples y(x) at points. The rover advances by rim motion x (1 - slip) per cycle.
// The mismatch suite wilcoxm (RockerSpec) correlates the slip over distance, lets the wheels dig
// in on soft ground, deepens the rut under the following wheels and tilts the ranging sensor.
#pragma once

#include <cstdint>

#include "sim/scenario.h"
#include "sim/simulation.h"

namespace slipgraph {
namespace sim {

SimResult SimulateRockerBogie(const Scenario& scenario, uint64_t seed);

}  // namespace sim
}  // namespace slipgraph
