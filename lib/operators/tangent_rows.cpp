#include "perinom/operators/tangent_rows.hpp"

#include "operator_access.hpp"
#include "perinom/operators/row_accumulator.hpp"

namespace perinom {

void for_each_tangent_row(
    const NonlocalOperator& G, const PointwiseTangent& tangent, const Stabilization* S,
    const std::function<void(std::size_t, const std::vector<ParticleId>&,
                             const std::vector<double>&)>& visit,
    const StrongRows* strong, const ScalarCsr* S0, const double* local) {
  const int d = G.dim(), d2 = d * d, d3 = d2 * d;
  const std::size_t n = G.rows();
  const BondGraph& g = G.graph();
  using A = OperatorAccess;
#pragma omp parallel
  {
    RowAccumulator acc(n, d2);
    std::vector<double> T(d3), blocks;
    double coef[3], scratch[3];
    // Adds sum_e T[a c e] G_e[m][j] for j in {m} + H_m: a dependence on u through grad u
    // at m.
    auto add_gradient_columns = [&](std::size_t m, const double* T) {
      auto add_column = [&](ParticleId j, const double* gmj) {
        double* K = acc.at(j);
        for (int ac = 0; ac < d2; ++ac) {
          double s = 0.0;
          for (int e = 0; e < d; ++e) s += T[ac * d + e] * gmj[e];
          K[ac] += s;
        }
      };
      add_column(static_cast<ParticleId>(m), A::diagonal(G, m));
      for (Offset k = g.begin(m); k < g.end(m); ++k)
        if (g.alive(k)) add_column(g.col(k), A::weights(G, k, scratch));
    };
    // Adds sum_b coef[b] C_m[a b c e] G_e[m][j] for j in {m} + H_m: the row's dependence
    // on u through the stress P_m, weighted by coef (a d-vector, volume included).
    auto add_source = [&](std::size_t m, const double* coef) {
      const double* C = tangent.C + tangent.stride * m;
      for (int a = 0; a < d; ++a)
        for (int c = 0; c < d; ++c)
          for (int e = 0; e < d; ++e) {
            double s = 0.0;
            for (int b = 0; b < d; ++b) s += coef[b] * C[((a * d + b) * d + c) * d + e];
            T[(a * d + c) * d + e] = s;
          }
      add_gradient_columns(m, T.data());
    };
#pragma omp for schedule(dynamic, 64)
    for (std::size_t i = 0; i < n; ++i) {
      if (strong && strong->in_band[i]) {
        const double vi = tangent.volume[i];
        const double* mi = strong->normal_over_h + i * d;
        for (int b = 0; b < d; ++b) coef[b] = -vi * A::diagonal(G, i)[b] + vi * mi[b];
        add_source(i, coef);
        for (Offset k = g.begin(i); k < g.end(i); ++k) {
          if (!g.alive(k)) continue;
          for (int b = 0; b < d; ++b) coef[b] = -vi * A::weight(G, k, b);
          add_source(g.col(k), coef);
        }
      } else {
        for (int b = 0; b < d; ++b) coef[b] = tangent.volume[i] * A::diagonal(G, i)[b];
        add_source(i, coef);
        for (Offset t = g.dual_begin(i); t < g.dual_end(i); ++t) {
          if (!g.dual_alive(t)) continue;
          const std::size_t m = g.dual_col(t);
          for (int b = 0; b < d; ++b) coef[b] = tangent.volume[m] * A::dual_weight(G, t, b);
          add_source(m, coef);
        }
      }
      if (local) add_gradient_columns(i, local + i * d3);
      if (S) S->add_row(i, acc, d);
      if (S0)
        for (Offset k = S0->offsets[i]; k < S0->offsets[i + 1]; ++k) {
          double* block = acc.at(S0->cols[k]);
          for (int a = 0; a < d; ++a) block[a * (d + 1)] += S0->values[k];
        }
      acc.finish();
      blocks.resize(acc.cols().size() * d2);
      for (std::size_t k = 0; k < acc.cols().size(); ++k)
        for (int ac = 0; ac < d2; ++ac) blocks[k * d2 + ac] = acc.block(k)[ac];
      visit(i, acc.cols(), blocks);
      acc.clear();
    }
  }
}

}  // namespace perinom
