// What the IES and EULUMDAT readers share (internal to radiosity/photometry*.cpp):
// numbers as read from a file with the line they came from, the symmetries both formats
// declare and the expansion of a file's planes to the whole sphere, and the checks that
// end every read (flux integral and warnings).
#pragma once

#include "radiosity/sources/photometry.h"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace dynrad::rad::detail {

// A number as written in the file, and the 1-based line it is on.
struct Token {
  std::string_view text;
  std::size_t line = 0;
};

// Splits `text` into words separated by whitespace (and by commas when
// `comma_separates`), each with its line; a line break is "\n", "\r\n" or a lone "\r".
// Starts at byte `from`, which is on line `first_line`.
std::vector<Token> tokenize(std::string_view text, std::size_t from, std::size_t first_line, bool comma_separates);

// Reads `text` as a whole decimal number (an optional sign, digits, a point or, when
// `decimal_comma`, a comma, an exponent). False if it is not one; `value` may then be
// anything, including a non-finite value from "nan" or "inf", which callers refuse.
bool parse_number(std::string_view text, bool decimal_comma, double& value);

// The symmetries of a type C distribution, and the half-open domain of C the file's
// planes cover (every other C is the mirror image of one in it):
enum class CSymmetry {
  axial,     // one plane, C irrelevant
  none,      // [0, 360)
  c0_c180,   // mirror in the C0-C180 plane: [0, 180]
  c90_c270,  // mirror in the C90-C270 plane: [90, 270]
  quadrant,  // both planes: [0, 90]
};

// Fills p.c_angles and p.candela (the whole sphere) from the file's planes: `angles`
// ascending within the symmetry's domain, `values` one row of p.gamma_angles.size()
// per plane, in cd. The caller has checked the angles' range and order.
void expand_planes(Photometry& p, CSymmetry symmetry, const std::vector<double>& angles,
                   const std::vector<double>& values);

// Sets p.flux = integrate_flux(p) and warns (in p.warnings) when it disagrees with
// p.stated_flux by more than 2%, or exceeds p.lamp_flux by more than 2% when
// `check_lamp_flux`.
void finish(Photometry& p, bool check_lamp_flux);

// "12.5" with up to 6 significant digits, for messages.
std::string number_text(double value);

}  // namespace dynrad::rad::detail
