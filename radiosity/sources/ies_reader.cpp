// IES LM-63 photometric files (IESNA LM-63-1986, -1991, -1995, -2002; IES LM-63-2019),
// type C photometry only.
//
// Layout: a version line ("IESNA:LM-63-2002"; none before 1991, "IESNA91" in 1991),
// keyword lines ("[LUMINAIRE] ..."; free text in 1986), a TILT= line, then numbers
// separated by white space (commas too, as some writers do) and wrapping across lines
// anywhere:
//   TILT=INCLUDE only: lamp-to-luminaire geometry, number of tilt angles N, N angles,
//     N multiplying factors;
//   number of lamps, lumens per lamp (-1: absolute photometry), candela multiplier,
//   number of vertical angles V, of horizontal angles H, photometric type (1 = C),
//   units of the opening (1 feet, 2 metres), its width, length, height;
//   ballast factor, a second factor (before 2002 the ballast-lamp photometric factor,
//   which multiplies the candela too; "future use" in 2002; the file generation type in
//   2019), input watts;
//   V vertical angles, H horizontal angles, then H blocks of V candela values.
// Type C symmetry is declared by the horizontal angles: 0 alone (axial), 0-90
// (quadrant), 0-180 (bilateral), 90-270 (bilateral about the C90-C270 plane,
// LM-63-2002), 0-360 (none; the plane at 360 repeats the one at 0 and is dropped).
//
// Numbers after the candela table are ignored with a warning: some writers end files
// with a stray value or a second copy of the last line, and nothing after the table
// belongs to the format. TILT=<file name> (tilt data in a separate file) is refused:
// the file would depend on another that is usually lost on the way.
#include "mesh/core/error.h"
#include "mesh/io/text_lines.h"
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

constexpr double kMaxCandela = 1e15;  // beyond any luminaire (a searchlight: ~1e9 cd)

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

class IesParser {
 public:
  IesParser(const std::string& path, std::string_view text) : path_(path), text_(text) {}

  Photometry parse() {
    p_.file = path_;
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);
    read_labels();
    tokens_ = detail::tokenize(text_, pos_, line_ + 1, true);
    if (include_tilt_) read_tilt();
    read_header();
    read_table();
    if (next_ < tokens_.size())
      p_.warnings.push_back(path_ + ":" + std::to_string(tokens_[next_].line) + ": " +
                            std::to_string(tokens_.size() - next_) +
                            " more values after the candela table (which ends with the " +
                            std::to_string(candela_count_) + " values the header declares) are ignored.");
    detail::finish(p_, true);
    return std::move(p_);
  }

 private:
  [[noreturn]] void fail(std::size_t line, const std::string& what) const { throw InputError(path_, line, what); }

  // The next line of the text, without its line break; false at the end.
  bool next_line(std::string_view& line) {
    if (!next_text_line(text_, pos_, line)) return false;
    ++line_;
    return true;
  }

  // Version line, keyword lines, TILT line; leaves pos_ after the TILT line.
  void read_labels() {
    std::string_view line;
    if (!next_line(line)) fail(0, "is empty. An IES file starts with a line such as IESNA:LM-63-2002.");
    const std::string first = upper(trimmed(line));
    bool first_is_label = false;
    if (first.rfind("IESNA:LM-63-1995", 0) == 0) {
      version_ = 1995;
    } else if (first.rfind("IESNA:LM-63-2002", 0) == 0) {
      version_ = 2002;
    } else if (first.rfind("IES:LM-63-2019", 0) == 0 || first.rfind("IESNA:LM-63-2019", 0) == 0) {
      version_ = 2019;
    } else if (first.rfind("IESNA91", 0) == 0 || first.rfind("IESNA:LM-63-1991", 0) == 0) {
      version_ = 1991;
    } else if (first.rfind("IESNA", 0) == 0 || first.rfind("IES:", 0) == 0) {
      fail(1, "the version line '" + std::string(trimmed(line)) +
                  "' names an LM-63 version dynrad does not know. Known: IESNA91, IESNA:LM-63-1995, "
                  "IESNA:LM-63-2002, IES:LM-63-2019; if the file follows one of them, correct the first line.");
    } else {
      version_ = 1986;
      first_is_label = true;
      p_.warnings.push_back(path_ +
                            ": has no version line (such as IESNA:LM-63-2002) and is read as LM-63-1986, whose "
                            "second ballast factor multiplies the candela values.");
    }
    p_.format = "IES LM-63-" + std::to_string(version_);

    std::string luminaire, catalogue;
    for (bool have = first_is_label; have || next_line(line); have = false) {
      const std::string_view text = trimmed(line);
      const std::string key = upper(text.substr(0, std::min<std::size_t>(text.size(), 16)));
      if (key.rfind("TILT", 0) == 0 && trimmed(text.substr(4)).substr(0, 1) == "=") {
        read_tilt_line(trimmed(trimmed(text.substr(4)).substr(1)));
        p_.name = !luminaire.empty() ? luminaire : catalogue;
        return;
      }
      if (key.rfind("[LUMINAIRE]", 0) == 0) luminaire = std::string(trimmed(text.substr(11)));
      if (key.rfind("[LUMCAT]", 0) == 0) catalogue = std::string(trimmed(text.substr(8)));
    }
    fail(line_,
         "has no TILT= line (it follows the keyword lines and precedes the numbers). Is the file truncated, "
         "or not an IES file?");
  }

  void read_tilt_line(std::string_view value) {
    const std::string v = upper(value);
    if (v == "NONE") return;
    if (v == "INCLUDE") {
      include_tilt_ = true;
      return;
    }
    if (v.empty()) fail(line_, "TILT= has no value. Write TILT=NONE, or TILT=INCLUDE followed by the tilt data.");
    fail(line_, "TILT=" + std::string(value) +
                    " refers to tilt data in a separate file, which dynrad does not read. Paste that file's "
                    "numbers (lamp-to-luminaire geometry, number of angles, angles, factors) in place of this line "
                    "after a line TILT=INCLUDE, or write TILT=NONE if the lamp's tilt does not matter.");
  }

  // The next number, finite; `what` names it in messages.
  double number(const std::string& what) {
    if (next_ >= tokens_.size())
      fail(tokens_.empty() ? line_ : tokens_.back().line,
           "the file ends where " + what + " should be. Is it truncated?");
    const Token& t = tokens_[next_++];
    double value = 0;
    if (!detail::parse_number(t.text, false, value))
      fail(t.line, "'" + std::string(t.text) + "' is not a number (expected " + what + ").");
    if (!std::isfinite(value)) fail(t.line, what + " '" + std::string(t.text) + "' is not a finite number.");
    return value;
  }

  std::size_t line_of_last() const { return tokens_[next_ - 1].line; }

  long integer(const std::string& what, long low, long high) {
    const double v = number(what);
    if (v != std::floor(v) || v < static_cast<double>(low) || v > static_cast<double>(high))
      fail(line_of_last(), what + " is " + number_text(v) + "; it must be a whole number from " + std::to_string(low) +
                               " to " + std::to_string(high) + ".");
    return static_cast<long>(v);
  }

  std::size_t remaining() const { return tokens_.size() - next_; }

  void read_tilt() {
    const long geometry = integer("the lamp-to-luminaire geometry (1, 2 or 3) of TILT=INCLUDE", 1, 3);
    (void)geometry;
    const std::size_t count_line = next_ < tokens_.size() ? tokens_[next_].line : line_;
    const long count = integer("the number of tilt angles", 1, std::numeric_limits<int>::max());
    if (static_cast<std::size_t>(count) > remaining() / 2)
      fail(count_line, "TILT=INCLUDE declares " + std::to_string(count) + " tilt angles, so " +
                           std::to_string(2 * count) + " numbers (angles, then factors), but only " +
                           std::to_string(remaining()) + " numbers follow. Is the file truncated?");
    p_.tilt_angles.reserve(static_cast<std::size_t>(count));
    for (long i = 0; i < count; ++i) {
      const double a = number("a tilt angle");
      if (a < 0 || a > 180) fail(line_of_last(), "tilt angle " + number_text(a) + " is outside 0 to 180 degrees.");
      if (!p_.tilt_angles.empty() && !(a > p_.tilt_angles.back()))
        fail(line_of_last(), "tilt angle " + number_text(a) + " is not above the one before (" +
                                 number_text(p_.tilt_angles.back()) + "): tilt angles must ascend.");
      p_.tilt_angles.push_back(a);
    }
    p_.tilt_factors.reserve(static_cast<std::size_t>(count));
    for (long i = 0; i < count; ++i) {
      const double f = number("a tilt factor");
      if (f < 0 || f > 1e6)
        fail(line_of_last(), "tilt factor " + number_text(f) + " is not a multiplying factor (0 to 1e6).");
      p_.tilt_factors.push_back(f);
    }
  }

  void read_header() {
    lamps_ = integer("the number of lamps", 1, 1000000);
    lumens_ = number("the lumens per lamp");
    if (lumens_ != -1 && !(lumens_ > 0))
      fail(line_of_last(),
           "lumens per lamp is " + number_text(lumens_) + "; it must be positive, or -1 for absolute photometry.");
    multiplier_ = number("the candela multiplier");
    if (!(multiplier_ > 0))
      fail(line_of_last(), "candela multiplier " + number_text(multiplier_) + " is not positive.");
    vertical_line_ = next_ < tokens_.size() ? tokens_[next_].line : line_;
    vertical_ = static_cast<std::size_t>(integer("the number of vertical angles", 2, std::numeric_limits<int>::max()));
    horizontal_ =
        static_cast<std::size_t>(integer("the number of horizontal angles", 1, std::numeric_limits<int>::max()));
    const double type = number("the photometric type");
    if (type == 2)
      fail(line_of_last(),
           "photometric type 2 is type B (floodlights, angles about a horizontal axis); dynrad reads "
           "type C only. Ask the manufacturer for type C data, or convert the file.");
    if (type == 3)
      fail(line_of_last(),
           "photometric type 3 is type A (automotive); dynrad reads type C only. Ask the "
           "manufacturer for type C data, or convert the file.");
    if (type != 1)
      fail(line_of_last(), "photometric type " + number_text(type) + " is not 1 (type C), 2 (B) or 3 (A).");
    const double units = number("the units type (1 feet, 2 metres)");
    if (units != 1 && units != 2)
      fail(line_of_last(), "units type " + number_text(units) + " is neither 1 (feet) nor 2 (metres).");
    const double scale = units == 1 ? 0.3048 : 1.0;
    const double width = number("the width of the luminous opening") * scale;
    const double length = number("the length of the luminous opening") * scale;
    const double height = number("the height of the luminous opening") * scale;
    if (width < 0 || length < 0) {  // round (LM-63-2002: both negative, the diameter)
      p_.round = true;
      p_.length = p_.width = std::max(std::abs(width), std::abs(length));
    } else {
      p_.length = length;
      p_.width = width;
    }
    p_.height = std::abs(height);
    ballast_ = number("the ballast factor");
    if (!(ballast_ > 0)) fail(line_of_last(), "ballast factor " + number_text(ballast_) + " is not positive.");
    const double second = number(version_ < 2002    ? "the ballast-lamp photometric factor"
                                 : version_ == 2002 ? "the future-use value (1)"
                                                    : "the file generation type");
    if (version_ < 2002) {
      if (!(second > 0))
        fail(line_of_last(), "ballast-lamp photometric factor " + number_text(second) + " is not positive.");
      lamp_factor_ = second;
    }
    number("the input watts");

    // Before anything is reserved: are the angles and values there?
    const std::size_t values = vertical_ * horizontal_;  // each below 2^31: no overflow
    if (vertical_ + horizontal_ > remaining() || values > remaining() - vertical_ - horizontal_)
      fail(vertical_line_, "declares " + std::to_string(vertical_) + " vertical and " + std::to_string(horizontal_) +
                               " horizontal angles, so " + std::to_string(vertical_ + horizontal_) + " angles and " +
                               std::to_string(values) + " candela values, but only " + std::to_string(remaining()) +
                               " numbers follow the header. Is the file truncated?");
    candela_count_ = values;
  }

  void read_table() {
    std::vector<double>& gamma = p_.gamma_angles;
    gamma.reserve(vertical_);
    std::size_t first_line = 0;
    for (std::size_t i = 0; i < vertical_; ++i) {
      const double a = number("a vertical angle");
      if (i == 0) first_line = line_of_last();
      if (a < 0 || a > 180)
        fail(line_of_last(), "vertical angle " + number_text(a) +
                                 " is outside 0 to 180 degrees (type C: 0 is straight down, 180 straight up).");
      if (!gamma.empty() && !(a - gamma.back() >= 1e-6))
        fail(line_of_last(), "vertical angle " + number_text(a) + " is not above the one before (" +
                                 number_text(gamma.back()) + "): vertical angles must ascend.");
      gamma.push_back(a);
    }
    if ((gamma.front() != 0 && gamma.front() != 90) || (gamma.back() != 90 && gamma.back() != 180))
      fail(first_line, "vertical angles run from " + number_text(gamma.front()) + " to " + number_text(gamma.back()) +
                           "; type C files run from 0 to 90, 90 to 180 or 0 to 180 degrees.");

    std::vector<double> planes;
    planes.reserve(horizontal_);
    for (std::size_t i = 0; i < horizontal_; ++i) {
      const double a = number("a horizontal angle");
      if (i == 0) first_line = line_of_last();
      if (a < 0 || a > 360)
        fail(line_of_last(), "horizontal angle " + number_text(a) + " is outside 0 to 360 degrees.");
      if (!planes.empty() && !(a - planes.back() >= 1e-6))
        fail(line_of_last(), "horizontal angle " + number_text(a) + " is not above the one before (" +
                                 number_text(planes.back()) + "): horizontal angles must ascend.");
      planes.push_back(a);
    }
    detail::CSymmetry symmetry;
    const double first = planes.front(), last = planes.back();
    if (planes.size() == 1 && first == 0) {
      symmetry = detail::CSymmetry::axial;
      p_.symmetry = "axial";
    } else if (first == 0 && last == 90) {
      symmetry = detail::CSymmetry::quadrant;
      p_.symmetry = "quadrant";
    } else if (first == 0 && last == 180) {
      symmetry = detail::CSymmetry::c0_c180;
      p_.symmetry = "bilateral";
    } else if (first == 90 && last == 270) {
      symmetry = detail::CSymmetry::c90_c270;
      p_.symmetry = "bilateral (C90-C270 plane)";
    } else if (first == 0 && last == 360) {
      symmetry = detail::CSymmetry::none;
      p_.symmetry = "none";
    } else {
      fail(first_line, "horizontal angles run from " + number_text(first) + " to " + number_text(last) +
                           "; type C files have 0 alone (axial symmetry), 0 to 90 (quadrant), 0 to 180 "
                           "(bilateral), 90 to 270 (bilateral about C90-C270) or 0 to 360 (none).");
    }

    const double factor = multiplier_ * ballast_ * lamp_factor_;
    std::vector<double> values;
    values.reserve(candela_count_);
    for (std::size_t i = 0; i < candela_count_; ++i) {
      const double v = number("a candela value");
      if (v < 0) fail(line_of_last(), "candela value " + number_text(v) + " is negative.");
      const double cd = v * factor;
      if (!(cd <= kMaxCandela))
        fail(line_of_last(), "candela value " + number_text(v) + " times the multiplier and ballast factors is " +
                                 number_text(cd) + " cd, beyond any luminaire (1e15 cd). Check the multiplier.");
      values.push_back(cd);
    }
    if (symmetry == detail::CSymmetry::none) {  // the plane at 360 is the plane at 0
      planes.pop_back();
      values.resize(values.size() - vertical_);
    }
    detail::expand_planes(p_, symmetry, planes, values);
    p_.lamp_flux = lumens_ == -1 ? 0 : static_cast<double>(lamps_) * lumens_;
    p_.stated_flux = 0;
  }

  std::string path_;
  std::string_view text_;
  std::size_t pos_ = 0, line_ = 0;  // the text's lines: where the next starts, the last one's number
  std::vector<Token> tokens_;
  std::size_t next_ = 0;  // next token
  int version_ = 0;
  bool include_tilt_ = false;
  long lamps_ = 0;
  double lumens_ = 0, multiplier_ = 1, ballast_ = 1, lamp_factor_ = 1;
  std::size_t vertical_ = 0, horizontal_ = 0, vertical_line_ = 0, candela_count_ = 0;
  Photometry p_;
};

}  // namespace

Photometry parse_ies(const std::string& path, const std::string& text) { return IesParser(path, text).parse(); }

}  // namespace dynrad::rad
