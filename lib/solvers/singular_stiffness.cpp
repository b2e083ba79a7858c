#include "singular_stiffness.hpp"

#include <algorithm>

#include "perinom/core/error.hpp"
#include "perinom/models/model_history.hpp"

namespace perinom::detail {

std::string singular_stiffness(const Model& model, int step, const std::string& factor) {
  const std::string singular = "the stiffness is singular (" + factor + ")";
  const ModelHistory* plastic = model.history();
  if (!plastic)
    throw InputErrorOnEveryRank("Newton: " + singular + ": the body can move without deforming; a boundary condition is "
                     "probably missing (" + model.support_advice() + ")");
  const std::vector<double> xi = plastic->history_variable();
  double yielded = std::any_of(xi.begin(), xi.end(), [](double x) { return x > 0.0; }) ? 1.0 : 0.0;
  model.max_across_ranks(&yielded, 1);
  const std::string where = " in load step " + std::to_string(step);
  // A small-strain body's stiffness changes only as it yields: past the first step (it
  // factored then) the trial states' yielding made it singular, whether or not earlier steps
  // had committed plastic strain.
  if (yielded > 0.0 || (step > 1 && !model.turns_with_body()))
    return "Newton: " + singular + where + ", as the body yields: its tangent has lost all stiffness along "
           "a mechanism; the last good state is load step " +
           std::to_string(step - 1);
  // Under finite rotation the tangent also changes with the state, through limit and
  // bifurcation points: a pressed block under dead pressures, turned elastically, was told it
  // yielded.
  if (step > 1)
    return "Newton: " + singular + where + ", where nothing had yielded: either the body yields into a mechanism "
           "at this step's load, or the tangent has passed a limit or bifurcation point (a body that buckles, "
           "or is turned under its loads); the last good state is load step " +
           std::to_string(step - 1);
  return "Newton: " + singular + where + ": either a boundary condition is missing (the body can move without "
         "deforming: `run` warns before the solve when the supports leave a rigid motion free), or the body yields "
         "into a mechanism at this step's load (more load steps show where)";
}

}  // namespace perinom::detail
