// Glass whose transmittance falls with the angle of incidence, as CIE 171:2006 (test
// 5.5) describes a pane: two surfaces of refractive index n = 1.52 (Fresnel's
// reflectance for each polarisation, light going back and forth between them) and
// absorption along the path inside, which lengthens as the light is refracted more
// obliquely. The pane is known by its transmittance at normal incidence (a material's
// "transmittance"), from which its internal absorption follows.
#pragma once

namespace dynrad::rad {

class GlassPane {
 public:
  static constexpr double kIndex = 1.52;
  // A pane of transmittance `normal` (0-1) at normal incidence. Above what two
  // uncoated surfaces of this index allow without absorption ((1 - R0) / (1 + R0) =
  // 0.918), the pane absorbs nothing and its transmittance at every angle is scaled to
  // reach `normal` face on (coated glass, or a value given as if it had no surfaces).
  explicit GlassPane(double normal);
  // The fraction passed at incidence cos_incidence (|cos| of the angle between the
  // direction and the pane's normal), unpolarised light.
  double transmittance(double cos_incidence) const;
  // The fraction reflected back to the side the light came from (not modelled in the
  // light transport: see radiosity/sources/daylight.h).
  double reflectance(double cos_incidence) const;
  double internal() const { return internal_; }  // the share one pass through the glass keeps, face on

 private:
  // Transmittance and reflectance for one polarisation's surface reflectance r and the
  // share a kept over one pass.
  static double pass(double r, double a) { return (1 - r) * (1 - r) * a / (1 - r * r * a * a); }
  void fresnel(double cos_incidence, double& rs, double& rp, double& a) const;
  double internal_ = 1, scale_ = 1;
};

}  // namespace dynrad::rad
