// EULUMDAT (.ldt) photometric files: one field per line, in a fixed order
// (Stockmar 1990; the field list as DIALux and AGi32 document it):
//    1 manufacturer / format identification   2 Ityp (type, 0-3)   3 Isym (symmetry, 0-4)
//    4 Mc, number of C-planes in 0-360        5 Dc, their spacing (0: uneven)
//    6 Ng, number of gamma angles             7 Dg, their spacing (0: uneven)
//    8 measurement report   9 luminaire name   10 luminaire number   11 file name
//   12 date / user
//   13-15 luminaire length (or diameter), width (0: round), height, mm
//   16-17 luminous area length (or diameter), width (0: round), mm
//   18-21 luminous area height at C0, C90, C180, C270, mm
//   22 downward flux fraction, %   23 light output ratio (LORL), %
//   24 conversion factor for the intensities   25 tilt during measurement
//   26 n, number of lamp sets; then 6 lines per set: number of lamps, lamp type, total
//      flux of the set (lm), colour temperature, colour rendering, wattage
//   then 10 direct ratios, the Mc C angles, the Ng gamma angles, and the intensities in
//   cd per 1000 lm of lamp flux, Ng per stored C-plane:
//     Isym 0: all Mc planes;  1: one plane;  2: C0 to C180 (Mc/2 + 1 planes);
//     3: C270 through C0 to C90 (Mc/2 + 1 planes: the spec's first index 3 Mc/4 + 1,
//        taken round the circle). Descriptions that say "C270 down to C90" (through
//        C180) store the same numbers: by the symmetry, I(270 + k Dc) = I(270 - k Dc).
//     4: C0 to C90 (Mc/4 + 1 planes).
// From the direct ratios on, numbers are read as a sequence (one per line as written,
// but a writer that puts several on a line is read the same). Decimal commas ("0,5")
// are read as points throughout; lines may end in CRLF, LF or CR.
//
// Candela = stored value x conversion factor x (total flux of all lamp sets) / 1000.
// A negative number of lamps marks absolute photometry in some writers' files (the
// "lamp flux" is then the luminaire's own, and the light output ratio 100%): the same
// formula gives the right candela, so the sign is accepted and otherwise ignored. More
// than one lamp set: their fluxes are added (a luminaire with two kinds of lamps), with
// a warning, since some writers list alternative equipment instead.
// The stated luminaire flux is LORL / 100 x the lamps' flux.
#include "mesh/core/error.h"
#include "radiosity/sources/photometry.h"
#include "radiosity/sources/photometry_parse.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

namespace dynrad::rad {
namespace {

using detail::number_text;
using detail::Token;

constexpr double kMaxCandela = 1e15;  // as for IES

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

class EulumdatParser {
 public:
  EulumdatParser(const std::string& path, std::string_view text) : path_(path), text_(text) {}

  Photometry parse() {
    p_.file = path_;
    p_.format = "EULUMDAT";
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);
    if (text_.find('\0') != std::string_view::npos)
      fail(0, "contains binary data (a NUL byte), so it is not an EULUMDAT text file.");

    text_line("the manufacturer");
    integer("the type indicator Ityp", 0, 3);
    const long isym = integer("the symmetry indicator Isym", 0, 4);
    const std::size_t mc_line = line_ + 1;
    const long mc = integer("the number of C-planes Mc", 1, 100000);
    number("the distance between C-planes Dc");
    const std::size_t ng_line = line_ + 1;
    const long ng = integer("the number of gamma angles Ng", 2, 100000);
    number("the distance between gamma angles Dg");
    text_line("the measurement report number");
    const std::string name(trimmed(text_line("the luminaire name")));
    const std::string catalogue(trimmed(text_line("the luminaire number")));
    p_.name = !name.empty() ? name : catalogue;
    text_line("the file name");
    text_line("the date / user");
    for (const char* what : {"the luminaire length", "the luminaire width", "the luminaire height"})
      non_negative(std::string(what) + " (mm)");
    const double area_length = non_negative("the luminous area length or diameter (mm)");
    const double area_width = non_negative("the luminous area width (mm)");
    double heights = 0;
    for (const char* plane : {"C0", "C90", "C180", "C270"})
      heights += non_negative(std::string("the luminous area height at ") + plane + " (mm)");
    if (area_width == 0 && area_length > 0) {
      p_.round = true;
      p_.length = p_.width = area_length / 1000;
    } else {
      p_.length = area_length / 1000;
      p_.width = area_width / 1000;
    }
    p_.height = heights / 4 / 1000;
    non_negative("the downward flux fraction (%)");
    const double lorl = non_negative("the light output ratio LORL (%)");
    const double conversion = number("the conversion factor for the intensities");
    if (!(conversion > 0)) fail(line_, "the conversion factor " + number_text(conversion) + " is not positive.");
    number("the tilt during measurement");
    const long sets = integer("the number of lamp sets n", 1, 100000);
    double flux = 0;
    for (long s = 0; s < sets; ++s) {
      const std::string set = " of lamp set " + std::to_string(s + 1);
      integer("the number of lamps" + set, -100000, 100000);
      text_line("the lamp type" + set);
      flux += non_negative("the total luminous flux" + set + " (lm)");
      text_line("the colour temperature" + set);
      text_line("the colour rendering" + set);
      text_line("the wattage" + set);  // not used; some writers add a unit
    }
    if (!(flux > 0) || !std::isfinite(flux))
      fail(line_, "the lamp sets' total luminous flux is " + number_text(flux) +
                      " lm, so the intensities (cd per 1000 lm) cannot be converted to candela. Give the lamps' flux.");
    if (sets > 1)
      p_.warnings.push_back(path_ + ": has " + std::to_string(sets) +
                            " lamp sets; the intensities are scaled by their total flux, " + number_text(flux) +
                            " lm. If the sets are alternatives rather than lamps fitted together, keep only the one "
                            "fitted.");
    p_.lamp_flux = flux;
    p_.stated_flux = lorl / 100 * flux;
    const double factor = conversion * flux / 1000;

    // The numbers: direct ratios, angles, intensities.
    tokens_ = detail::tokenize(text_, pos_, line_ + 1, false);
    const std::size_t planes = isym == 0   ? static_cast<std::size_t>(mc)
                               : isym == 1 ? 1
                               : isym == 4 ? static_cast<std::size_t>(mc / 4 + 1)
                                           : static_cast<std::size_t>(mc / 2 + 1);
    if ((isym == 2 || isym == 3) && mc % (isym == 2 ? 2 : 4) != 0)
      fail(mc_line, "Isym " + std::to_string(isym) + " needs a number of C-planes divisible by " +
                        (isym == 2 ? "2 (so that C180 is one of them)" : "4 (so that C90 and C270 are among them)") +
                        "; Mc is " + std::to_string(mc) + ".");
    if (isym == 4 && mc % 4 != 0)
      fail(mc_line, "Isym 4 needs a number of C-planes divisible by 4 (so that C90 is one of them); Mc is " +
                        std::to_string(mc) + ".");
    const std::size_t c_count = static_cast<std::size_t>(mc), g_count = static_cast<std::size_t>(ng);
    const std::size_t needed = 10 + c_count + g_count + planes * g_count;  // below 2^40
    if (needed > tokens_.size())
      fail(ng_line, "Mc = " + std::to_string(mc) + " C-planes and Ng = " + std::to_string(ng) +
                        " gamma angles with Isym " + std::to_string(isym) + " need " + std::to_string(needed) +
                        " numbers after the lamp sets (10 direct ratios, the angles, " + std::to_string(planes) +
                        " x " + std::to_string(ng) + " intensities), but only " + std::to_string(tokens_.size()) +
                        " follow. Is the file truncated?");
    for (int i = 0; i < 10; ++i) value("a direct ratio");

    std::vector<double> c(c_count);
    for (std::size_t i = 0; i < c_count; ++i) {
      c[i] = value("a C angle");
      if (c[i] < 0 || c[i] >= 360) fail(last_line(), "C angle " + number_text(c[i]) + " is outside 0 to 360 degrees.");
      if (i == 0 && c[i] != 0) fail(last_line(), "the first C angle is " + number_text(c[i]) + "; it must be 0.");
      if (i > 0 && !(c[i] - c[i - 1] >= 1e-6))
        fail(last_line(), "C angle " + number_text(c[i]) + " is not above the one before (" + number_text(c[i - 1]) +
                              "): C angles must ascend.");
    }
    std::vector<double>& gamma = p_.gamma_angles;
    gamma.resize(g_count);
    for (std::size_t i = 0; i < g_count; ++i) {
      gamma[i] = value("a gamma angle");
      if (gamma[i] < 0 || gamma[i] > 180)
        fail(last_line(), "gamma angle " + number_text(gamma[i]) +
                              " is outside 0 to 180 degrees (0 is straight down, 180 straight up).");
      if (i > 0 && !(gamma[i] - gamma[i - 1] >= 1e-6))
        fail(last_line(), "gamma angle " + number_text(gamma[i]) + " is not above the one before (" +
                              number_text(gamma[i - 1]) + "): gamma angles must ascend.");
    }

    // The stored planes' angles, in the symmetry's domain (see photometry_parse.h).
    std::vector<double> angles;
    detail::CSymmetry symmetry = detail::CSymmetry::none;
    const auto require = [&](std::size_t index, double angle) {
      if (std::abs(c[index] - angle) > 1e-6)
        fail(mc_line, "with Isym " + std::to_string(isym) + ", C angle number " + std::to_string(index + 1) + " of " +
                          std::to_string(mc) + " must be " + number_text(angle) + ", but it is " +
                          number_text(c[index]) + ". Check Mc and the C angles.");
    };
    switch (isym) {
      case 0:
        p_.symmetry = "none";
        symmetry = mc == 1 ? detail::CSymmetry::axial : detail::CSymmetry::none;
        angles = c;
        break;
      case 1:
        p_.symmetry = "about the vertical axis";
        symmetry = detail::CSymmetry::axial;
        angles = {0.0};
        break;
      case 2:
        p_.symmetry = "C0-C180 plane";
        symmetry = detail::CSymmetry::c0_c180;
        require(c_count / 2, 180);
        angles.assign(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(planes));
        break;
      case 3:
        p_.symmetry = "C90-C270 plane";
        symmetry = detail::CSymmetry::c90_c270;
        require(3 * c_count / 4, 270);
        require(c_count / 4, 90);
        // Stored from C270 round to C90; their mirror images 180 - C run from 270 down
        // to 90: the domain [90, 270], descending (reversed below).
        for (std::size_t j = 0; j < planes; ++j) {
          const double a = 180 - c[(3 * c_count / 4 + j) % c_count];
          angles.push_back(a < 90 - 1e-6 ? a + 360 : a);
        }
        break;
      default:
        p_.symmetry = "both planes";
        symmetry = detail::CSymmetry::quadrant;
        require(c_count / 4, 90);
        angles.assign(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(planes));
        break;
    }

    std::vector<double> values(planes * g_count);
    for (std::size_t i = 0; i < values.size(); ++i) {
      const double v = value("an intensity (cd/klm)");
      if (v < 0) fail(last_line(), "intensity " + number_text(v) + " cd/klm is negative.");
      values[i] = v * factor;
      if (!(values[i] <= kMaxCandela))
        fail(last_line(), "intensity " + number_text(v) + " cd/klm times the lamps' flux and conversion factor is " +
                              number_text(values[i]) + " cd, beyond any luminaire (1e15 cd). Check the lamp flux.");
    }
    if (isym == 3) {  // make the angles ascend, rows with them
      std::reverse(angles.begin(), angles.end());
      for (std::size_t j = 0; j < planes / 2; ++j)
        std::swap_ranges(values.begin() + static_cast<std::ptrdiff_t>(j * g_count),
                         values.begin() + static_cast<std::ptrdiff_t>((j + 1) * g_count),
                         values.begin() + static_cast<std::ptrdiff_t>((planes - 1 - j) * g_count));
    }
    for (std::size_t j = 1; j < angles.size(); ++j)
      if (!(angles[j] - angles[j - 1] >= 1e-6))  // Isym 3 across C0, which the check above did not see
        fail(mc_line, "the C angles stored with Isym " + std::to_string(isym) + " do not ascend round the circle.");
    if (next_ < tokens_.size())
      p_.warnings.push_back(path_ + ":" + std::to_string(tokens_[next_].line) + ": " +
                            std::to_string(tokens_.size() - next_) +
                            " more values after the intensities (Isym, Mc and Ng declare " +
                            std::to_string(values.size()) + ") are ignored.");
    detail::expand_planes(p_, symmetry, angles, values);
    detail::finish(p_, false);
    return std::move(p_);
  }

 private:
  [[noreturn]] void fail(std::size_t line, const std::string& what) const { throw InputError(path_, line, what); }

  // The next line, without its line break; `what` names it if the file has ended.
  std::string_view text_line(const std::string& what) {
    if (pos_ >= text_.size())
      fail(line_, "the file ends after line " + std::to_string(line_) + "; line " + std::to_string(line_ + 1) +
                      " should hold " + what + ". Is it truncated?");
    const std::size_t end = text_.find_first_of("\r\n", pos_);
    const std::string_view line =
        text_.substr(pos_, end == std::string_view::npos ? std::string_view::npos : end - pos_);
    pos_ = end == std::string_view::npos ? text_.size() : end + 1;
    if (end != std::string_view::npos && text_[end] == '\r' && pos_ < text_.size() && text_[pos_] == '\n') ++pos_;
    ++line_;
    return line;
  }

  double number(const std::string& what) {
    const std::string_view text = trimmed(text_line(what));
    double v = 0;
    if (text.empty()) fail(line_, "line " + std::to_string(line_) + " should hold " + what + " but is empty.");
    if (!detail::parse_number(text, true, v))
      fail(line_, "line " + std::to_string(line_) + " should hold " + what + ", a number, but reads '" +
                      std::string(text.substr(0, 40)) + "'.");
    if (!std::isfinite(v)) fail(line_, what + " '" + std::string(text) + "' is not a finite number.");
    return v;
  }

  double non_negative(const std::string& what) {
    const double v = number(what);
    if (v < 0) fail(line_, what + " is " + number_text(v) + "; it cannot be negative.");
    return v;
  }

  long integer(const std::string& what, long low, long high) {
    const double v = number(what);
    if (v != std::floor(v) || v < static_cast<double>(low) || v > static_cast<double>(high))
      fail(line_, what + " is " + number_text(v) + "; it must be a whole number from " + std::to_string(low) + " to " +
                      std::to_string(high) + ".");
    return static_cast<long>(v);
  }

  // The next number of the sequence after the lamp sets (present: counted beforehand).
  double value(const std::string& what) {
    const Token& t = tokens_[next_++];
    double v = 0;
    if (!detail::parse_number(t.text, true, v))
      fail(t.line, "'" + std::string(t.text.substr(0, 40)) + "' is not a number (expected " + what + ").");
    if (!std::isfinite(v)) fail(t.line, what + " '" + std::string(t.text) + "' is not a finite number.");
    return v;
  }
  std::size_t last_line() const { return tokens_[next_ - 1].line; }

  std::string path_;
  std::string_view text_;
  std::size_t pos_ = 0, line_ = 0;  // where the next line starts; the last line's number
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
  Photometry p_;
};

}  // namespace

Photometry parse_eulumdat(const std::string& path, const std::string& text) {
  return EulumdatParser(path, text).parse();
}

}  // namespace dynrad::rad
