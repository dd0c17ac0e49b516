// The seed every sampler starts from when it is given none: the solver's rays, a grid's
// hemisphere, a model's mean free path, the emergency check, the Python module. The
// same input gives the same answer for it, and no test may depend on its value:
// scripts/seed-audit.sh builds with another one (the CMake cache variable
// DYNRAD_DEFAULT_SEED, compiled into default_seed.cpp alone, so changing it rebuilds
// one file) and runs the whole suite.
#pragma once

#include <cstdint>

namespace dynrad {

std::uint64_t default_seed();

}  // namespace dynrad
