#include "perinom/operators/tangent_rows.hpp"

#include <type_traits>

#include "operator_access.hpp"
#include "perinom/operators/row_accumulator.hpp"

namespace perinom {
namespace {

using A = OperatorAccess;

// Row i of K into an accumulator of d x d blocks; one per thread (it keeps scratch).
class TangentRowFill {
 public:
  TangentRowFill(const NonlocalOperator& G, const PointwiseTangent& tangent, const StabilizationTerm* S,
                 const StrongRows* strong, const double* local, bool stored_S0 = false)
      : G_(G), g_(G.graph()), tangent_(tangent), S_(S), S0_(stored_S0 && S ? S->stored() : nullptr), strong_(strong),
        local_(local), d_(G.dim()), T_(static_cast<std::size_t>(d_) * d_ * d_) {}

  void operator()(std::size_t i, RowAccumulator& acc) {
    const int d = d_;
    double coef[3];
    if (strong_ && strong_->in_band[i]) {
      const double vi = tangent_.volume[i];
      const double* mi = strong_->normal_over_h + i * d;
      for (int b = 0; b < d; ++b) coef[b] = -vi * A::diagonal(G_, i)[b] + vi * mi[b];
      add_source(i, coef, acc);
      for (Offset k = g_.begin(i); k < g_.end(i); ++k) {
        if (!g_.alive(k)) continue;
        for (int b = 0; b < d; ++b) coef[b] = -vi * A::weight(G_, k, b);
        add_source(g_.col(k), coef, acc);
      }
    } else {
      for (int b = 0; b < d; ++b) coef[b] = tangent_.volume[i] * A::diagonal(G_, i)[b];
      add_source(i, coef, acc);
      for (Offset t = g_.dual_begin(i); t < g_.dual_end(i); ++t) {
        if (!g_.dual_alive(t)) continue;
        const std::size_t m = g_.dual_col(t);
        for (int b = 0; b < d; ++b) coef[b] = tangent_.volume[m] * A::dual_weight(G_, t, b);
        add_source(m, coef, acc);
      }
    }
    if (local_) add_gradient_columns(i, local_ + i * d * d * d, acc);
    if (S0_) add_stored_row(*S0_, i, acc, d);
    else if (S_) S_->add_row(i, acc, d);
  }

 private:
  // Adds sum_e T[a c e] G_e[m][j] for j in {m} + H_m: a dependence on u through grad u at m.
  void add_gradient_columns(std::size_t m, const double* T, RowAccumulator& acc) {
    if (d_ == 2) return add_gradient_columns(std::integral_constant<int, 2>{}, m, T, acc);
    if (d_ == 3) return add_gradient_columns(std::integral_constant<int, 3>{}, m, T, acc);
    add_gradient_columns(d_, m, T, acc);
  }
  // The same with the dimension a compile-time constant where it is one (Dim: int or
  // std::integral_constant), so the block loops unroll.
  template <class Dim>
  void add_gradient_columns(Dim dim, std::size_t m, const double* T, RowAccumulator& acc) {
    const int d = dim, d2 = d * d;
    double scratch[3];
    auto add_column = [&](ParticleId j, const double* gmj) {
      double* K = acc.at(j);
      for (int ac = 0; ac < d2; ++ac) {
        double s = 0.0;
        for (int e = 0; e < d; ++e) s += T[ac * d + e] * gmj[e];
        K[ac] += s;
      }
    };
    add_column(static_cast<ParticleId>(m), A::diagonal(G_, m));
    for (Offset k = g_.begin(m); k < g_.end(m); ++k)
      if (g_.alive(k)) add_column(g_.col(k), A::weights(G_, k, scratch));
  }

  // Adds sum_b coef[b] C_m[a b c e] G_e[m][j] for j in {m} + H_m: the row's dependence on u
  // through the stress P_m, weighted by coef (a d-vector, volume included).
  void add_source(std::size_t m, const double* coef, RowAccumulator& acc) {
    const int d = d_;
    const double* C = tangent_.C + tangent_.stride * m;
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < d; ++c)
        for (int e = 0; e < d; ++e) {
          double s = 0.0;
          for (int b = 0; b < d; ++b) s += coef[b] * C[((a * d + b) * d + c) * d + e];
          T_[(a * d + c) * d + e] = s;
        }
    add_gradient_columns(m, T_.data(), acc);
  }

  const NonlocalOperator& G_;
  const BondGraph& g_;
  PointwiseTangent tangent_;
  const StabilizationTerm* S_;
  const ScalarCsr* S0_;  // S's stored rows, when they are to be read as stored
  const StrongRows* strong_;
  const double* local_;
  int d_;
  std::vector<double> T_;
};

}  // namespace

void for_each_tangent_row(const NonlocalOperator& G, const PointwiseTangent& tangent, const StabilizationTerm* S,
                          const BlockRowVisitor& visit, const StrongRows* strong, const double* local) {
  for_each_block_row(G.rows(), G.rows(), G.dim() * G.dim(),
                     [&] { return RowFill(TangentRowFill(G, tangent, S, strong, local)); }, visit);
}

void for_each_tangent_row(const std::vector<ParticleId>& rows, const NonlocalOperator& G,
                          const PointwiseTangent& tangent, const StabilizationTerm* S, const BlockRowVisitor& visit,
                          bool sorted) {
  for_each_block_row(rows, G.rows(), G.dim() * G.dim(),
                     [&] { return RowFill(TangentRowFill(G, tangent, S, nullptr, nullptr, true)); }, visit, sorted);
}

}  // namespace perinom
