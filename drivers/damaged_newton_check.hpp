#pragma once
// solver.check: newton for a load path whose bonds broke (issue 18): Newton solves the final
// loads again on the model as it ended, broken bonds and detached particles included.
#include <vector>

#include "perinom/io/json_writer.hpp"
#include "perinom/scene/problem.hpp"
#include "difference.hpp"

namespace perinom::cli {

/// The equilibrium of the broken body at the last stage's full load, by Newton (KINSOL + the
/// assembled tangent of the refreshed rows), one load step per stage (the body is linear
/// elastic: the scene refuses the check with drucker_prager), against the load path's u. The
/// detached particles carry nothing, so their rows are empty: Newton holds them where the path
/// left them (their live bonds still enter their neighbours' gradients). A body that broke into
/// a piece without supports has a singular tangent: newton_error then says so. A stress that
/// ends below kUnloadedEnd of the largest along the path (`stress_path`: a body broken
/// through carries rounding) is compared over that largest.
io::Json damaged_newton_check(Problem& p, const std::vector<double>& u, const PathScale& stress_path);

}  // namespace perinom::cli
