// The explicit time loops allocate nothing: every workspace is sized before the first
// iteration. Global operator new is replaced in this test program to count allocations
// (it counts for every test, and for the library too, whose calls bind to these
// definitions); the observer, called once per iteration, reads the counter inside the loop.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdlib>
#include <new>

#include "perinom/scene/problem.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/solvers/verlet.hpp"

namespace {
std::atomic<long> allocations{0};

void* counted(std::size_t n, std::size_t align = 0) {
  ++allocations;
  void* p = nullptr;
  if (align > alignof(std::max_align_t)) {
    if (posix_memalign(&p, align, n ? n : 1) != 0) p = nullptr;
  } else {
    p = std::malloc(n ? n : 1);
  }
  if (!p) throw std::bad_alloc();
  return p;
}
}  // namespace

// Every replaceable form, nothrow ones included (Catch2 uses new (std::nothrow)): a form left
// out would come from the runtime and meet our free(), which AddressSanitizer reports as an
// alloc-dealloc mismatch.
void* nothrow_counted(std::size_t n, std::size_t align = 0) noexcept {
  try {
    return counted(n, align);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}
void* operator new(std::size_t n) { return counted(n); }
void* operator new[](std::size_t n) { return counted(n); }
void* operator new(std::size_t n, std::align_val_t a) { return counted(n, std::size_t(a)); }
void* operator new[](std::size_t n, std::align_val_t a) { return counted(n, std::size_t(a)); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return nothrow_counted(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return nothrow_counted(n); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return nothrow_counted(n, std::size_t(a));
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return nothrow_counted(n, std::size_t(a));
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }

using namespace perinom;

namespace {

/// Counts the allocations between the observer's calls at iterations `from` and `to`.
struct LoopCounter {
  std::int64_t from, to;
  long at_from = -1, at_to = -1;
  Observer observer() {
    Observer o;
    o.every = 1;
    o.call = [this](std::int64_t it, double, const std::vector<double>&) {
      if (it == from) at_from = allocations.load();
      if (it == to) at_to = allocations.load();
    };
    return o;
  }
};

}  // namespace

TEST_CASE("the counter sees allocations (the test can fail)", "[solvers]") {
  const long before = allocations.load();
  auto* v = new std::vector<double>(1000);
  delete v;
  CHECK(allocations.load() - before >= 2);
}

TEST_CASE("ADR and Verlet iterations allocate nothing", "[solvers]") {
  for (const char* variant : {"improved, fused S, support at the face", "assembled S",
                              "classical, matrix-free S", "single-precision weights",
                              "consistent, Galerkin supports at the face"}) {
    std::vector<std::string> set = {"discretization.dx=0.004"};
    if (std::string(variant).find("consistent") != 0) set.push_back("model.formulation=improved");
    if (std::string(variant).find("assembled") == 0) set.push_back("model.stabilization_storage=assembled");
    if (std::string(variant).find("classical") == 0)
      set.insert(set.end(), {"model.formulation=classical", "model.stabilization_storage=matrix_free"});
    if (std::string(variant).find("single") == 0) set.push_back("model.operator_order=1");
    if (std::string(variant).find("single") == 0) set.push_back("model.weight_precision=single");
    const Scene scene = read_scene(PERINOM_SOURCE_DIR "/examples/uniaxial_compression.yaml", set);
    Problem p = build_problem(scene);
    std::vector<double> u;
    AdrOptions adr;
    adr.tolerance = 0.0;  // run every iteration
    adr.max_iterations = 120;
    LoopCounter c{5, 120};
    const SolveReport rep = solve_adr(p.as<CorrespondenceModel>(), p.loading, adr, u, nullptr, c.observer());
    INFO(variant);
    REQUIRE(rep.iterations == 120);
    REQUIRE(c.at_from >= 0);
    CHECK(c.at_to - c.at_from == 0);

    std::vector<double> v;
    u.assign(p.as<CorrespondenceModel>().dofs(), 0.0);
    VerletOptions verlet;
    verlet.steps = 120;
    // The improved formulation gains energy in Verlet (issue 14) and its guard would stop the
    // run before step 120; this test counts allocations, not energy.
    verlet.energy_check = false;
    LoopCounter c2{5, 120};
    solve_verlet(p.as<CorrespondenceModel>(), p.loading, verlet, u, v, nullptr, c2.observer());
    REQUIRE(c2.at_from >= 0);
    CHECK(c2.at_to - c2.at_from == 0);
  }
}
