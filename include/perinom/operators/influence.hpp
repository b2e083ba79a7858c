#pragma once
/// @file Influence functions w(|xi|) (THEORY sec. 1).
#include <string>

namespace perinom {

enum class Influence { constant, inverse_distance, inverse_square, gaussian };

/// w(r) for a bond of length r in a family of radius delta.
/// constant: 1; inverse_distance: delta / r; inverse_square: (delta / r)^2 (the scale
/// delta^2 keeps the weights dimensionless and cancels in every operator);
/// gaussian: exp(-4 r^2 / delta^2).
double influence(Influence kind, double r, double delta);

/// Parses "constant", "inverse_distance", "inverse_square", "gaussian"; false if unknown.
bool parse_influence(const std::string& name, Influence& kind);
/// The name parse_influence reads.
const char* influence_name(Influence kind);

}  // namespace perinom
