// Luminaire photometry: manufacturers' IES LM-63 and EULUMDAT files read into one
// candela distribution in the C-gamma system (type C photometry, the one both formats
// use for interior luminaires).
//
// Angles, in the luminaire's own frame: gamma is measured from the nadir (the
// direction the luminaire points, straight down as photometered), 0 to 180 degrees;
// C is the azimuth about the nadir axis, 0 to 360 degrees, counter-clockwise seen from
// above, C0 along the luminaire's length and C90 along its width. (Luminaire places
// this frame in the scene: see luminaire.h.)
//
// The readers are strict: anything the format does not allow, or that would make the
// distribution meaningless (a count that does not match the values, angles out of
// order or out of range, a negative or non-finite candela value, a photometric type
// other than C), is an InputError naming the file and the line, saying what to do.
// They never read past the end of the file and never allocate more than the file's
// size allows.
#pragma once

#include <string>
#include <vector>

namespace dynrad::rad {

struct Photometry {
  std::string file;    // path as given
  // "IES LM-63-1995", "IES LM-63-2002", "IES LM-63-2019", "EULUMDAT"; also
  // "IES LM-63-1991" (first line IESNA91) and "IES LM-63-1986" (no version line).
  std::string format;
  std::string name;    // luminaire name or catalogue number, where the file gives one

  // The distribution, expanded over the whole sphere from the symmetry the file
  // declares: c_angles ascending from 0 and below 360 (the plane at 360 is the one at
  // 0), gamma_angles ascending within [0, 180]; candela[c * gamma_angles.size() + g]
  // in cd, every factor of the file applied (IES: candela multiplier, ballast factor
  // and, up to LM-63-1995, the ballast-lamp photometric factor; EULUMDAT: cd/klm times
  // the lamps' flux / 1000 and the conversion factor). Beyond the last gamma angle the intensity is 0, and so
  // before the first (a file from 90 to 180 gives no light downwards). At least two
  // gamma angles; a single C angle (0) means the same plane all round.
  std::vector<double> c_angles, gamma_angles, candela;
  // Symmetry the file declared, in words ("none", "about the vertical axis",
  // "C0-C180 plane", "C90-C270 plane", "both planes" / IES: "axial", "quadrant",
  // "bilateral", "bilateral (C90-C270 plane)" for horizontal angles 90-270, "none").
  std::string symmetry;

  // Luminous flux: `flux` is the integral of the distribution over the sphere (lm).
  // `lamp_flux` is the lamps' total as the file states (0 when the file gives
  // absolute photometry, IES lumens -1); `stated_flux` is the luminaire's flux the
  // file implies (EULUMDAT: light output ratio times lamp flux; IES: 0, the format
  // states only lamp lumens). Readers warn when `flux` disagrees with what is stated
  // by more than 2% (or exceeds the lamps' flux).
  double flux = 0, lamp_flux = 0, stated_flux = 0;

  // Luminous opening in metres along C0 (length) and C90 (width), and its height;
  // round when `round` (diameter = length). All 0 for a point.
  double length = 0, width = 0, height = 0;
  bool round = false;

  // IES TILT=INCLUDE: multiplying factors by lamp tilt angle (degrees from the
  // orientation the luminaire was photometered in), ascending. Empty: no tilt data.
  std::vector<double> tilt_angles, tilt_factors;
  // The factor at `tilt` degrees, linear between the file's angles and clamped at its
  // ends (1 without tilt data).
  double tilt_factor(double tilt) const;

  std::vector<std::string> warnings;  // each names the file

  // Intensity in cd towards (c, gamma), degrees: smooth (C1) interpolation between the
  // file's angles (monotone cubic Hermite, which makes no new peaks and no negative
  // values: within each cell of the table it stays between the cell's corner values),
  // exact at the file's angles, periodic in C, 0 outside the gamma angles (and for a
  // NaN angle).
  double intensity(double c_deg, double gamma_deg) const;
};

// By extension (.ies, .ldt; case-insensitive) or, failing that, by content (an IES
// file starts with "IESNA" or has a TILT= line). Throws InputError.
Photometry read_photometry(const std::string& path);
Photometry read_ies(const std::string& path);
Photometry read_eulumdat(const std::string& path);
// The same from text already in memory (fuzzing, tests); `path` names it in messages.
Photometry parse_ies(const std::string& path, const std::string& text);
Photometry parse_eulumdat(const std::string& path, const std::string& text);

// Integral of `p`'s intensity over the sphere, lm (what Photometry::flux holds; for
// tests and for distributions built by hand): exact in C, 5-point Gauss-Legendre on
// pieces of at most 2.5 degrees in gamma (see photometry.cpp); 0 for an inconsistent
// table (sizes that do not match).
double integrate_flux(const Photometry& p);

}  // namespace dynrad::rad
