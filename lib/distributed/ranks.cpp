#include "perinom/distributed/ranks.hpp"

#include <cstdlib>

#include "../solvers/petsc_plugin.hpp"
#include "perinom/solvers/petsc.hpp"

namespace perinom {
namespace {

/// The module, under mpirun only: a one-process run never loads PETSc for these.
const detail::PetscPlugin* distributed() {
  if (mpirun_processes() <= 1) return nullptr;
  return &detail::petsc_plugin("a run on " + std::to_string(mpirun_processes()) + " MPI ranks");
}

}  // namespace

long mpirun_processes() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* v = std::getenv(name)) return std::strtol(v, nullptr, 10);
  return 1;
}

long mpirun_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK"})
    if (const char* v = std::getenv(name)) return std::strtol(v, nullptr, 10);
  return 0;
}

Ranks mpi_ranks() {
  Ranks r;
  if (const detail::PetscPlugin* p = distributed()) p->world(&r.rank, &r.size);
  return r;
}

Halo::Halo(std::size_t owned, const std::vector<std::int64_t>& ghosts, int block, double* values) {
  if (const detail::PetscPlugin* p = distributed()) vec_ = p->halo_create(owned, ghosts.data(), ghosts.size(), block, values);
}

Halo::~Halo() {
  if (vec_) distributed()->halo_destroy(vec_);
}

void Halo::update() {
  if (vec_) distributed()->halo_update(vec_);
}

void Halo::add_to_owners() {
  if (vec_) distributed()->halo_add_to_owners(vec_);
}

double sum_over_ranks(double v) {
  if (const detail::PetscPlugin* p = distributed()) p->reduce(&v, 1, false);
  return v;
}

double max_over_ranks(double v) {
  if (const detail::PetscPlugin* p = distributed()) p->reduce(&v, 1, true);
  return v;
}

void sum_over_ranks(double* values, int count) {
  if (const detail::PetscPlugin* p = distributed()) p->reduce(values, count, false);
}

void max_over_ranks(double* values, int count) {
  if (const detail::PetscPlugin* p = distributed()) p->reduce(values, count, true);
}

std::vector<double> gather_on_root(const std::vector<double>& mine) {
  const detail::PetscPlugin* p = distributed();
  if (!p) return mine;
  int rank = 0, size = 1;
  p->world(&rank, &size);
  const double total = sum_over_ranks(static_cast<double>(mine.size()));
  std::vector<double> all(rank == 0 ? static_cast<std::size_t>(total) : 0);
  p->gather(mine.data(), mine.size(), all.data());
  return all;
}

void barrier() {
  if (const detail::PetscPlugin* p = distributed()) p->barrier();
}

void abort_ranks(int code) {
  if (mpirun_processes() > 1 && petsc_available()) detail::petsc_plugin("abort_ranks").abort_ranks(code);
}

}  // namespace perinom
