#pragma once
/// @file The distributed path's communication, in the PETSc module (internal to lib/solvers):
/// ghosted vectors over the caller's arrays, reductions and a gather, on PETSc's world.
#include <cstddef>
#include <cstdint>

namespace perinom::detail {

/// This process's rank and the number of ranks (starts PETSc, and with it MPI).
void world(int* rank, int* size);
/// A ghosted vector of block size `block` over `values` (owned * block values, then count *
/// block for the ghosts, whose block indices along the distributed numbering are `ghosts`);
/// the ranks' owned blocks follow each other in rank order.
void* halo_create(std::size_t owned, const std::int64_t* ghosts, std::size_t count, int block, double* values);
/// The ghosts' values from their owners (a forward scatter).
void halo_update(void* halo);
/// Each ghost's value added into its owner's (a reverse scatter); the ghosts keep theirs.
void halo_add_to_owners(void* halo);
void halo_destroy(void* halo);
/// values[0..count) summed (or their largest, with max) over the ranks, on every rank.
void reduce(double* values, int count, bool max);
/// Each rank's `count` values, in rank order, into `root` on rank 0 (unused elsewhere).
void gather(const double* owned, std::size_t count, double* root);
void barrier();
/// Ends every rank with exit code `code` (MPI_Abort) once PETSc runs; nothing before.
void abort_ranks(int code);

}  // namespace perinom::detail
