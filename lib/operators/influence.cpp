#include "perinom/operators/influence.hpp"

#include <cmath>

namespace perinom {

double influence(Influence kind, double r, double delta) {
  switch (kind) {
    case Influence::constant: return 1.0;
    case Influence::inverse_distance: return delta / r;
    case Influence::inverse_square: return (delta / r) * (delta / r);
    case Influence::gaussian: return std::exp(-4.0 * r * r / (delta * delta));
  }
  return 1.0;
}

const char* influence_name(Influence kind) {
  switch (kind) {
    case Influence::constant: return "constant";
    case Influence::inverse_distance: return "inverse_distance";
    case Influence::inverse_square: return "inverse_square";
    case Influence::gaussian: return "gaussian";
  }
  return "?";
}

bool parse_influence(const std::string& name, Influence& kind) {
  if (name == "constant") kind = Influence::constant;
  else if (name == "inverse_distance") kind = Influence::inverse_distance;
  else if (name == "inverse_square") kind = Influence::inverse_square;
  else if (name == "gaussian") kind = Influence::gaussian;
  else return false;
  return true;
}

}  // namespace perinom
