// The "sky" section of a JSON scene file (see daylight.h for the keys).
#include "mesh/core/error.h"
#include "mesh/load.h"
#include "radiosity/sources/perez.h"
#include "radiosity/sources/daylight.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/sources/scene_json.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace dynrad::rad {

namespace {

using json = nlohmann::json;

void check_keys(const std::string& path, const json& object, const std::string& where, const std::set<std::string>& known) {
  for (const auto& item : object.items())
    if (!known.count(item.key())) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw InputError(path, 0, "unknown key \"" + item.key() + "\" in " + where + " (known keys: " + list + ").");
    }
}

// 1-366, for the Sun-Earth distance.
int day_of_year(const LocalTime& t) {
  static const int before[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
  const bool leap = (t.year % 4 == 0 && t.year % 100 != 0) || t.year % 400 == 0;
  return before[t.month - 1] + t.day + (leap && t.month > 2 ? 1 : 0);
}

}  // namespace

std::vector<Luminaire> read_daylight(const std::string& path, const std::vector<GlazingTriangle>& glazing,
                                     const std::vector<std::array<Vec3d, 3>>& openings) {
  const json sky = scene_section(path, "sky");
  if (sky.is_null()) return {};
  auto fail = [&](const std::string& what) { throw InputError(path, 0, what); };
  if (!sky.is_object()) fail("\"sky\" must be an object (\"type\", \"horizontal_illuminance\", \"sun\", ...).");
  check_keys(path, sky, "sky",
             {"type", "number", "horizontal_illuminance", "diffuse_horizontal", "zenith_luminance", "sun",
              "ground_reflectance", "north", "rays", "diffuse_horizontal_irradiance", "direct_normal_irradiance",
              "dew_point"});
  auto number = [&](const json& v, const std::string& where) { return scene_number(path, v, where); };
  auto day = std::make_shared<Daylight>();
  SkyModel& model = day->sky;
  const std::string type = sky.contains("type") ? (sky["type"].is_string() ? sky["type"].get<std::string>() : "?")
                                                : "cie_overcast";
  if (type == "cie_overcast") {
    model.type = SkyModel::Type::cie_overcast;
  } else if (type == "uniform") {
    model.type = SkyModel::Type::uniform;
  } else if (type == "cie") {
    model.type = SkyModel::Type::cie;
    if (!sky.contains("number")) fail("sky.type \"cie\" needs \"number\", the CIE standard sky type from 1 to 15.");
    const double k = number(sky["number"], "sky.number");
    if (k != std::floor(k) || k < 1 || k > 15) fail("sky.number must be a CIE standard sky type from 1 to 15.");
    model.cie_type = static_cast<int>(k);
  } else if (type == "perez") {
    model.type = SkyModel::Type::perez;
    for (const char* key : {"diffuse_horizontal_irradiance", "direct_normal_irradiance"})
      if (!sky.contains(key))
        fail(std::string("sky.type \"perez\" needs \"") + key +
             "\" (W/m2: the hour's diffuse horizontal and direct normal irradiance, as a weather file gives them).");
  } else {
    fail("sky.type must be \"cie_overcast\", \"cie\" (with \"number\"), \"perez\" (with irradiances) or \"uniform\".");
  }
  if (sky.contains("number") && type != "cie") fail("sky.number is for sky.type \"cie\".");
  for (const char* key : {"diffuse_horizontal_irradiance", "direct_normal_irradiance", "dew_point"})
    if (sky.contains(key) && type != "perez") fail(std::string("sky.") + key + " is for sky.type \"perez\".");
  // Plan orientation: up +z, north in the plan.
  Vec3d north(0, 1, 0);
  if (sky.contains("north")) {
    const json& v = sky["north"];
    if (!v.is_array() || v.size() != 2) fail("sky.north must be [x, y], north's direction in the plan.");
    north = Vec3d(number(v[0], "sky.north[0]"), number(v[1], "sky.north[1]"), 0);
    if (!(north.norm() > 0)) fail("sky.north must not be [0, 0].");
    north.normalize();
  }
  const Vec3d up(0, 0, 1);
  // The sun: where it is (for the shape of CIE skies, and as a source when it has a
  // direct-normal illuminance).
  bool sun_above = false;
  SunPosition p;
  int day_number = 0;  // of the year, when the sun is placed by a date (0: unknown)
  if (sky.contains("sun")) {
    const json& s = sky["sun"];
    if (!s.is_object()) fail("sky.sun must be an object.");
    check_keys(path, s, "sky.sun", {"latitude", "longitude", "time", "timezone", "altitude", "azimuth", "direct_normal"});
    if (s.contains("altitude") || s.contains("azimuth")) {
      if (!s.contains("altitude") || !s.contains("azimuth") || s.contains("latitude") || s.contains("time"))
        fail("sky.sun takes either \"altitude\" and \"azimuth\" or \"latitude\", \"longitude\", \"time\" and "
             "\"timezone\".");
      p.zenith = 90 - number(s["altitude"], "sky.sun.altitude");
      p.azimuth = number(s["azimuth"], "sky.sun.azimuth");
      if (p.zenith < 0 || p.zenith > 180) fail("sky.sun.altitude must be from -90 to 90 degrees.");
    } else {
      for (const char* key : {"latitude", "longitude", "time", "timezone"})
        if (!s.contains(key))
          fail(std::string("sky.sun needs \"") + key +
               "\" (latitude and longitude in degrees, north and east positive; time like \"2026-06-21T12:00\", local; "
               "timezone in hours east of UTC), or \"altitude\" and \"azimuth\".");
      const double latitude = number(s["latitude"], "sky.sun.latitude");
      const double longitude = number(s["longitude"], "sky.sun.longitude");
      const double timezone = number(s["timezone"], "sky.sun.timezone");
      if (std::abs(latitude) > 90) fail("sky.sun.latitude must be from -90 to 90.");
      if (std::abs(longitude) > 180) fail("sky.sun.longitude must be from -180 to 180.");
      if (std::abs(timezone) > 14) fail("sky.sun.timezone must be from -14 to 14 hours.");
      if (!s["time"].is_string()) fail("sky.sun.time must be a string like \"2026-06-21T12:00\".");
      try {
        const LocalTime t = parse_local_time(s["time"].get<std::string>(), timezone);
        p = sun_position(latitude, longitude, t);
        day_number = day_of_year(t);
      } catch (const std::invalid_argument& e) {
        fail(std::string("sky.sun.time: ") + e.what() + ".");
      }
    }
    day->sun = sun_direction(p, up, north);
    sun_above = p.zenith < 90;
    if (s.contains("direct_normal")) {
      day->direct_normal = number(s["direct_normal"], "sky.sun.direct_normal");
      if (day->direct_normal < 0) fail("sky.sun.direct_normal must not be negative (lx).");
      if (!sun_above) day->direct_normal = 0;
    }
  } else if (model.type == SkyModel::Type::cie && cie_sky_parameters(model.cie_type).c != 0) {
    fail("sky type " + std::to_string(model.cie_type) + " is brighter towards the sun: give \"sun\" (its position).");
  } else if (model.type == SkyModel::Type::perez) {
    fail("sky.type \"perez\" needs \"sun\" (its position: the hour's sky is shaped round it).");
  }
  model.up = up;
  model.sun = day->sun;
  // Perez: the hour's sky from its irradiances (radiosity/sources/perez.h), and its
  // illuminances from their luminous efficacy unless they are given in lx.
  double perez_diffuse = 0;
  std::string perez_summary;
  if (model.type == SkyModel::Type::perez) {
    PerezInputs hour;
    hour.zenith = std::clamp(p.zenith, 0.0, 180.0) * M_PI / 180;
    hour.day_of_year = day_number;
    const double limit = extraterrestrial_irradiance(day_number);
    hour.diffuse_horizontal = number(sky["diffuse_horizontal_irradiance"], "sky.diffuse_horizontal_irradiance");
    hour.direct_normal = number(sky["direct_normal_irradiance"], "sky.direct_normal_irradiance");
    if (!(hour.diffuse_horizontal > 0) || hour.diffuse_horizontal > limit)
      fail(fmt::format("sky.diffuse_horizontal_irradiance must be above 0 and at most {:.0f} W/m2 (the "
                       "extraterrestrial irradiance): a Perez sky needs diffuse light.",
                       limit));
    if (hour.direct_normal < 0 || hour.direct_normal > limit)
      fail(fmt::format("sky.direct_normal_irradiance must be from 0 to {:.0f} W/m2 (the extraterrestrial "
                       "irradiance).",
                       limit));
    if (sky.contains("dew_point")) {
      hour.dew_point = number(sky["dew_point"], "sky.dew_point");
      if (*hour.dew_point < -90 || *hour.dew_point > 70) fail("sky.dew_point must be from -90 to 70 (C).");
    }
    const PerezConditions conditions = perez_conditions(hour);
    const PerezEfficacy efficacy = perez_efficacy(conditions);
    model.perez = perez_coefficients(conditions.bin, hour.zenith, conditions.brightness);
    perez_diffuse = hour.diffuse_horizontal * efficacy.diffuse;
    if (!sky["sun"].contains("direct_normal") && sun_above) day->direct_normal = hour.direct_normal * efficacy.direct;
    perez_summary = fmt::format(
        "; Perez: clearness {:.3f} (bin {} of 8), brightness {:.3f}, precipitable water {:.2f} cm{}, luminous efficacy "
        "{:.1f} lm/W diffuse, {:.1f} lm/W direct{}",
        conditions.clearness, conditions.bin, conditions.brightness, conditions.precipitable_water,
        hour.dew_point ? "" : " (no dew point given)", efficacy.diffuse, efficacy.direct,
        day_number ? "" : " (no date: the mean Sun-Earth distance)");
  }
  if (sky.contains("sun"))
    day->sun_summary = fmt::format("sun at altitude {:.2f} deg, azimuth {:.2f} deg (clockwise from north), direct "
                                   "normal {:.4g} lx{}",
                                   90 - p.zenith, p.azimuth, day->direct_normal,
                                   sun_above ? "" : " (below the horizon: no sunlight)");
  // Scale: zenith luminance, or the sky's horizontal illuminance.
  int scales = 0;
  for (const char* key : {"horizontal_illuminance", "diffuse_horizontal", "zenith_luminance"}) scales += sky.contains(key);
  if (scales > 1)
    fail("sky takes one of \"horizontal_illuminance\" (or its synonym \"diffuse_horizontal\") and "
         "\"zenith_luminance\".");
  model.zenith_luminance = 1;
  const double unit_horizontal = model.horizontal_illuminance();
  if (sky.contains("zenith_luminance")) {
    model.zenith_luminance = number(sky["zenith_luminance"], "sky.zenith_luminance");
    if (!(model.zenith_luminance > 0)) fail("sky.zenith_luminance must be above 0 (cd/m^2).");
  } else {
    const char* key = sky.contains("diffuse_horizontal") ? "diffuse_horizontal" : "horizontal_illuminance";
    const double e = sky.contains(key)                     ? number(sky[key], std::string("sky.") + key)
                     : model.type == SkyModel::Type::perez ? perez_diffuse
                                                           : 10000.0;
    if (!(e > 0)) fail(std::string("sky.") + key + " must be above 0 (lx).");
    model.zenith_luminance = e / unit_horizontal;
  }
  day->horizontal_sky = model.zenith_luminance * unit_horizontal;
  double ground_reflectance = 0.2;
  if (sky.contains("ground_reflectance")) {
    ground_reflectance = number(sky["ground_reflectance"], "sky.ground_reflectance");
    if (ground_reflectance < 0 || ground_reflectance >= 1) fail("sky.ground_reflectance must be from 0 to below 1.");
  }
  const double sun_horizontal = day->direct_normal * std::max(0.0, OpenMesh::dot(day->sun, up));
  model.ground_luminance = ground_reflectance * (day->horizontal_sky + sun_horizontal) / M_PI;
  if (sky.contains("rays")) {
    const double r = number(sky["rays"], "sky.rays");
    if (r != std::floor(r) || r < 4 || r > 256) fail("sky.rays must be a whole number from 4 to 256 (rays x rays per point).");
    day->side = static_cast<int>(r);
  }
  if (!glazing.empty() || !openings.empty()) day->glazing = std::make_shared<Glazing>(glazing, openings);
  day->sky_summary = model.describe() + fmt::format(", ground reflectance {:.3g}; {}x{} directions per point{}{}",
                                                    ground_reflectance, day->side, day->side,
                                                    glazing.empty() ? "" : fmt::format(", {} glazing triangles", glazing.size()),
                                                    day->glazing && day->glazing->size() > day->glazing->glass_count()
                                                        ? fmt::format(", {} opening triangles", day->glazing->size() - day->glazing->glass_count())
                                                        : "");
  day->sky_summary += perez_summary;
  std::vector<Luminaire> out;
  if (day->direct_normal > 0) {
    Luminaire sun;
    sun.kind = Luminaire::Kind::sun;
    sun.name = "sun";
    sun.daylight = day;
    out.push_back(sun);
  }
  Luminaire l;
  l.kind = Luminaire::Kind::sky;
  l.name = "sky";
  l.daylight = day;
  out.push_back(l);
  return out;
}

}  // namespace dynrad::rad
