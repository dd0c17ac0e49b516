// The process's memory, as Linux reports it in /proc: what the solver's memory budget
// and the reports read.
#pragma once

#include <cstddef>

namespace dynrad::rad {

// Resident memory of this process in bytes (Linux /proc; 0 where unknown).
std::size_t resident_memory();
// The process's peak resident memory so far (VmHWM; 0 where unknown).
std::size_t peak_resident_memory();

}  // namespace dynrad::rad
