#include "radiosity/sources/glass.h"

#include <algorithm>
#include <cmath>

namespace dynrad::rad {

GlassPane::GlassPane(double normal) {
  normal = std::clamp(normal, 0.0, 1.0);
  const double r0 = (kIndex - 1) * (kIndex - 1) / ((kIndex + 1) * (kIndex + 1));
  const double most = (1 - r0) / (1 + r0);  // no absorption
  if (normal >= most) {
    internal_ = 1;
    scale_ = normal / most;
    return;
  }
  // normal = (1 - r0)^2 a / (1 - r0^2 a^2), solved for a (the positive root).
  const double p = (1 - r0) * (1 - r0);
  internal_ = normal > 0 ? (-p + std::sqrt(p * p + 4 * normal * normal * r0 * r0)) / (2 * normal * r0 * r0) : 0.0;
}

void GlassPane::fresnel(double cos_incidence, double& rs, double& rp, double& a) const {
  const double ci = std::clamp(cos_incidence, 0.0, 1.0);
  const double si = std::sqrt(1 - ci * ci);
  const double st = si / kIndex, ct = std::sqrt(1 - st * st);
  rs = (ci - kIndex * ct) / (ci + kIndex * ct);
  rp = (kIndex * ci - ct) / (kIndex * ci + ct);
  rs *= rs;
  rp *= rp;
  a = internal_ > 0 ? std::pow(internal_, 1 / ct) : 0.0;  // the path inside is 1 / cos(refracted) times longer
}

double GlassPane::transmittance(double cos_incidence) const {
  double rs = 0, rp = 0, a = 0;
  fresnel(cos_incidence, rs, rp, a);
  return scale_ * 0.5 * (pass(rs, a) + pass(rp, a));
}

double GlassPane::reflectance(double cos_incidence) const {
  double rs = 0, rp = 0, a = 0;
  fresnel(cos_incidence, rs, rp, a);
  auto back = [a](double r) { return r + (1 - r) * (1 - r) * r * a * a / (1 - r * r * a * a); };
  return 0.5 * (back(rs) + back(rp));
}

}  // namespace dynrad::rad
