#pragma once
/// @file One Drucker-Prager material point driven through the seed's biaxial protocol
/// (seed 000 sec. 5.3, Table 2) by mixed stress/strain control, plane strain.
#include <vector>

#include "perinom/materials/drucker_prager.hpp"

namespace perinom {

/// Consolidation: sigma_xx = sigma_yy ramped to -confining in `consolidation_steps`; then
/// compression: eps_yy decreased by `vertical_strain` in `compression_steps` at constant
/// sigma_xx = -confining. eps_zz = 0 and no shear throughout.
struct BiaxialProtocol {
  double confining = 600e3;  ///< Pa (compression positive, as in the seed's table)
  int consolidation_steps = 100;
  double vertical_strain = 0.05;
  int compression_steps = 100;
};

/// Seed 000 Table 2: E = 30 MPa, nu = 0.25, phi = 35 deg, c = 60 kPa, m0 = 0.2 throughout;
/// tests 1-4 confine at 400, 600, 800, 1000 kPa (h = 0, d0 = 0); tests 5 and 6 harden
/// (h = 25, 50) and test 7 dilates (d0 = 1), at 600 kPa.
struct BiaxialTest {
  DruckerPrager material;
  BiaxialProtocol protocol;
};
/// Test 1 ... 7 of Table 2; throws std::out_of_range otherwise.
BiaxialTest seed_biaxial_test(int test);

/// The state after each load step.
struct MaterialPointRecord {
  double eps_xx = 0.0, eps_yy = 0.0;
  DruckerPrager::State state;
};

/// Runs the protocol. substeps = 0 integrates each step by the return map (`update`);
/// substeps > 0 by the explicit rate equations in that many sub-steps
/// (`update_substepped`), the independent reference. The lateral (and during consolidation
/// the vertical) strain increments are found by Newton with a finite-difference Jacobian
/// of the update, to 1e-6 Pa. Returns one record per step, the initial state first.
/// Throws SolveError when a held stress cannot be reached (the point cannot carry it).
std::vector<MaterialPointRecord> drive_biaxial(const DruckerPrager& dp, const BiaxialProtocol& protocol,
                                               int substeps = 0);

}  // namespace perinom
