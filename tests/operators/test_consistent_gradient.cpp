// The consistent gradient G~ (consistent_gradient.hpp): its rows stay exact for linear fields,
// its columns satisfy the discrete divergence theorem sum_i V_i G~[i][j] = c_j, and the
// stiffness it makes is symmetric. The uncorrected G fails the column test near the surface,
// which is the surface effect the correction removes.
#include <catch2/catch.hpp>

#include <cmath>

#include "../support/clouds.hpp"
#include "perinom/geometry/boundary_facets.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/operators/boundary_trace.hpp"
#include "perinom/operators/consistent_gradient.hpp"

using namespace perinom;

namespace {

struct Case {
  int dim;
  int n;
  double jitter;
  double ratio;
  bool hole;
};

BoxGeometry box_of(const Case& c) {
  BoxGeometry box;
  box.dim = c.dim;
  for (int a = 0; a < c.dim; ++a) box.max[a] = c.n;
  if (c.hole) box.holes.push_back(Hole{c.dim == 2 ? Hole::Shape::circle : Hole::Shape::cylinder,
                                       {0.5 * c.n, 0.5 * c.n, 0.5 * c.n}, 0.22 * c.n, 2});
  return box;
}

/// max_j |sum_i V_i G_b[i][j] - c_j[b]| over max |c|, for weights g on the families.
double column_defect(const PointCloud& cloud, const Families& f, const std::vector<double>& g,
                     const std::vector<double>& c) {
  const int d = cloud.dim;
  std::vector<double> s(cloud.size() * d, 0.0);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    for (Offset k = f.begin(i); k < f.end(i); ++k)
      for (int b = 0; b < d; ++b) {
        s[f.neighbors[k] * d + b] += cloud.volume[i] * g[k * d + b];
        s[i * d + b] -= cloud.volume[i] * g[k * d + b];
      }
  double worst = 0.0;
  for (std::size_t k = 0; k < s.size(); ++k) worst = std::max(worst, std::abs(s[k] - c[k]));
  return worst / test::max_abs(c);
}

/// max over particles of |sum_j g_ij (x) xi_ij - I|.
double linear_defect(const PointCloud& cloud, const Families& f, const std::vector<double>& g) {
  const int d = cloud.dim;
  double worst = 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    for (int a = 0; a < d; ++a)
      for (int b = 0; b < d; ++b) {
        double s = a == b ? -1.0 : 0.0;
        for (Offset k = f.begin(i); k < f.end(i); ++k)
          s += g[k * d + b] * (cloud.x[f.neighbors[k] * d + a] - cloud.x[i * d + a]);
        worst = std::max(worst, std::abs(s));
      }
  return worst;
}

}  // namespace

TEST_CASE("lattice facets close the body: the discrete divergence theorem holds", "[geometry][consistent]") {
  for (const Case c : {Case{2, 12, 0.0, 3.015, false}, Case{2, 16, 0.3, 3.015, true}, Case{3, 6, 0.3, 2.015, true}}) {
    const BoxGeometry box = box_of(c);
    const PointCloud cloud = make_lattice(box, 1.0, c.jitter, 3);
    const BoundaryFacets f = lattice_facets(box, cloud);
    CHECK(divergence_theorem_defect(f, cloud) <= 1e-13);
    // Every facet sits on the box surface or borders a dropped cell.
    for (std::size_t k = 0; k < f.size(); ++k) CHECK(f.area[k] > 0.0);
  }
}

TEST_CASE("the corrected gradient stays exact for linear fields and meets the column constraints", "[operators][consistent]") {
  for (const Case c : {Case{2, 12, 0.0, 3.015, false}, Case{2, 16, 0.3, 3.015, true}, Case{3, 7, 0.3, 2.015, false}}) {
    const BoxGeometry box = box_of(c);
    const PointCloud cloud = make_lattice(box, 1.0, c.jitter, 3);
    const Families families = test::brute_force_radius(cloud, c.ratio);
    const BondWeights weights = bond_weights(cloud, families, Influence::inverse_square);
    const NonlocalOperator G(cloud, families, weights);
    const BoundaryTrace trace(lattice_facets(box, cloud), cloud, G);
    const std::vector<double> measure = trace.column_measure(cloud.size());
    std::vector<double> g(G.bonds() * c.dim);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      Offset k = families.begin(i);
      G.visit_row(i, [&](ParticleId j, const double* w) {
        if (static_cast<std::size_t>(j) == i) return;  // the diagonal
        for (int b = 0; b < c.dim; ++b) g[k * c.dim + b] = w[b];
        ++k;
      });
    }
    ConsistencyReport report;
    const auto corrected = consistent_gradient_weights(cloud, families, weights, G, G, measure, {}, &report);
    const double before = column_defect(cloud, families, g, measure);
    const double after = column_defect(cloud, families, corrected, measure);
    WARN("dim " << c.dim << " jitter " << c.jitter << (c.hole ? " with a hole" : "") << ": column defect "
                << before << " -> " << after << ", |G~ - G|/|G| " << report.relative_change << ", "
                << report.iterations << " CG iterations");
    CHECK(report.converged);
    CHECK(before > 1e-2);  // the surface effect of the uncorrected G
    CHECK(after <= 1e-10);
    CHECK(linear_defect(cloud, families, corrected) <= 1e-10);
    CHECK(report.rhs_defect <= 1e-10);
  }
}

TEST_CASE("the consistent stiffness is symmetric, for operator orders 1 and 2", "[models][consistent]") {
  for (int order : {1, 2}) {
    const Case c{2, 10, 0.25, 3.015, false};
    const BoxGeometry box = box_of(c);
    const PointCloud cloud = make_lattice(box, 1.0, c.jitter, 5);
    const Families families = test::brute_force_radius(cloud, c.ratio);
    CorrespondenceOptions opt;
    opt.formulation = Formulation::consistent;
    opt.operator_order = order;
    const LinearElastic material{1.0e6, 0.3, 1.0, 2, PlaneCondition::strain};
    CorrespondenceModel model(cloud, families, material, opt, {}, lattice_facets(box, cloud));
    const std::size_t n = cloud.size() * 2;
    std::vector<double> K(n * n, 0.0);
    model.visit_tangent_rows([&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
      for (std::size_t k = 0; k < cols.size(); ++k)
        for (int a = 0; a < 2; ++a)
          for (int e = 0; e < 2; ++e) K[(i * 2 + a) * n + cols[k] * 2 + e] += blocks[(k * 2 + a) * 2 + e];
    });
    double asym = 0.0, norm = 0.0;
    for (std::size_t r = 0; r < n; ++r)
      for (std::size_t s = 0; s < n; ++s) {
        asym = std::max(asym, std::abs(K[r * n + s] - K[s * n + r]));
        norm = std::max(norm, std::abs(K[r * n + s]));
      }
    CHECK(asym <= 1e-12 * norm);
  }
}
