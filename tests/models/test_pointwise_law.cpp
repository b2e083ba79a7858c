// The pointwise law interface (pointwise_law.hpp) driven alone, and through the model.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

#include "../support/clouds.hpp"
#include "perinom/materials/material_point.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/models/elastic_points.hpp"
#include "perinom/models/finite_rotation.hpp"
#include "perinom/models/plastic_points.hpp"
#include "perinom/neighbors/search.hpp"

using namespace perinom;

namespace {

LinearElastic elastic(int dim, PlaneCondition plane) {
  LinearElastic m;
  m.E = 30e6, m.nu = 0.25, m.density = 2000, m.dim = dim, m.plane = plane;
  return m;
}

// A Drucker-Prager law of seed 000 Table 2 that yields at strains of a few 1e-3.
DruckerPrager drucker_prager() {
  DruckerPrager dp = seed_biaxial_test(5).material;  // hardening, so the tangent is regular
  dp.cohesion = 20e3;
  return dp;
}

// N gradients: a compression along x with shear, scaled per particle.
std::vector<double> gradients(int d, std::size_t n, double scale) {
  const auto r = test::random_field(n * d * d, 1.0, 3);
  std::vector<double> H(n * d * d);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < d * d; ++k) H[i * d * d + k] = scale * ((k == 0 ? -3.0 : 0.0) + 0.5 * r[i * d * d + k]);
  return H;
}

// Every particle's stresses through the interface, in two blocks (as the model calls it).
std::vector<double> stresses(PointwiseLaw& law, const std::vector<double>& H) {
  std::vector<double> P(H.size());
  const std::size_t n = law.size(), half = n / 2;
  law.stresses(0, half, H.data(), P.data());
  law.stresses(half, n, H.data(), P.data());
  return P;
}

// |dP/dH - finite differences of the interface's stresses| / |dP/dH| at H (central, step h).
double tangent_defect(PointwiseLaw& law, const std::vector<double>& H, double h) {
  const int d = law.dim(), d2 = d * d, d4 = d2 * d2;
  const std::size_t n = law.size();
  std::vector<double> C;
  const std::size_t stride = law.tangents(H.data(), C);
  double err = 0.0, ref = 0.0;
  for (int ce = 0; ce < d2; ++ce) {
    auto Hp = H, Hm = H;
    for (std::size_t i = 0; i < n; ++i) Hp[i * d2 + ce] += h, Hm[i * d2 + ce] -= h;
    const auto Pp = stresses(law, Hp), Pm = stresses(law, Hm);
    for (std::size_t i = 0; i < n; ++i)
      for (int ab = 0; ab < d2; ++ab) {
        const double fd = (Pp[i * d2 + ab] - Pm[i * d2 + ab]) / (2.0 * h);
        const double c = C[i * stride + ab * d2 + ce];
        err = std::max(err, std::abs(c - fd));
        ref = std::max(ref, std::abs(c));
      }
  }
  (void)d4;
  return err / ref;
}

}  // namespace

TEST_CASE("elastic points answer with LinearElastic's stress, energy, tangent and Cauchy stress", "[models]") {
  for (const auto& [dim, plane] : {std::pair{2, PlaneCondition::strain}, std::pair{2, PlaneCondition::stress},
                                   std::pair{3, PlaneCondition::none}}) {
    const LinearElastic m = elastic(dim, plane);
    const std::size_t n = 7;
    ElasticPoints law(m, n);
    PointwiseLaw& l = law;
    CHECK_FALSE(l.has_history());
    const int d2 = dim * dim;
    const auto H = gradients(dim, n, 1e-3);
    const auto P = stresses(l, H);
    std::vector<double> psi(n), sigma(n * 9), C;
    l.energies(0, n, H.data(), psi.data());
    l.cauchy(H.data(), sigma.data());
    REQUIRE(l.tangents(H.data(), C) == 0);
    std::vector<double> Ce(d2 * d2);
    m.tangent(Ce.data());
    CHECK(C == Ce);
    for (std::size_t i = 0; i < n; ++i) {
      double Pe[9], se[9];
      m.stress(H.data() + i * d2, Pe);
      m.stress3(H.data() + i * d2, se);
      for (int k = 0; k < d2; ++k) CHECK(P[i * d2 + k] == Pe[k]);
      for (int k = 0; k < 9; ++k) CHECK(sigma[i * 9 + k] == se[k]);
      CHECK(psi[i] == m.energy(H.data() + i * d2));
    }
    std::vector<double> field;
    l.field("stress", H.data(), field);
    CHECK(field == sigma);
    CHECK(tangent_defect(l, H, 1e-6) < 1e-8);
  }
}

namespace {

// Particles yield at this H: batch stresses, tangents, Cauchy stresses, energies and commit
// through the interface against the per-particle calls of a twin law (PlasticPoints or
// FiniteRotationLaw); `points` are the Drucker-Prager points inside each.
template <class Law>
void check_per_particle(int dim, Law& direct, PointwiseLaw& law, PlasticPoints& direct_points,
                        PlasticPoints& through_points) {
  const std::size_t n = law.size();
  const int d2 = dim * dim, d4 = d2 * d2;
  REQUIRE(law.has_history());
  const auto H = gradients(dim, n, 2e-3);
  const auto P = stresses(law, H);
  std::vector<double> psi(n), sigma(n * 9), C;
  REQUIRE(law.tangents(H.data(), C) == std::size_t(d4));
  law.cauchy(H.data(), sigma.data());
  for (std::size_t i = 0; i < n; ++i) {
    double Pd[9], Cd[81], sd[9];
    direct.stress(i, H.data() + i * d2, Pd);
    direct.tangent(i, H.data() + i * d2, Cd);
    direct.cauchy(i, H.data() + i * d2, sd);
    for (int k = 0; k < d2; ++k) CHECK(P[i * d2 + k] == Pd[k]);
    for (int k = 0; k < d4; ++k) CHECK(C[i * d4 + k] == Cd[k]);
    for (int k = 0; k < 9; ++k) CHECK(sigma[i * 9 + k] == sd[k]);
  }
  law.energies(0, n, H.data(), psi.data());
  for (std::size_t i = 0; i < n; ++i) CHECK(psi[i] == direct_points.stored_energy(i));
  law.commit(), direct_points.commit();
  for (std::size_t i = 0; i < n; ++i) {
    CHECK(through_points.committed()[i].law.xi == direct_points.committed()[i].law.xi);
    CHECK(through_points.committed()[i].law.xi > 0.0);
  }
}

// Drucker-Prager points in return-map mode, alone or inside a finite-rotation wrapper.
std::unique_ptr<PointwiseLaw> drucker_prager_law(Kinematics kin, int dim, std::size_t n) {
  auto points = std::make_unique<PlasticPoints>(drucker_prager(), dim, n);
  points->set_mode(PlasticMode::return_map);
  if (kin == Kinematics::small_strain) return points;
  return std::make_unique<FiniteRotationLaw>(std::move(points), dim);
}

PlasticPoints& points_of(PointwiseLaw& law) {
  if (auto* wrapper = dynamic_cast<FiniteRotationLaw*>(&law)) return dynamic_cast<PlasticPoints&>(wrapper->inner());
  return dynamic_cast<PlasticPoints&>(law);
}

}  // namespace

TEST_CASE("Drucker-Prager points through the law interface equal their per-particle calls", "[models]") {
  for (const int dim : {2, 3}) {
    const std::size_t n = 6;
    INFO("dim " << dim);
    auto direct = drucker_prager_law(Kinematics::small_strain, dim, n);
    auto through = drucker_prager_law(Kinematics::small_strain, dim, n);
    check_per_particle(dim, points_of(*direct), *through, points_of(*direct), points_of(*through));
  }
}

TEST_CASE("the finite-rotation wrapper through the law interface equals its per-particle calls", "[models]") {
  for (const int dim : {2, 3}) {
    const std::size_t n = 6;
    INFO("dim " << dim);
    auto direct = drucker_prager_law(Kinematics::finite_rotation, dim, n);
    auto through = drucker_prager_law(Kinematics::finite_rotation, dim, n);
    check_per_particle(dim, dynamic_cast<FiniteRotationLaw&>(*direct), *through, points_of(*direct), points_of(*through));
  }
}

TEST_CASE("the law's tangent is the finite difference of its stresses, elastic and plastic", "[models]") {
  // Plastic: from a committed yielded state, loaded further (return map, as Newton does).
  for (const Kinematics kin : {Kinematics::small_strain, Kinematics::finite_rotation})
    for (const int dim : {2, 3}) {
      const std::size_t n = 4;
      auto law = drucker_prager_law(kin, dim, n);
      const auto H1 = gradients(dim, n, 1.5e-3), H2 = gradients(dim, n, 2.5e-3);
      stresses(*law, H1);
      law->commit();
      REQUIRE(points_of(*law).committed()[0].law.xi > 0.0);
      INFO("dim " << dim << (kin == Kinematics::finite_rotation ? " finite rotation" : " small strain"));
      CHECK(tangent_defect(*law, H2, 1e-9) < 1e-5);
    }
}

TEST_CASE("the finite-rotation wrapper's checkpoint restores its states, F included", "[models]") {
  // Yield, commit, save; then move on and commit again; restore: the stresses at a new H are
  // those of the saved state (bitwise), and a history of the wrapped law's size is refused.
  const int dim = 2;
  const std::size_t n = 5;
  auto law = drucker_prager_law(Kinematics::finite_rotation, dim, n);
  LawHistory& history = *law->history();
  REQUIRE(history.values_per_particle() == points_of(*law).values_per_particle() + 9);
  stresses(*law, gradients(dim, n, 2e-3));
  law->commit();
  const HistoryState saved = history.save_history();
  const auto H = gradients(dim, n, 3e-3);
  const auto expected = stresses(*law, H);
  stresses(*law, gradients(dim, n, -1e-3));
  law->commit();
  REQUIRE(stresses(*law, H) != expected);
  history.restore_history(saved);
  CHECK(stresses(*law, H) == expected);
  CHECK(history.save_history().values == saved.values);
  // F is in the checkpoint: the saved values hold F = I + H at the first state, not I.
  CHECK(saved.values[points_of(*law).values_per_particle()] != 1.0);
  CHECK_THROWS_AS(history.restore_history(points_of(*law).save_history()), std::invalid_argument);
  history.reset_history();
  std::vector<double> xi;
  law->field("eq_plastic_strain", H.data(), xi);
  CHECK(*std::max_element(xi.begin(), xi.end()) == 0.0);
}

TEST_CASE("a law with history changes its committed states only at commit", "[models]") {
  const int dim = 2;
  const std::size_t n = 3;
  PlasticPoints points(drucker_prager(), dim, n);
  points.set_mode(PlasticMode::return_map);
  PointwiseLaw& law = points;
  const auto fields = law.fields();
  REQUIRE(fields.front().name == "stress");
  const auto H = gradients(dim, n, 2e-3), zero = std::vector<double>(H.size(), 0.0);
  std::vector<double> xi, sigma_before(n * 9), sigma_after(n * 9), psi(n);
  // Stresses, energies, tangents and Cauchy stresses evaluate; none commits.
  stresses(law, H);
  law.energies(0, n, H.data(), psi.data());
  std::vector<double> C;
  law.tangents(H.data(), C);
  law.cauchy(H.data(), sigma_before.data());
  law.field("eq_plastic_strain", zero.data(), xi);
  for (const double v : xi) CHECK(v == 0.0);
  CHECK(points.trial()[0].law.xi > 0.0);
  // Commit: the trial states become the committed ones, and the fields show them.
  law.commit();
  law.field("eq_plastic_strain", zero.data(), xi);
  std::vector<double> yielded, eps_p, flagged;
  law.field("yielded", zero.data(), yielded);
  law.field("plastic_strain", zero.data(), eps_p);
  law.field("lbc_flagged", zero.data(), flagged);
  REQUIRE(xi.size() == n);
  REQUIRE(eps_p.size() == n * 9);
  for (std::size_t i = 0; i < n; ++i) {
    CHECK(xi[i] == points.committed()[i].law.xi);
    CHECK(xi[i] > 0.0);
    CHECK(yielded[i] == 1.0);
    CHECK(flagged[i] == 0.0);
    CHECK(eps_p[i * 9] == points.committed()[i].law.eps_p[0]);
  }
  // Unloading to H = 0 from the committed state leaves a residual stress; the Cauchy stress
  // is evaluated, never kept.
  law.cauchy(zero.data(), sigma_after.data());
  law.cauchy(zero.data(), sigma_before.data());
  CHECK(sigma_after == sigma_before);
  CHECK(points.committed()[0].law.xi == xi[0]);
  CHECK_THROWS_AS(law.field("no such field", zero.data(), xi), std::invalid_argument);
}

namespace {

// A third law, written as a user would: twice the elastic stress (nothing else in the model).
class TwiceElastic final : public PointwiseLaw {
 public:
  TwiceElastic(const LinearElastic& m, std::size_t n) : inner_(m, n) {}
  int dim() const override { return inner_.dim(); }
  std::size_t size() const override { return inner_.size(); }
  bool has_history() const override { return false; }
  void stresses(std::size_t begin, std::size_t end, const double* H, double* P) override {
    inner_.stresses(begin, end, H, P);
    const std::size_t d2 = std::size_t(dim()) * dim();
    for (std::size_t k = begin * d2; k < end * d2; ++k) P[k] *= 2.0;
  }
  void energies(std::size_t begin, std::size_t end, const double* H, double* psi) override {
    inner_.energies(begin, end, H, psi);
    for (std::size_t i = begin; i < end; ++i) psi[i] *= 2.0;
  }
  std::size_t tangents(const double* H, std::vector<double>& C) const override {
    const std::size_t stride = inner_.tangents(H, C);
    for (auto& c : C) c *= 2.0;
    return stride;
  }
  void cauchy(const double* H, double* sigma) const override {
    inner_.cauchy(H, sigma);
    for (std::size_t k = 0; k < size() * 9; ++k) sigma[k] *= 2.0;
  }
  void commit() override {}
  std::size_t memory_bytes() const override { return 0; }
  std::vector<LawField> fields() const override { return {{"stress", 9}}; }
  void field(const std::string& name, const double* H, std::vector<double>& values) const override {
    if (name != "stress") throw std::invalid_argument(name);
    values.resize(size() * 9);
    cauchy(H, values.data());
  }

 private:
  ElasticPoints inner_;
};

}  // namespace

TEST_CASE("a model given a third law uses it in force, energy, stress and tangent", "[models]") {
  // No stabilization (it uses the material's moduli): every term is twice the elastic one.
  const PointCloud c = test::lattice(3, 5, 0.3);
  const Families f = radius_families(c, 2.015);
  const LinearElastic m = elastic(3, PlaneCondition::none);
  const CorrespondenceOptions opt{Influence::inverse_square, 0.0};
  CorrespondenceModel plain(c, f, m, opt);
  CorrespondenceModel twice(c, f, m, opt, {}, {}, std::make_unique<TwiceElastic>(m, c.size()));
  CHECK(twice.plastic() == nullptr);
  const auto u = test::random_field(c.size() * 3, 1e-4, 5);
  std::vector<double> f1(u.size()), f2(u.size()), s1, s2;
  plain.internal_force(u.data(), f1.data());
  twice.internal_force(u.data(), f2.data());
  for (std::size_t k = 0; k < u.size(); ++k) CHECK(f2[k] == 2.0 * f1[k]);
  CHECK(twice.energy(u.data()) == Approx(2.0 * plain.energy(u.data())).epsilon(1e-14));
  plain.stress3(u.data(), s1);
  twice.stress3(u.data(), s2);
  for (std::size_t k = 0; k < s1.size(); ++k) CHECK(s2[k] == 2.0 * s1[k]);
  plain.prepare_tangent(u.data());
  twice.prepare_tangent(u.data());
  // The rows may be visited concurrently: kept, then compared.
  std::vector<std::vector<double>> rows1(c.size()), rows2(c.size());
  plain.visit_tangent_rows([&](std::size_t i, const std::vector<ParticleId>&, const std::vector<double>& b) { rows1[i] = b; });
  twice.visit_tangent_rows([&](std::size_t i, const std::vector<ParticleId>&, const std::vector<double>& b) { rows2[i] = b; });
  for (std::size_t i = 0; i < c.size(); ++i) {
    REQUIRE(rows2[i].size() == rows1[i].size());
    for (std::size_t k = 0; k < rows1[i].size(); ++k) CHECK(rows2[i][k] == 2.0 * rows1[i][k]);
  }
  CHECK_THROWS_AS(CorrespondenceModel(c, f, m, opt, {}, {}, std::make_unique<ElasticPoints>(m, c.size() - 1)),
                  std::invalid_argument);
}

TEST_CASE("a law with history given to the model drives the model's history, with no plasticity option",
          "[models]") {
  const PointCloud c = test::lattice(2, 6, 0.2);
  const Families f = radius_families(c, 2.015);
  const LinearElastic m = elastic(2, PlaneCondition::strain);
  const CorrespondenceOptions opt{Influence::inverse_square, 0.5};
  CorrespondenceModel elastic_model(c, f, m, opt);
  CHECK(elastic_model.history() == nullptr);
  CorrespondenceModel model(c, f, m, opt, {}, {}, std::make_unique<PlasticPoints>(drucker_prager(), 2, c.size()));
  ModelHistory* h = model.history();
  REQUIRE(h != nullptr);
  REQUIRE(model.plastic() != nullptr);
  // Loaded into the plastic range under the return map, committed: the history moved.
  h->set_history_mode(HistoryMode::return_map);
  CHECK(model.plastic()->mode() == PlasticMode::return_map);
  std::vector<double> u(c.size() * 2);
  for (std::size_t i = 0; i < c.size(); ++i) u[i * 2 + 1] = -0.02 * c.x[i * 2 + 1];
  h->commit(u.data());
  const std::vector<double> xi = h->history_variable();
  REQUIRE(xi.size() == c.size());
  CHECK(*std::max_element(xi.begin(), xi.end()) > 0.0);
  // Saved, reset, restored: the same committed numbers.
  const HistoryState saved = h->save_history();
  CHECK(saved.values.size() == c.size() * h->values_per_particle());
  h->reset_history();
  const std::vector<double> virgin = h->history_variable();
  CHECK(*std::max_element(virgin.begin(), virgin.end()) == 0.0);
  h->restore_history(saved);
  CHECK(h->history_variable() == xi);
  CHECK_THROWS_AS(h->restore_history(HistoryState{{1.0}, {0}}), std::invalid_argument);
}
