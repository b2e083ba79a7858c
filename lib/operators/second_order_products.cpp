// The four products of SecondOrderOperator. They live apart from the assembly so that, like
// the first-order products, they are compiled for this machine's processor (PERINOM_NATIVE)
// while the assembly, which uses Eigen, is not (lib/CMakeLists.txt says why); the gather
// kernels they share with GradientOperator are then compiled one way in both.
#include "perinom/operators/second_order_operator.hpp"

#include <stdexcept>
#include <string>
#include <type_traits>

#include "gather_kernels.hpp"

namespace perinom {
namespace {

template <int V>
using Int = std::integral_constant<int, V>;

// Calls run(Int<M>, Int<NC>) for the runtime weights per bond m and components nc: the gather
// kernels are templates on both.
template <class Run>
void dispatch(int m, int nc, Run&& run) {
  auto with_nc = [&](auto M) {
    if (nc == 1) return run(M, Int<1>{});
    if (nc == 2) return run(M, Int<2>{});
    if (nc == 3) return run(M, Int<3>{});
    throw std::invalid_argument("SecondOrderOperator: no kernel for " + std::to_string(nc) +
                                " components (1, 2 or 3)");
  };
  if (m == 2) return with_nc(Int<2>{});
  if (m == 3) return with_nc(Int<3>{});
  if (m == 6) return with_nc(Int<6>{});
  throw std::invalid_argument("SecondOrderOperator: no kernel for " + std::to_string(m) +
                              " weights per bond");
}

}  // namespace

void SecondOrderOperator::apply(const Block& b, const double* f, int nc, double* out) const {
  dispatch(b.m, nc, [&](auto M, auto NC) {
    kernels::gradient<decltype(M)::value, decltype(NC)::value>(rows(), offsets_.data(), cols_.data(),
                                                               b.w.data(), f, out);
  });
}

void SecondOrderOperator::transpose(const Block& b, const double* q, int nc, double* out,
                                    const std::vector<ParticleId>* subset) const {
  const std::size_t n = subset ? subset->size() : rows();
  const ParticleId* r = subset ? subset->data() : nullptr;
  dispatch(b.m, nc, [&](auto M, auto NC) {
    kernels::transpose<decltype(M)::value, decltype(NC)::value>(
        n, r, t_offsets_.data(), t_cols_.data(), b.t_w.data(), b.diag.data(), q, out);
  });
}

void SecondOrderOperator::gradient(const double* f, int nc, double* out) const {
  apply(grad_, f, nc, out);
}

void SecondOrderOperator::gradient_transpose(const double* q, int nc, double* out,
                                             const std::vector<ParticleId>* subset) const {
  transpose(grad_, q, nc, out, subset);
}

namespace {

void require_hessian(bool assembled) {
  if (!assembled)
    throw std::logic_error(
        "SecondOrderOperator: the Hessian weights were not assembled (SecondOrderOptions::hessian "
        "is false)");
}

}  // namespace

void SecondOrderOperator::hessian(const double* f, int nc, double* out) const {
  require_hessian(has_hessian());
  apply(hess_, f, nc, out);
}

void SecondOrderOperator::hessian_transpose(const double* q, int nc, double* out,
                                            const std::vector<ParticleId>* subset) const {
  require_hessian(has_hessian());
  transpose(hess_, q, nc, out, subset);
}

}  // namespace perinom
