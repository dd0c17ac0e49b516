// A parallel loop over indices that stays on the calling thread when the loop is
// short. The solver's loops run once or more per level of every shot; many levels
// hold a handful of elements, and waking the worker threads for them costs more than
// the work. The body must not depend on which thread runs it.
#pragma once

#include <tbb/parallel_for.h>

#include <cstddef>

namespace dynrad::rad {

template <class Body>
void parallel_for_index(std::size_t count, std::size_t serial_below, const Body& body) {
  if (count < serial_below) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  tbb::parallel_for(std::size_t(0), count, body);
}

}  // namespace dynrad::rad
