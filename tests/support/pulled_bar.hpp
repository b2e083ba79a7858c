#pragma once
// A plane-stress bar 60 mm x 12 mm, left end on rollers (u_x = 0, one particle also u_y = 0),
// pulled by a traction of 1 MPa on the right end: the scene text without solver or probes,
// shared by the ADR tests and the resume tests. Analytic: u_x(L) = t L / E.
#include <string>

namespace perinom::test {

inline const std::string pulled_bar = R"(
name: bar
dimension: 2
geometry: {box: {min: [0, 0], max: [0.06, 0.012]}, thickness: 0.01}
discretization: {dx: 0.002, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 30.0e6, nu: 0.25, density: 2000, plane: stress}
boundary:
  - {region: left, fix: [x]}
  - {region: {box: {min: [0, 0], max: [0.002, 0.002]}}, fix: [y]}
  - {region: right, traction: [1.0e6, 0]}
)";

}  // namespace perinom::test
