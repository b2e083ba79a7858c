// K_T = T^T K T assembled straight from the tangent rows equals the product of the assembled
// matrices, with supports on the particles and at the faces (where T couples dofs).
#include <catch2/catch.hpp>

#include <string>

#include "../../lib/solvers/galerkin.hpp"
#include "perinom/scene/problem.hpp"

using namespace perinom;

TEST_CASE("the reduced stiffness from the rows equals T^T K T", "[solvers][galerkin]") {
  for (const std::string at : {"layer", "face"})
    for (const std::string dim : {"2", "3"}) {
      INFO(dim << "-D, supports at the " << at);
      const std::string box = dim == "2" ? "{min: [0, 0], max: [0.006, 0.010]}" : "{min: [0, 0, 0], max: [0.004, 0.004, 0.006]}";
      const std::string fix = dim == "2" ? "[x, y]" : "[x, y, z]";
      const std::string scene = "name: s\ndimension: " + dim + "\ngeometry: {box: " + box +
                                "}\ndiscretization: {dx: 0.001, horizon: {ratio: 3.015}, jitter: 0.2}\n"
                                "material: {type: linear_elastic, E: 30.0e6, nu: 0.25, density: 2000}\n"
                                "model: {formulation: consistent}\nboundary:\n"
                                "  - {region: bottom, fix: " + fix + ", at: " + at + "}\n"
                                "  - {region: left, fix: [x], at: " + at + "}\n"
                                "  - {region: top, pressure: 1.0e5}\n";
      Problem p = build_problem(parse_scene(scene, "scene"));
      TangentModel& model = p.physics();
      std::vector<double> u(model.dofs(), 0.0);
      model.prepare_tangent(u.data());
      const auto index = detail::free_index(model.dofs(), p.loading);
      int free = 0;
      for (const auto k : index) free += k >= 0 ? 1 : 0;
      const detail::Reduction red = detail::reduce(model.dofs(), p.loading, index, free);
      const detail::Sparse K = detail::assemble_stiffness(model);
      const detail::Sparse expected = red.T.transpose() * K * red.T;
      const detail::RowSparse got = detail::reduced_stiffness(model, detail::TRows(red.T, index));
      REQUIRE(got.rows() == expected.rows());
      // Rows sorted, no repeated column.
      for (int r = 0; r < got.rows(); ++r)
        for (int k = got.outerIndexPtr()[r] + 1; k < got.outerIndexPtr()[r + 1]; ++k)
          REQUIRE(got.innerIndexPtr()[k - 1] < got.innerIndexPtr()[k]);
      CHECK(got.nonZeros() == expected.nonZeros());  // the same pattern, no entry more
      const double difference = (detail::Sparse(got) - expected).norm();
      CHECK(difference <= 1e-13 * expected.norm());
      if (at == "face") CHECK(red.T.nonZeros() > red.T.cols());  // T couples dofs there
    }
}
