#include "petsc_session.hpp"

#include "perinom/core/error.hpp"

namespace perinom {
namespace {

/// The message of the error being raised (PETSc's own, e.g. "Unknown KSP type: gmress"),
/// kept for check() rather than printed.
std::string& last_message() {
  static std::string message;
  return message;
}

PetscErrorCode keep_message(MPI_Comm, int, const char*, const char*, PetscErrorCode n, PetscErrorType type,
                            const char* message, void*) {
  if (type == PETSC_ERROR_INITIAL) last_message() = message ? message : "";
  return n;
}

}  // namespace

namespace detail {

void check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  std::string message = std::string("PETSc: ") + what + " failed" + (text ? std::string(": ") + text : std::string());
  if (!last_message().empty()) message += " (" + last_message() + ")";
  last_message().clear();
  throw SolveError(message);
}

void start_petsc(const std::string& options) {
  PetscBool started = PETSC_FALSE;
  PetscInitialized(&started);
  if (!started) {
    // No signal handler of PETSc's (the sanitizers and the program keep theirs). PETSc
    // reads PETSC_OPTIONS from the environment itself.
    check(PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr), "PetscOptionsSetValue");
  }
  if (!options.empty()) check(PetscOptionsInsertString(nullptr, options.c_str()), "reading --petsc-options");
  if (started) return;
  check(PetscInitializeNoArguments(), "PetscInitialize");
  PetscPushErrorHandler(keep_message, nullptr);
}

void end_petsc() {
  PetscBool started = PETSC_FALSE, ended = PETSC_FALSE;
  PetscInitialized(&started);
  PetscFinalized(&ended);
  if (started && !ended) PetscFinalize();
}

}  // namespace detail
}  // namespace perinom
