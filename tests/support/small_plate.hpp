#pragma once
// A small thin-plate scene (0.1 m square, 2 mm thick, steel): simply supported on the left,
// clamped on the right, a uniform pressure; the scene text without solver or probes.
#include <string>

namespace perinom::test {

inline const std::string small_plate = R"(
name: plate
dimension: 2
geometry: {box: {min: [0.0, 0.0], max: [0.1, 0.1]}, thickness: 0.002}
discretization: {dx: 0.01, horizon: {ratio: 2.015}}
material: {type: linear_elastic, E: 2.0e11, nu: 0.3, density: 7800.0}
model: {type: thin_plate}
boundary:
  - {region: left, support: simply_supported}
  - {region: right, support: clamped}
  - {region: all, pressure: 100.0}
)";

}  // namespace perinom::test
