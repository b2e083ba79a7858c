#pragma once
/// @file The MPI ranks of a distributed run (issue 19) and what they exchange: a halo over a
/// rank's local array, reductions and a gather. Backed by the PETSc module (PETSc's world);
/// a build without PETSc runs on one rank and refuses more, naming why.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace perinom {

/// The number of processes mpirun started, from its environment (1 without mpirun); reading
/// it starts nothing.
long mpirun_processes();
/// This process's rank as mpirun's environment gives it (0 without mpirun); starts nothing.
long mpirun_rank();

struct Ranks {
  int rank = 0, size = 1;
};
/// This process's rank among the ranks; starts PETSc (and MPI) under mpirun, nothing without.
Ranks mpi_ranks();

/// A rank's local array in the distributed numbering: `owned` blocks of `block` values
/// first (the rank's contiguous range; ranks follow each other in rank order), then one
/// block for each of `ghosts` (their positions along that numbering). update() fills the
/// ghost blocks from their owners, in place; add_to_owners() adds each ghost block into its
/// owner's block (the ghosts keep their values). The array must outlive the halo and not move.
class Halo {
 public:
  Halo(std::size_t owned, const std::vector<std::int64_t>& ghosts, int block, double* values);
  ~Halo();
  Halo(const Halo&) = delete;
  Halo& operator=(const Halo&) = delete;
  void update();
  void add_to_owners();

 private:
  void* vec_ = nullptr;
};

/// The sum (or the largest) of a value over the ranks, on every rank.
double sum_over_ranks(double v);
double max_over_ranks(double v);
/// The same for `count` values at once, in place.
void sum_over_ranks(double* values, int count);
void max_over_ranks(double* values, int count);
/// Each rank's values, concatenated in rank order, on rank 0 (empty elsewhere).
std::vector<double> gather_on_root(const std::vector<double>& mine);
/// Every rank waits for the others.
void barrier();
/// Under mpirun, once the ranks run: ends every rank with exit code `code` (MPI_Abort), so
/// that an error on some ranks never leaves the others waiting in an exchange. Returns
/// without mpirun or before the ranks start (every rank then fails alike).
void abort_ranks(int code);

}  // namespace perinom
