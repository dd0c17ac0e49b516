// A year of daylight from daylight coefficients (see annual.h).
#include "radiosity/climate/annual.h"

#include "mesh/core/error.h"
#include "radiosity/sources/perez.h"
#include "radiosity/sources/sky.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>

namespace dynrad::rad {

YearSky year_sky(const Weather& weather, const SkyPatches& fine, const SkyPatches& indirect,
                 const AnnualOptions& options) {
  YearSky year;
  bool leap = false;
  for (const WeatherHour& h : weather.hours) leap = leap || (h.month == 2 && h.day == 29);
  year.reference_year = leap ? 2020 : 2019;
  const std::size_t n = weather.hours.size();
  std::vector<Vec3d> suns(n);
  std::vector<double> zenith(n);
  int day_of_year = 0, last_day = -1, last_month = -1;
  std::vector<int> days(n);
  for (std::size_t r = 0; r < n; ++r) {
    const WeatherHour& h = weather.hours[r];
    year.rows.push_back({h.month, h.day, h.hour});
    if (h.day != last_day || h.month != last_month) ++day_of_year;
    last_day = h.day;
    last_month = h.month;
    days[r] = day_of_year;
    LocalTime t;
    t.year = year.reference_year;
    t.month = h.month;
    t.day = h.day;
    t.hour = h.hour - 1;
    t.minute = 30;
    t.timezone = weather.site.timezone;
    const SunPosition p = sun_position(weather.site.latitude, weather.site.longitude, t);
    suns[r] = sun_direction(p, options.up, options.north);
    zenith[r] = p.zenith * M_PI / 180;
  }
  std::vector<SunNodes> nodes;
  year.suns = sun_positions(indirect, options.coefficients.sun_spacing, suns, &nodes);
  year.hours.resize(n);
  year.dark.assign(n, 1);
  year.diffuse_horizontal.assign(n, 0.0);
  std::vector<std::string> errors(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t r) {
    const WeatherHour& h = weather.hours[r];
    const bool up = zenith[r] < M_PI / 2;
    if (!(h.diffuse_horizontal > 0) || (!up && h.diffuse_horizontal < 1)) return;
    PerezInputs in;
    in.zenith = std::min(zenith[r], M_PI / 2);
    in.diffuse_horizontal = h.diffuse_horizontal;
    in.direct_normal = up ? h.direct_normal : 0.0;
    in.day_of_year = std::min(days[r], 366);
    if (std::isfinite(h.dew_point)) in.dew_point = h.dew_point;
    try {
      const PerezIlluminance lux = perez_illuminance(in);
      SkyModel sky = perez_sky(in, suns[r], options.up, lux.diffuse_horizontal);
      const double sun_horizontal = up ? lux.direct_normal * OpenMesh::dot(suns[r], options.up) : 0.0;
      sky.ground_luminance = options.ground_reflectance * (lux.diffuse_horizontal + sun_horizontal) / M_PI;
      year.hours[r] = hour_sky(sky, suns[r], up ? lux.direct_normal : 0.0, fine, indirect,
                               up ? nodes[r] : SunNodes{});
      year.dark[r] = 0;
      year.diffuse_horizontal[r] = lux.diffuse_horizontal;
    } catch (const std::invalid_argument& e) {
      errors[r] = e.what();
    }
  });
  for (std::size_t r = 0; r < n; ++r)
    if (!errors[r].empty())
      throw InputError(weather.path, weather.hours[r].line,
                       "this hour's sky cannot be made (" + errors[r] + "); check its radiation fields.");
  return year;
}

AnnualGridHours grid_year(const std::vector<PointCoefficients>& points, const std::vector<Vec3d>& positions,
                          const Vec3d& normal, const Visibility& visibility, const Glazing* glazing,
                          const YearSky& year) {
  const std::size_t hours = year.hours.size(), count = points.size();
  AnnualGridHours out;
  out.total = HourlyIlluminance(count, hours);
  out.sun = HourlyIlluminance(count, hours);
  out.masked.resize(count);
  for (std::size_t k = 0; k < count; ++k) out.masked[k] = points[k].masked;
  tbb::parallel_for(std::size_t(0), hours, [&](std::size_t h) {
    if (year.dark[h]) return;
    const HourSky& sky = year.hours[h];
    for (std::size_t k = 0; k < count; ++k) {
      if (points[k].masked) continue;
      const double sun = sky.direct_normal > 0
                             ? sun_illuminance(visibility, glazing, positions[k], normal, sky.sun, sky.direct_normal)
                             : 0.0;
      const HourIlluminance e = hour_illuminance(points[k], sky, sun);
      out.total.at(h, k) = static_cast<float>(e.total);
      out.sun.at(h, k) = static_cast<float>(sun);
    }
  });
  return out;
}

}  // namespace dynrad::rad
