// perinom material-point: the seed's biaxial tests (seed 000 Table 2, THEORY sec. 9) at one
// Drucker-Prager material point, by the return map and by the sub-stepped rate equations.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "commands.hpp"
#include "perinom/core/error.hpp"
#include "perinom/materials/linear_elastic.hpp"
#include "perinom/materials/material_point.hpp"
#include "perinom/materials/measures.hpp"

namespace perinom::cli {
int material_point(const Options& opt) {
  if (opt.test < 1 || opt.test > 7) throw InputError("--test must be 1 ... 7 (seed 000 Table 2)");
  if (opt.substeps < 1) throw InputError("--substeps must be at least 1");
  const BiaxialTest t = seed_biaxial_test(opt.test);
  const DruckerPrager& dp = t.material;
  const BiaxialProtocol& protocol = t.protocol;
  const auto path = drive_biaxial(dp, protocol);
  const auto reference = drive_biaxial(dp, protocol, opt.substeps);

  const std::string dir = opt.out.empty() ? "out/material_point" : opt.out;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::string file = dir + "/biaxial_test" + std::to_string(opt.test) + ".csv";
  std::ofstream csv(file);
  if (!csv) throw InputError("--out " + dir + ": the output folder cannot be created or written");
  csv << "step,eps_xx,eps_yy,sigma_xx,sigma_yy,sigma_zz,mean_stress,von_mises,eq_plastic_strain,"
         "von_mises_substepped,eq_plastic_strain_substepped\n";
  csv.precision(10);
  for (std::size_t k = 0; k < path.size(); ++k) {
    const auto& r = path[k];
    const double* s = r.state.sigma;
    csv << k << ',' << r.eps_xx << ',' << r.eps_yy << ',' << s[0] << ',' << s[4] << ',' << s[8] << ','
        << mean_stress(s) << ',' << von_mises(s) << ',' << r.state.xi << ',' << von_mises(reference[k].state.sigma)
        << ',' << reference[k].state.xi << '\n';
  }
  const auto& end = path.back().state;
  const auto& ref = reference.back().state;
  std::printf("perinom: biaxial test %d (confining %.0f kPa, h = %g, d0 = %g), plane strain, %d + %d steps\n",
              opt.test, protocol.confining / 1e3, dp.h, dp.d0, protocol.consolidation_steps, protocol.compression_steps);
  std::printf("  final von Mises          %.2f kPa (sub-stepped, %d per step: %.2f kPa)\n", von_mises(end.sigma) / 1e3,
              opt.substeps, von_mises(ref.sigma) / 1e3);
  std::printf("  final eq. plastic strain %.5f (sub-stepped: %.5f)\n", end.xi, ref.xi);
  std::printf("  curves in %s\n", file.c_str());
  return 0;
}

}  // namespace perinom::cli
