#pragma once
// The stability check as the perinom program prints it: `perinom check --spectrum`, and the
// warning `perinom run` gives before a static solve with the improved or strong formulation.
#include "perinom/scene/problem.hpp"
#include "perinom/solvers/spectrum.hpp"

namespace perinom::cli {

/// The loading whose free dofs the check reduces to: the scene's, or its first stage's.
const Loading& checked_loading(const Problem& p);

/// The report, a line a quantity, then "stable" or "UNSTABLE: ...".
void print_spectrum(const SpectrumReport& r);

/// For the improved and strong formulations (non-symmetric K), before a static solve: runs
/// the check when the scene is within its size limit and prints a warning (stderr) when it
/// finds negative or complex eigenvalues; above the limit, prints once that the formulation
/// may be unstable and the check was skipped. Nothing for symmetric formulations.
void warn_if_unstable(Problem& p);

}  // namespace perinom::cli
