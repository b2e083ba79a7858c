#pragma once
// A support held at its particles (`at: layer`, the default) where a face could hold it: the
// consistent formulation balances the body's stress at the face (its tractions and `at: face`
// reactions act there through the particles' reconstruction), so a reaction put on the
// particles instead is out of balance with the stress next to it. A 20 x 4 mm bar in uniform
// tension, its left side held at the layer, came out 1.23 / 0.61 / 0.30% short at the tip at
// dx = 1 / 0.5 / 0.25 mm (measured from the held particles), the held layer's stress 0.46 of
// the load, with exit 0; at the face it is exact. Run and check say so before the solve.
#include <string>

#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// "" or the note (without a prefix) for a correspondence body with the consistent
/// formulation whose side or group supports (fix or displacement) are held at the layer.
std::string layer_support_note(const Problem& p);

}  // namespace perinom::cli
