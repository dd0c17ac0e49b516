// libFuzzer target for the reader `dynrad view` checks a .glb with (mesh/io/read_glb.h): the
// input bytes are the file. InputError is the expected answer to bad input and is
// caught here. Anything else is a bug the fuzzer reports: another exception escaping, a
// crash, a sanitizer finding, or a file accepted that the page could not show: no
// triangles, no vertices, bounds that are not finite, a scalar attribute without values.
#include "mesh/core/error.h"
#include "mesh/io/read_glb.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

[[noreturn]] void bug(const char* what) {
  std::fprintf(stderr, "fuzz: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const dynrad::GlbSummary s = dynrad::glb_summary_from_memory(bytes, "fuzz.glb");
    if (s.triangles == 0 || s.vertices == 0 || s.primitives == 0) bug("accepted a file with nothing to show");
    if (s.bounds.empty() || !dynrad::is_finite(s.bounds.lo) || !dynrad::is_finite(s.bounds.hi))
      bug("accepted positions whose bounds are not finite");
    for (const auto& [name, values] : s.scalars) {
      if (values.empty()) bug("a scalar attribute without values");
      for (float v : values)
        if (!std::isfinite(v)) bug("a scalar value that is not finite");
    }
  } catch (const dynrad::InputError&) {
    // Refused with a message: what bad input should get.
  }
  return 0;
}
