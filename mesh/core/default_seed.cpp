// The default seed (default_seed.h); the build sets DYNRAD_DEFAULT_SEED for this file.
#include "mesh/core/default_seed.h"

#ifndef DYNRAD_DEFAULT_SEED
#define DYNRAD_DEFAULT_SEED 1
#endif

namespace dynrad {

std::uint64_t default_seed() { return DYNRAD_DEFAULT_SEED; }

}  // namespace dynrad
