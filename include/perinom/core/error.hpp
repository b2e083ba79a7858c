#pragma once
/// @file Errors that carry context: which key, which particle, which sizes.
#include <cstdint>
#include <stdexcept>
#include <string>

namespace perinom {

/// Bad input: a malformed scene, an impossible discretization, an unwritable folder.
/// The command line maps it to exit code 2.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

/// A solve that went wrong (NaN or Inf in the state, a diverging iteration).
/// The command line maps it to exit code 3, after writing the last good state.
class SolveError : public std::runtime_error {
 public:
  explicit SolveError(const std::string& what) : std::runtime_error(what) {}
};

/// An InputError or SolveError every MPI rank raises alike: decided on values the ranks share
/// (MUMPS's count of null pivots, a residual summed over the ranks, a scene every rank reads).
/// The command line prints it once, on rank 0, and every rank ends with its exit code on its
/// own, without MPI_Abort (whose banner, and the message once per rank, buried the one line
/// that mattered). In a one-process run they are their base classes.
class InputErrorOnEveryRank : public InputError {
 public:
  using InputError::InputError;
};
class SolveErrorOnEveryRank : public SolveError {
 public:
  using SolveError::SolveError;
};

/// A state failed the NaN/Inf guard: a force, an energy or a field to be written is not
/// finite. `step` is the iteration or time step that failed; the solver has put the last
/// state that passed the guard back into its output vectors.
class DivergenceError : public SolveError {
 public:
  DivergenceError(const std::string& what, std::int64_t step) : SolveError(what), step(step) {}
  std::int64_t step;
};

}  // namespace perinom
