// libFuzzer target for the photometry readers (DYNRAD_FUZZ_PHOTOMETRY: ies or ldt).
// The input bytes are an IES or EULUMDAT file's text, parsed from memory.
//
// InputError is the expected answer to bad input and is caught here. Anything else is
// a bug the fuzzer reports: another exception escaping, a crash, a sanitizer finding,
// or a read that succeeds with a distribution that is not one: a NaN, negative or
// infinite intensity or flux, angles out of order, a table of the wrong size.
#include "mesh/core/error.h"
#include "radiosity/sources/photometry.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#ifndef DYNRAD_FUZZ_PHOTOMETRY
#error "DYNRAD_FUZZ_PHOTOMETRY must name the format: ies or ldt"
#endif

namespace {

constexpr std::string_view kFormat = DYNRAD_FUZZ_PHOTOMETRY;

[[noreturn]] void bug(const char* what) {
  std::fprintf(stderr, "fuzz: %s\n", what);
  std::abort();
}

void check(const dynrad::rad::Photometry& p) {
  if (p.c_angles.empty() || p.gamma_angles.size() < 2 || p.candela.size() != p.c_angles.size() * p.gamma_angles.size())
    bug("the table's size does not match its angles");
  for (std::size_t i = 0; i < p.c_angles.size(); ++i)
    if (!(p.c_angles[i] >= 0 && p.c_angles[i] < 360) || (i > 0 && !(p.c_angles[i] > p.c_angles[i - 1])))
      bug("C angles out of [0, 360) or not ascending");
  for (std::size_t i = 0; i < p.gamma_angles.size(); ++i)
    if (!(p.gamma_angles[i] >= 0 && p.gamma_angles[i] <= 180) ||
        (i > 0 && !(p.gamma_angles[i] > p.gamma_angles[i - 1])))
      bug("gamma angles out of [0, 180] or not ascending");
  double peak = 0;
  for (const double v : p.candela) {
    if (!(v >= 0) || !std::isfinite(v)) bug("a candela value is negative or not finite");
    peak = std::max(peak, v);
  }
  for (const double c : {0.0, 12.5, 90.0, 181.0, 270.0, 359.99, -45.0})
    for (const double g : {0.0, 0.5, 30.0, 89.9, 90.0, 135.0, 180.0}) {
      const double v = p.intensity(c, g);
      if (!(v >= 0 && v <= peak)) bug("intensity is NaN, negative or above the table's peak");
    }
  const double flux = dynrad::rad::integrate_flux(p);
  if (!(flux >= 0) || !std::isfinite(flux) || flux != p.flux) bug("flux is NaN, negative or not integrate_flux");
  for (const double t : {-10.0, 0.0, 33.0, 90.0, 200.0})
    if (!std::isfinite(p.tilt_factor(t)) || p.tilt_factor(t) < 0) bug("tilt factor is NaN or negative");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const dynrad::rad::Photometry p =
        kFormat == "ies" ? dynrad::rad::parse_ies("fuzz.ies", text) : dynrad::rad::parse_eulumdat("fuzz.ldt", text);
    check(p);
  } catch (const dynrad::InputError&) {
    // Refused with a message: the right answer to a bad file.
  }
  return 0;
}
