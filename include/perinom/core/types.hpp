#pragma once
/// @file Index types. Particle ids are 32-bit (2^31 particles is far beyond one
/// machine); bond offsets are 64-bit because bond counts pass 2^31 at about
/// 17 million particles in 3-D.
#include <cstdint>

namespace perinom {

using ParticleId = std::int32_t;  ///< a particle, or a column of an operator
using Offset = std::int64_t;      ///< a position in a bond (CSR) array

}  // namespace perinom
