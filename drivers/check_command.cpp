// perinom check: validate a scene, build its operators, and print the plan and its memory.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "commands.hpp"
#include "classical_mesh_note.hpp"
#include "curved_surface_note.hpp"
#include "lattice_hole_note.hpp"
#include "layer_support_note.hpp"
#include "locking_warning.hpp"
#include "memory_estimate.hpp"
#include "perinom/core/error.hpp"
#include "perinom/distributed/graph_partition.hpp"
#include "perinom/neighbors/partition.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/scene/registry.hpp"
#include "perinom/solvers/jacobian.hpp"
#include "perinom/solvers/petsc.hpp"
#include "point_tie_note.hpp"
#include "precrack_row_note.hpp"
#include "point_volume_note.hpp"
#include "stability_check.hpp"
#include "support_check.hpp"
#include "thick_plate_note.hpp"
#include "thin_body_note.hpp"

namespace perinom::cli {
namespace {

/// One partition's line: owned, ghosts within one and two horizons (least-most, mean share).
void print_shares(const char* label, const std::vector<RankShare>& shares) {
  std::size_t owned_lo = shares[0].owned, owned_hi = 0, one_lo = shares[0].ghosts_one, one_hi = 0, two_lo = shares[0].ghosts_two,
              two_hi = 0, one = 0, two = 0, owned = 0;
  for (const RankShare& s : shares) {
    owned_lo = std::min(owned_lo, s.owned), owned_hi = std::max(owned_hi, s.owned);
    one_lo = std::min(one_lo, s.ghosts_one), one_hi = std::max(one_hi, s.ghosts_one);
    two_lo = std::min(two_lo, s.ghosts_two), two_hi = std::max(two_hi, s.ghosts_two);
    one += s.ghosts_one, two += s.ghosts_two, owned += s.owned;
  }
  std::printf("  %-15s %s: owned %zu-%zu particles;\n"
              "                  ghosts within one horizon %zu-%zu (%.1f%% of the owned, mean), within two %zu-%zu (%.1f%%)\n",
              "", label, owned_lo, owned_hi, one_lo, one_hi, 100.0 * double(one) / double(owned), two_lo, two_hi,
              100.0 * double(two) / double(owned));
}

/// What R ranks would own and need from each other (issue 19): contiguous blocks of the
/// Morton order (the distributed force's partition) and PT-Scotch's partition of the bond
/// graph, where this build has PETSc.
void print_partition(const Problem& p, int ranks) {
  const Families families = scene_families(p.scene, p.cloud);
  std::printf("  partition       %d ranks\n", ranks);
  if (std::size_t(ranks) > p.cloud.size()) {
    // As run refuses it: a rank needs particles of its own.
    std::printf("                  more ranks than the %zu particles: mpirun -np %d perinom run refuses this scene "
                "(every rank needs particles of its own)\n", p.cloud.size(), ranks);
    return;
  }
  print_shares("contiguous blocks of a Morton curve", partition_shares(families, morton_order(p.cloud), ranks));
  if (petsc_available()) print_shares("PT-Scotch on the bond graph", rank_shares(families, scotch_partition(families, ranks), ranks));
  else std::printf("                  PT-Scotch: not in this build (no PETSc)\n");
}

}  // namespace

namespace {

/// A body from a mesh or a point file: its elements, sizes against the horizon, groups.
void print_body(const Problem& p) {
  const Scene& s = p.scene;
  const std::string horizon = s.discretization.horizon_neighbors > 0
                                  ? std::to_string(s.discretization.horizon_neighbors) + " nearest neighbours"
                                  : "delta = " + std::to_string(s.discretization.horizon_ratio) + " x dx " +
                                        std::to_string(s.discretization.dx) + " m";
  if (p.mesh_elements > 0)
    std::printf("  mesh            %s: %zu elements, mean element size %.4g m (horizon %s)\n",
                s.body_files.mesh.c_str(), p.mesh_elements, p.mean_size, horizon.c_str());
  else
    std::printf("  points          %s: mean spacing %.4g m (horizon %s)\n", s.body_files.points.c_str(), p.mean_size,
                horizon.c_str());
  std::string groups;
  for (const auto& g : p.groups) groups += (groups.empty() ? "" : ", ") + g.name + " (" + std::to_string(g.facets.size()) + ")";
  std::printf("  boundary groups %s\n", groups.empty() ? "none" : (groups + " facets").c_str());
  if (p.facet_defect > 0.0) std::printf("  facets          divergence theorem defect %.2g\n", p.facet_defect);
}

}  // namespace

int check(const Options& opt) {
  if (opt.positional.size() != 1) throw InputError("check needs exactly one scene file");
  const Scene scene = read_scene(opt.positional[0], opt.overrides);
  const MemoryEstimate estimate = estimate_memory(scene);
  require_memory(scene, estimate, opt.max_memory > 0.0 ? opt.max_memory : available_memory(), opt.max_memory > 0.0);
  PhaseTimer timer;
  Problem p = build_problem(scene, &timer);  // not const: StaticSystem sizes the Jacobian from the model
  const auto mb = [](std::size_t b) { return b / 1048576.0; };
  std::printf("scene %s (%s): valid\n", scene.name.c_str(), scene.source.c_str());
  // The model's lines: one labelled "dimension" completes the dimension line.
  const std::vector<PlanLine> plan = p.physics().plan();
  std::string dimension_note;
  for (const auto& line : plan)
    if (line.label == "dimension") dimension_note += line.text;
  std::printf("  dimension       %d%s\n", scene.dim, dimension_note.c_str());
  std::printf("  particles       %zu\n", p.cloud.size());
  if (const std::string volumes = point_volume_warning(p); !volumes.empty())
    std::printf("  volumes         warning: %s\n", volumes.c_str());
  if (const std::string thin = thin_body_note(p); !thin.empty()) std::printf("  thin            %s\n", thin.c_str());
  if (const std::string thick = thick_plate_note(p); !thick.empty()) std::printf("  thick           %s\n", thick.c_str());
  if (const std::string hole = lattice_hole_note(p); !hole.empty()) std::printf("  hole            %s\n", hole.c_str());
  if (const std::string bend = curved_surface_note(p); !bend.empty()) std::printf("  curved          %s\n", bend.c_str());
  if (const std::string tie = point_tie_note(p); !tie.empty()) std::printf("  tie             %s\n", tie.c_str());
  if (const std::string row = precrack_row_note(p); !row.empty()) std::printf("  precrack        %s\n", row.c_str());
  if (const std::string locking = locking_warning(p); !locking.empty())
    std::printf("  locking         warning: %s\n", locking.c_str());
  if (const std::string plastic = plastic_collapse_note(p); !plastic.empty())
    std::printf("  collapse        %s\n", plastic.c_str());
  if (const std::string layer = layer_support_note(p); !layer.empty()) std::printf("  supports        %s\n", layer.c_str());
  if (const std::string classical = classical_mesh_note(p); !classical.empty())
    std::printf("  formulation     %s\n", classical.c_str());
  if (!scene.solver.type.empty() && scene.solver.type != "verlet") warn_if_free(p);  // as run warns before a static solve
  std::printf("  bonds           %zu (%.1f per particle)\n", p.bonds, double(p.bonds) / p.cloud.size());
  if (scene.body_files.given()) print_body(p);
  for (const auto& line : plan)
    if (line.label != "dimension") std::printf("  %-15s %s\n", line.label.c_str(), line.text.c_str());
  if (const auto& dp = scene.plasticity)
    std::printf("  material        drucker_prager, phi = %g deg, c = %g Pa, m0 = %g, d0 = %g, h = %g\n",
                dp->friction_angle * 180.0 / M_PI, dp->cohesion, dp->m0, dp->d0, dp->h);
  std::printf("  constraints     %zu fixed degrees of freedom%s\n", p.loading.fixed.size(),
              p.loading.force.empty() ? "" : ", external forces");
  for (const auto& pin : p.pins) {
    std::string held;
    for (const int a : pin.components) held += std::string(held.empty() ? "" : ", ") + "xyz"[a];
    std::printf("  rigid_body pin  particle %u in %s\n", static_cast<unsigned>(pin.particle), held.c_str());
  }
  for (std::size_t k = 0; k < scene.stages.size(); ++k)
    std::printf("  stage %zu         %s: %d load steps, %zu fixed degrees of freedom%s\n", k + 1,
                p.stages[k].name.c_str(), p.stages[k].steps, p.stages[k].loading.fixed.size(),
                p.stages[k].loading.force.empty() ? "" : ", external forces");
  if (const auto& d = p.scene.damage) {
    if (d->criterion == "instability") std::printf("  damage          instability, s_max = %g\n", d->s_max);
    if (d->criterion == "stress" && d->fracture_energy > 0.0)
      std::printf("  damage          stress, f_t = %g Pa; broken bonds soften, G_f = %g J/m^2\n", d->f_t, d->fracture_energy);
    else if (d->criterion == "stress")
      std::printf("  damage          stress, f_t = %g Pa\n", d->f_t);
    if (d->criterion == "stretch" && d->G_c <= 0.0) std::printf("  damage          stretch, s_c = %g\n", d->s_c);
    if (d->criterion == "stretch" && d->G_c > 0.0)
      std::printf("  damage          stretch, s_c = %.4g from G_c = %g J/m^2 (bond-based calibration by the bulk "
                  "modulus, %s influence, delta = %.4g m the median family radius)\n",
                  d->s_c, d->G_c, influence_name(scene.discretization.weight), d->G_c_delta);
  }
  const bool newton_solve = scene.solver.type == "newton" || scene.solver.check == "newton";
  std::printf("  solver          %s%s%s\n", scene.solver.type.c_str(),
              newton_solve ? ", Newton's linear solver " : "", newton_solve ? scene.solver.linear_solver.c_str() : "");
  std::printf("  assembled operators and fields:\n");
  std::size_t total = 0;
  const Model& model = p.physics();
  for (const auto& m : model.memory()) {
    std::printf("    %-30s %10.2f MiB  (%.1f bytes per bond)\n", m.first.c_str(), mb(m.second),
                double(m.second) / p.bonds);
    total += m.second;
  }
  std::printf("    %-30s %10.2f MiB\n", "solver state (u, v, f, ...)",
              mb(model.dofs() * 6 * sizeof(double)));
  total += model.dofs() * 6 * sizeof(double);
  const bool newton = solver_of(scene).jacobian || scene.solver.check == "newton";
  if (newton) {
    // The Jacobian's pattern, as the Newton solver will build it (values included).
    const StaticSystem system(p.physics(), p.loading);
    const std::size_t bytes = system.jacobian().memory_bytes();
    std::printf("    %-30s %10.2f MiB  (%zu nonzeros; the LU factors come on top, typically\n"
                "    %-30s several times this in 2-D and more in 3-D)\n",
                "Newton Jacobian (CSR, 64-bit)", mb(bytes), system.jacobian().col.size(), "");
    total += bytes;
  }
  // The model's first item, the Newton Jacobian when no Newton solve needs it, the model's others.
  std::vector<std::string> items = model.not_assembled();
  if (!newton) items.insert(items.begin() + std::min<std::size_t>(1, items.size()), "Newton Jacobian (no newton solver)");
  std::string not_assembled;
  for (const auto& item : items) not_assembled += (not_assembled.empty() ? "" : ", ") + item;
  if (!not_assembled.empty()) std::printf("  not assembled: %s\n", not_assembled.c_str());
  std::printf("  total           %.2f MiB (%.1f bytes per bond)\n", mb(total), double(total) / p.bonds);
  // A body from files has no estimate before building (its size is in the file): a figure
  // here (the bare process's) read as one beside "no estimate".
  if (estimate.known)
    std::printf("  peak memory     %.2f MiB (VmHWM, the process so far), estimated before building %.2f MiB\n",
                mb(peak_resident_bytes()), mb(estimate.bytes));
  else
    std::printf("  peak memory     %.2f MiB (VmHWM, the process so far; a body from files is not estimated before "
                "building)\n",
                mb(peak_resident_bytes()));
  for (const auto& probe : p.probes) {
    if (probe.spec.is_line) {
      std::printf("  probe %-20s line, %zu particle(s)\n", probe.spec.name.c_str(), probe.particles.size());
      continue;
    }
    // Where a point probe's value comes from: its particle, or the point through it.
    const int d = p.cloud.dim;
    const double* x = p.cloud.point(probe.particles[0]);
    double r2 = 0.0;
    for (int a = 0; a < d; ++a) r2 += (x[a] - probe.spec.point[a]) * (x[a] - probe.spec.point[a]);
    char at[96];
    if (d == 3) std::snprintf(at, sizeof at, "%g, %g, %g", x[0], x[1], x[2]);
    else std::snprintf(at, sizeof at, "%g, %g", x[0], x[1]);
    std::printf("  probe %-20s point, particle %u at (%s), %.3g m from the point: %s\n", probe.spec.name.c_str(),
                static_cast<unsigned>(probe.particles[0]), at, std::sqrt(r2),
                probe.spec.reconstruct ? "reconstructed at the point" : "its value is read at the particle");
  }
  std::printf("  setup time      %.3f s\n", timer.total());
  if (opt.ranks > 0) print_partition(p, opt.ranks);
  if (opt.spectrum) {
    std::fflush(stdout);
    print_spectrum(stiffness_spectrum(p.physics(), checked_loading(p)));
  }
  return 0;
}

}  // namespace perinom::cli
