#include "plugin/validate/cases.h"

#include "plugin/validate/reference.h"

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <mutex>

namespace dynrad::validate {

namespace {

// An OBJ written quad by quad (corners counter-clockwise seen from the front).
class Obj {
 public:
  explicit Obj(const std::string& mtl) : text_("mtllib " + mtl + "\n") {}
  void use(const std::string& material) { text_ += "usemtl " + material + "\n"; }
  void quad(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
    for (const Vec3d& p : {a, b, c, d}) text_ += fmt::format("v {} {} {}\n", p[0], p[1], p[2]);
    text_ += fmt::format("f {} {} {} {}\n", count_ + 1, count_ + 2, count_ + 3, count_ + 4);
    count_ += 4;
  }
  // A horizontal rectangle at height z facing up (+1) or down (-1).
  void flat(double x0, double y0, double x1, double y1, double z, int facing) {
    if (facing > 0)
      quad(Vec3d(x0, y0, z), Vec3d(x1, y0, z), Vec3d(x1, y1, z), Vec3d(x0, y1, z));
    else
      quad(Vec3d(x0, y0, z), Vec3d(x0, y1, z), Vec3d(x1, y1, z), Vec3d(x1, y0, z));
  }
  // A rectangle of the plane y = y0 over [x0, x1] x [z0, z1], facing +y or -y.
  void facade(double x0, double z0, double x1, double z1, double y0, int facing) {
    if (facing > 0)
      quad(Vec3d(x0, y0, z0), Vec3d(x0, y0, z1), Vec3d(x1, y0, z1), Vec3d(x1, y0, z0));
    else
      quad(Vec3d(x0, y0, z0), Vec3d(x1, y0, z0), Vec3d(x1, y0, z1), Vec3d(x0, y0, z1));
  }
  // A rectangle of the plane x = x0 over [y0, y1] x [z0, z1], facing +x or -x.
  void side(double y0, double z0, double y1, double z1, double x0, int facing) {
    if (facing > 0)
      quad(Vec3d(x0, y0, z0), Vec3d(x0, y1, z0), Vec3d(x0, y1, z1), Vec3d(x0, y0, z1));
    else
      quad(Vec3d(x0, y0, z0), Vec3d(x0, y0, z1), Vec3d(x0, y1, z1), Vec3d(x0, y1, z0));
  }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
  int count_ = 0;
};

// The four vertical sides of the box [x0, x1] x [y0, y1] x [z0, z1], facing out of it
// (`outward`) or into it.
void box_sides(Obj& obj, double x0, double y0, double x1, double y1, double z0, double z1, bool outward) {
  const int s = outward ? -1 : +1;
  obj.side(y0, z0, y1, z1, x0, s);
  obj.side(y0, z0, y1, z1, x1, -s);
  obj.facade(x0, z0, x1, z1, y0, s);
  obj.facade(x0, z0, x1, z1, y1, -s);
}

// A room [0, w] x [0, d] x [0, h] facing inwards. `ceiling_hole` and `facade_hole`
// (x0, a0, x1, a1: the ceiling's x and y, the facade's x and z) cut an opening, when
// not empty, in the ceiling or in the wall y = 0.
void room(Obj& obj, double w, double d, double h, std::vector<double> ceiling_hole = {},
          std::vector<double> facade_hole = {}) {
  obj.flat(0, 0, w, d, 0, +1);
  if (ceiling_hole.empty()) {
    obj.flat(0, 0, w, d, h, -1);
  } else {
    const double x0 = ceiling_hole[0], y0 = ceiling_hole[1], x1 = ceiling_hole[2], y1 = ceiling_hole[3];
    obj.flat(0, 0, x0, d, h, -1);
    obj.flat(x1, 0, w, d, h, -1);
    obj.flat(x0, 0, x1, y0, h, -1);
    obj.flat(x0, y1, x1, d, h, -1);
  }
  obj.side(0, 0, d, h, 0, +1);
  obj.side(0, 0, d, h, w, -1);
  obj.facade(0, 0, w, h, d, -1);
  if (facade_hole.empty()) {
    obj.facade(0, 0, w, h, 0, +1);
  } else {
    const double x0 = facade_hole[0], z0 = facade_hole[1], x1 = facade_hole[2], z1 = facade_hole[3];
    obj.facade(0, 0, x0, h, 0, +1);
    obj.facade(x1, 0, w, h, 0, +1);
    obj.facade(x0, 0, x1, z0, 0, +1);
    obj.facade(x0, z1, x1, h, 0, +1);
  }
}

// An LM-63 file of an isotropic source of `candela` in every direction.
std::string isotropic_ies(double candela) {
  std::string out = "IESNA:LM-63-2002\n[TEST] dynrad validate: an isotropic point source\nTILT=NONE\n";
  out += "1 -1 1 37 1 1 2 0 0 0\n1 1 0\n";
  for (int k = 0; k <= 36; ++k) out += fmt::format("{}{}", 5 * k, k < 36 ? " " : "\n");
  out += "0\n";
  for (int k = 0; k <= 36; ++k) out += fmt::format("{}{}", candela, k < 36 ? " " : "\n");
  return out;
}

// I cos(incidence) / d^2 from a point source of `candela` at `source`, unobstructed.
double point_source(double candela, const Vec3d& source, const Vec3d& x, const Vec3d& n) {
  const Vec3d to = source - x;
  const double d2 = to.sqrnorm();
  return std::max(0.0, OpenMesh::dot(to, n) / std::sqrt(d2)) * candela / d2;
}

std::vector<std::pair<Vec3d, Vec3d>> floor_points(double w, double d, double step, double inset) {
  std::vector<std::pair<Vec3d, Vec3d>> out;
  for (double y = inset; y <= d - inset + 1e-9; y += step)
    for (double x = inset; x <= w - inset + 1e-9; x += step) out.push_back({Vec3d(x, y, 0), Vec3d(0, 0, 1)});
  return out;
}

std::string grid_json(const std::string& name, double x0, double y0, double x1, double y1, double height,
                      double spacing) {
  return fmt::format(R"({{"name": "{}", "rectangle": [{}, {}, {}, {}], "height": {}, "spacing": {}, "border": 0}})",
                     name, x0, y0, x1, y1, height, spacing);
}

constexpr double kLumensPerWatt = 179;  // an emitting face's W/m^2 to lm/m^2 (docs/scene-files.md: units)

Case point_over_plane() {
  Case c;
  c.id = "5.2";
  c.title = "point source over a plane";
  c.choices =
      "An isotropic 1000 cd source 3 m above the centre of a black 20 x 20 m plane; the plane's illuminance on a 0.75 m "
      "grid out to 6 m (incidence up to 70.5 degrees), and a work plane 0.85 m up (0.5 m grid). Reference: I cos(theta) "
      "/ d^2.";
  Obj obj("plane.mtl");
  obj.use("black");
  obj.flat(-10, -10, 10, 10, 0, +1);
  const Vec3d lamp(0, 0, 3);
  c.files = {{"point.json", R"({"meshes": [{"file": "plane.obj"}],
  "luminaires": [{"photometry": "isotropic.ies", "position": [0, 0, 3]}],
  "grids": [)" + grid_json("plane", 0, 0, 6, 6, 0.85, 0.5) + "]}"},
             {"plane.obj", obj.text()},
             {"plane.mtl", "newmtl black\nKd 0 0 0\n"},
             {"isotropic.ies", isotropic_ies(1000)}};
  c.reference = [lamp](const Vec3d& x, const Vec3d& n) { return point_source(1000, lamp, x, n); };
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= i; ++j) c.mesh_points.push_back({Vec3d(0.75 * i, 0.75 * j, 0), Vec3d(0, 0, 1)});
  c.grids = {"plane"};
  return c;
}

Case area_source() {
  Case c;
  c.id = "5.3";
  c.title = "Lambertian area source in a room";
  c.choices =
      "A black 4 x 4 x 3 m room; a 1.2 x 1.2 m Lambertian source of 1000 cd/m^2 in the middle of the ceiling (an "
      "emitting face, --units photometric). Floor points on a 0.5 m grid, 12 points of one wall, a work plane 0.85 m "
      "up. Reference: pi L times the configuration factor of the square (Lambert's contour integral).";
  Obj obj("room.mtl");
  obj.use("black");
  room(obj, 4, 4, 3, {1.4, 1.4, 2.6, 2.6});
  obj.use("source");
  obj.flat(1.4, 1.4, 2.6, 2.6, 3, -1);
  const double luminance = 1000;
  c.files = {{"area.json", R"({"meshes": [{"file": "room.obj"}], "grids": [)" + grid_json("room", 0, 0, 4, 4, 0.85, 0.5) +
                               "]}"},
             {"room.obj", obj.text()},
             {"room.mtl", fmt::format("newmtl black\nKd 0 0 0\nnewmtl source\nKd 0 0 0\nKe {0} {0} {0}\n",
                                      M_PI * luminance / kLumensPerWatt)}};
  c.options = {"--units", "photometric"};
  const std::vector<Vec3d> square = {Vec3d(1.4, 1.4, 3), Vec3d(2.6, 1.4, 3), Vec3d(2.6, 2.6, 3), Vec3d(1.4, 2.6, 3)};
  c.reference = [square, luminance](const Vec3d& x, const Vec3d& n) {
    return M_PI * luminance * polygon_factor(x, n, square);
  };
  c.mesh_points = floor_points(4, 4, 0.5, 0.25);
  for (double y : {0.5, 1.5, 2.5, 3.5})
    for (double z : {0.5, 1.5, 2.5}) c.mesh_points.push_back({Vec3d(0, y, z), Vec3d(1, 0, 0)});
  c.grids = {"room"};
  return c;
}

Case flux_point_source() {
  Case c;
  c.id = "5.4";
  c.variant = "point source";
  c.title = "flux conservation";
  c.choices =
      "An isotropic 1000 cd source (4000 pi lm) in the middle of a black 4 x 4 x 3 m room: the illuminance of the lit "
      "mesh integrated over every surface must be the source's flux.";
  Obj obj("room.mtl");
  obj.use("black");
  room(obj, 4, 4, 3);
  c.files = {{"flux.json", R"({"meshes": [{"file": "room.obj"}],
  "luminaires": [{"photometry": "isotropic.ies", "position": [2, 2, 1.5]}]})"},
             {"room.obj", obj.text()},
             {"room.mtl", "newmtl black\nKd 0 0 0\n"},
             {"isotropic.ies", isotropic_ies(1000)}};
  c.reference = [](const Vec3d& x, const Vec3d& n) { return point_source(1000, Vec3d(2, 2, 1.5), x, n); };
  c.areas = {{"all surfaces", Vec3d(-1, -1, -1), Vec3d(5, 5, 4), Vec3d(0, 0, 0), 4000 * M_PI, 0}};
  return c;
}

Case flux_daylight(bool roof) {
  Case c;
  c.id = "5.4";
  c.variant = roof ? "roof opening" : "facade opening";
  c.title = "flux conservation";
  c.choices = roof ? "A black 4 x 4 x 3 m room with a 1 x 1 m opening in the middle of its ceiling under the "
                     "traditional CIE overcast sky of 10,000 lx, black ground: the flux on the room's surfaces must be "
                     "10,000 lx x 1 m^2."
                   : "The same room with a 2 x 1 m opening in the wall y = 0 (sill at 1 m): the flux must be the sky's "
                     "illuminance on the outside of that wall (integrated numerically) x 2 m^2.";
  Obj obj("room.mtl");
  obj.use("black");
  if (roof)
    room(obj, 4, 4, 3, {1.5, 1.5, 2.5, 2.5});
  else
    room(obj, 4, 4, 3, {}, {1, 1, 3, 2});
  c.files = {{"flux.json", R"({"meshes": [{"file": "room.obj"}],
  "sky": {"type": "cie_overcast", "horizontal_illuminance": 10000, "ground_reflectance": 0}})"},
             {"room.obj", obj.text()},
             {"room.mtl", "newmtl black\nKd 0 0 0\n"}};
  const double flux = roof ? 10000.0 : 2 * overcast_on_plane(10000, Vec3d(0, -1, 0));
  c.areas = {{"all surfaces", Vec3d(-1, -1, -1), Vec3d(5, 5, 4), Vec3d(0, 0, 0), flux, 0}};
  c.reference = [](const Vec3d&, const Vec3d&) { return 0.0; };
  return c;
}

// CIE 171 5.6: light reflected by one diffuse surface, checked where it arrives. The
// floor of an open-topped room is the only surface that reflects; the sun at the zenith
// lights it evenly (the walls, vertical, get none), so its exitance is rho E and a wall
// point receives rho E times its configuration factor to the floor: the factor of a
// rectangle perpendicular to the receiving plane, sharpest at the wall's foot.
Case diffuse_reflection(double reflectance) {
  Case c;
  c.id = "5.6";
  c.variant = fmt::format("reflectance {}", reflectance);
  c.title = "diffuse reflection (configuration factors)";
  c.choices = fmt::format(
      "A 4 x 4 x 3 m room without a ceiling: black walls, a floor of reflectance {} lit by the sun at the zenith with "
      "100,000 lx (the sky made negligible: uniform, 1e-9 cd/m^2); the walls get no direct light. 24 points on two walls "
      "from 0.1 to 2.5 m up (the lowest 10 cm above the floor, where the factor changes fastest). Reference: rho E "
      "times the configuration factor from the point to the floor (Lambert's contour integral).",
      reflectance);
  Obj obj("room.mtl");
  obj.use("floor");
  obj.flat(0, 0, 4, 4, 0, +1);
  obj.use("black");
  box_sides(obj, 0, 0, 4, 4, 0, 3, false);
  c.files = {{"reflection.json", R"({"meshes": [{"file": "room.obj"}],
  "sky": {"type": "uniform", "zenith_luminance": 1e-9, "ground_reflectance": 0,
          "sun": {"altitude": 90, "azimuth": 180, "direct_normal": 100000}}})"},
             {"room.obj", obj.text()},
             {"room.mtl", fmt::format("newmtl black\nKd 0 0 0\nnewmtl floor\nKd {0} {0} {0}\n", reflectance)}};
  const std::vector<Vec3d> floor = {Vec3d(0, 0, 0), Vec3d(4, 0, 0), Vec3d(4, 4, 0), Vec3d(0, 4, 0)};
  const double exitance = reflectance * 100000;
  c.reference = [floor, exitance](const Vec3d& x, const Vec3d& n) { return exitance * polygon_factor(x, n, floor); };
  for (double y : {0.5, 1.5, 2.0})
    for (double z : {0.1, 0.5, 1.0, 2.5}) {
      c.mesh_points.push_back({Vec3d(0, y, z), Vec3d(1, 0, 0)});
      c.mesh_points.push_back({Vec3d(4 - y, 4, z), Vec3d(0, -1, 0)});
    }
  return c;
}

// A slab test of the segment from x towards unit d against the box [lo, hi].
bool hits_box(const Vec3d& lo, const Vec3d& hi, const Vec3d& x, const Vec3d& d) {
  double enter = 1e-9, leave = 1e300;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) {
      if (x[k] < lo[k] || x[k] > hi[k]) return false;
      continue;
    }
    double t0 = (lo[k] - x[k]) / d[k], t1 = (hi[k] - x[k]) / d[k];
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
  }
  return enter < leave;
}

Case sun_and_obstruction() {
  Case c;
  c.id = "5.7";
  c.title = "internal obstruction lit by the sun";
  c.choices =
      "A black 1 x 1 x 1 m block in the middle of a black 10 x 10 m plane, the sun at altitude 30 degrees, azimuth 225 "
      "(south-west), 100,000 lx direct normal; the sky made negligible (uniform, 1e-9 cd/m^2). Points on a 0.5 m grid "
      "of the plane (those under the block and those within 2 cm of the shadow's outline left out), and on the block's "
      "top and sunlit sides. Reference: E_n cos(theta), 0 where the ray to the sun meets the block.";
  Obj obj("block.mtl");
  obj.use("black");
  obj.flat(0, 0, 10, 10, 0, +1);
  const Vec3d lo(4.5, 4.5, 0), hi(5.5, 5.5, 1);
  obj.flat(4.5, 4.5, 5.5, 5.5, 1, +1);
  box_sides(obj, 4.5, 4.5, 5.5, 5.5, 0, 1, true);
  c.files = {{"sun.json", R"({"meshes": [{"file": "block.obj"}],
  "sky": {"type": "uniform", "zenith_luminance": 1e-9, "ground_reflectance": 0,
          "sun": {"altitude": 30, "azimuth": 225, "direct_normal": 100000}}})"},
             {"block.obj", obj.text()},
             {"block.mtl", "newmtl black\nKd 0 0 0\n"}};
  const double altitude = 30 * M_PI / 180, azimuth = 225 * M_PI / 180;
  const Vec3d sun(std::sin(azimuth) * std::cos(altitude), std::cos(azimuth) * std::cos(altitude), std::sin(altitude));
  c.reference = [sun, lo, hi](const Vec3d& x, const Vec3d& n) {
    const double cosine = OpenMesh::dot(sun, n);
    if (cosine <= 0) return 0.0;
    // Start a hair off the surface, so a point on the block does not meet the block.
    if (hits_box(lo, hi, x + n * 1e-6, sun)) return 0.0;
    return 100000 * cosine;
  };
  // The shadow on the plane: the block's outline cast along -sun, a hexagon; a point is
  // near its outline when moving it 2 cm changes the answer.
  auto near_outline = [&](const Vec3d& x) {
    const bool shadowed = hits_box(lo, hi, x, sun);
    for (double dx : {-0.02, 0.0, 0.02})
      for (double dy : {-0.02, 0.0, 0.02})
        if (hits_box(lo, hi, x + Vec3d(dx, dy, 0), sun) != shadowed) return true;
    return false;
  };
  for (const auto& p : floor_points(10, 10, 0.5, 0.25)) {
    const Vec3d& x = p.first;
    if (x[0] > 4.48 && x[0] < 5.52 && x[1] > 4.48 && x[1] < 5.52) continue;
    if (near_outline(x)) continue;
    c.mesh_points.push_back(p);
  }
  for (double u : {4.75, 5.0, 5.25})
    for (double v : {0.25, 0.5, 0.75}) {
      c.mesh_points.push_back({Vec3d(u, 4.5 + v, 1), Vec3d(0, 0, 1)});
      c.mesh_points.push_back({Vec3d(4.5, u, v), Vec3d(-1, 0, 0)});
      c.mesh_points.push_back({Vec3d(u, 4.5, v), Vec3d(0, -1, 0)});
    }
  return c;
}

Case cube(double reflectance) {
  Case c;
  c.id = "5.8";
  c.variant = fmt::format("reflectance {}", reflectance);
  c.title = "interreflection in a cube";
  c.choices =
      "A closed 4 x 4 x 4 m cube of one reflectance with an isotropic 1000 cd source (4000 pi lm) at its centre. Each "
      "face's mean indirect illuminance (the lit mesh integrated over the face, less the face's direct share, flux / 6) "
      "against rho Phi / (S_T (1 - rho)), S_T = 96 m^2: the integrating-sphere formula, exact for the mean over the "
      "cube, and by symmetry for each face's mean. At reflectance 0 the indirect light is 0: compared against the direct "
      "share.";
  Obj obj("cube.mtl");
  obj.use("wall");
  room(obj, 4, 4, 4);
  c.files = {{"cube.json", R"({"meshes": [{"file": "cube.obj"}],
  "luminaires": [{"photometry": "isotropic.ies", "position": [2, 2, 2]}]})"},
             {"cube.obj", obj.text()},
             {"cube.mtl", fmt::format("newmtl wall\nKd {0} {0} {0}\n", reflectance)},
             {"isotropic.ies", isotropic_ies(1000)}};
  const double flux = 4000 * M_PI;
  const double indirect = reflectance * flux / (96 * (1 - reflectance));
  c.reference = [](const Vec3d&, const Vec3d&) { return 0.0; };
  const double e = 0.01;
  const std::pair<const char*, std::array<Vec3d, 3>> faces[] = {
      {"floor", {Vec3d(-e, -e, -e), Vec3d(4 + e, 4 + e, e), Vec3d(0, 0, 1)}},
      {"ceiling", {Vec3d(-e, -e, 4 - e), Vec3d(4 + e, 4 + e, 4 + e), Vec3d(0, 0, -1)}},
      {"wall x = 0", {Vec3d(-e, -e, -e), Vec3d(e, 4 + e, 4 + e), Vec3d(1, 0, 0)}},
      {"wall x = 4", {Vec3d(4 - e, -e, -e), Vec3d(4 + e, 4 + e, 4 + e), Vec3d(-1, 0, 0)}},
      {"wall y = 0", {Vec3d(-e, -e, -e), Vec3d(4 + e, e, 4 + e), Vec3d(0, 1, 0)}},
      {"wall y = 4", {Vec3d(-e, 4 - e, -e), Vec3d(4 + e, 4 + e, 4 + e), Vec3d(0, -1, 0)}}};
  for (const auto& [name, f] : faces) c.areas.push_back({name, f[0], f[1], f[2], flux / 6 + indirect * 16, flux / 6});
  return c;
}

// The glass of the glazed cases: clear, 6 mm, n = 1.52; its transmittance face on
// chosen as 0.88 (CIE 171's value for the pane was not in the public descriptions).
constexpr double kGlass = 0.88;

Case glass_at(int incidence) {
  Case c;
  c.id = "5.5";
  c.variant = fmt::format("incidence {} degrees", incidence);
  c.title = "directional transmittance of clear glass";
  c.choices =
      "A black room 40 x 40 m and 1 m high with a 2 x 2 m opening in the middle of its ceiling, glazed with clear glass "
      "(0.88 face on, n = 1.52); the sun at this incidence on the pane (azimuth 180), 100,000 lx direct normal, the sky "
      "negligible (uniform, 1e-9 cd/m^2). Five points in the sun patch on the floor and four in the dark around it. "
      "Reference: E_n cos(theta) times the pane's transmittance (reference.h's ClearGlass: Fresnel's reflectances, the "
      "light between the surfaces summed term by term, the absorption found by bisection).";
  Obj obj("room.mtl");
  obj.use("black");
  room(obj, 40, 40, 1, {19, 19, 21, 21});
  obj.use("glass");
  obj.flat(19, 19, 21, 21, 1, -1);
  c.files = {{"glass.json", fmt::format(R"({{"meshes": [{{"file": "room.obj"}}],
  "sky": {{"type": "uniform", "zenith_luminance": 1e-9, "ground_reflectance": 0,
          "sun": {{"altitude": {}, "azimuth": 180, "direct_normal": 100000}}}}}})",
                                        90 - incidence)},
             {"room.obj", obj.text()},
             {"room.mtl", fmt::format("newmtl black\nKd 0 0 0\nnewmtl glass\nKd 0 0 0\nd {}\n", 1 - kGlass)}};
  const double z = incidence * M_PI / 180;
  const Vec3d sun(0, -std::sin(z), std::cos(z));
  // The sun patch: the opening moved down 1 m along -sun, centred at (20, 20 + tan z).
  const double centre = 20 + std::tan(z);
  const ClearGlass pane(kGlass);
  c.reference = [sun, centre, pane](const Vec3d& x, const Vec3d& n) {
    const bool lit = std::abs(x[0] - 20) < 1 && std::abs(x[1] - centre) < 1;
    return lit ? 100000 * std::max(0.0, OpenMesh::dot(sun, n)) * pane(sun[2]) : 0.0;
  };
  for (const auto& [dx, dy] : std::vector<std::pair<double, double>>{{0, 0}, {0.5, 0.5}, {-0.5, 0.5}, {0.5, -0.5}, {-0.5, -0.5}})
    c.mesh_points.push_back({Vec3d(20 + dx, centre + dy, 0), Vec3d(0, 0, 1)});
  for (const auto& [dx, dy] : std::vector<std::pair<double, double>>{{2, 0}, {-2, 0}, {0, 2}, {0, -2}})
    c.mesh_points.push_back({Vec3d(20 + dx, centre + dy, 0), Vec3d(0, 0, 1)});
  return c;
}

// The daylight cases: a black 4 x 4 x 3 m room with an unglazed opening, under the
// traditional overcast sky (sky 0) or CIE general sky 1-15 with the sun at altitude 35
// degrees due south (-y), 10,000 lx on the unobstructed horizontal, black ground.
enum class Opening { roof, roof_glazed, facade, facade_glazed, facade_overhang, facade_fins };


// `ground` > 0: a grey ground of that reflectance, and points on the walls that see it
// through the opening (the externally reflected component) beside the floor's.
Case daylight(Opening kind, int sky, double ground = 0) {
  Case c;
  c.goal = 0.02;
  c.variant = sky == 0 ? "traditional overcast sky" : fmt::format("CIE sky {}", sky);
  if (ground > 0) c.variant += fmt::format(", ground {}", ground);
  const Rect roof_opening{Vec3d(1.5, 1.5, 3), Vec3d(1, 0, 0), Vec3d(0, 1, 0)};
  const Rect facade_opening{Vec3d(1, 0, 1), Vec3d(2, 0, 0), Vec3d(0, 0, 1)};
  std::vector<Rect> masks;
  Obj obj("room.mtl");
  obj.use("black");
  // The room first, then the masks (the order the mesh's cleanup meets them in decides
  // how an overhang's edge joins the wall; see bench/results/daylight_portals.md).
  const bool roof = kind == Opening::roof || kind == Opening::roof_glazed;
  if (roof)
    room(obj, 4, 4, 3, {1.5, 1.5, 2.5, 2.5});
  else
    room(obj, 4, 4, 3, {}, {1, 1, 3, 2});
  switch (kind) {
    case Opening::roof:
      c.id = "5.9";
      c.title = "roof opening, unglazed";
      c.choices = "A 1 x 1 m opening in the middle of the ceiling.";
      break;
    case Opening::roof_glazed:
      c.id = "5.10";
      c.title = "roof opening, glazed";
      c.choices = "The 5.9 opening glazed with clear glass of 0.88 face on (n = 1.52), less at oblique incidence.";
      break;
    case Opening::facade_glazed:
      c.id = "5.12";
      c.title = "facade opening, glazed";
      c.choices = "The 5.11 opening glazed with clear glass of 0.88 face on (n = 1.52), less at oblique incidence.";
      break;
    case Opening::facade:
      c.id = "5.11";
      c.title = "facade opening, unglazed";
      c.choices = "A 2 x 1 m opening in the wall y = 0, its sill 1 m up, centred.";
      break;
    case Opening::facade_overhang:
      c.id = "5.13";
      c.title = "facade opening with a horizontal mask";
      c.choices = "The 5.11 opening under an overhang: a black plate 1 m deep at the opening's head (2 m up), 4 m wide.";
      obj.flat(0, -1, 4, 0, 2, -1);
      masks.push_back({Vec3d(0, -1, 2), Vec3d(4, 0, 0), Vec3d(0, 1, 0)});
      break;
    case Opening::facade_fins:
      c.id = "5.14";
      c.title = "facade opening with vertical masks";
      c.choices = "The 5.11 opening between two black fins 1 m deep at its sides (x = 1 and x = 3), from 0.5 to 2.5 m up.";
      obj.quad(Vec3d(1, -1, 0.5), Vec3d(1, 0, 0.5), Vec3d(1, 0, 2.5), Vec3d(1, -1, 2.5));  // facing +x
      obj.quad(Vec3d(3, -1, 0.5), Vec3d(3, -1, 2.5), Vec3d(3, 0, 2.5), Vec3d(3, 0, 0.5));  // facing -x
      masks.push_back({Vec3d(1, -1, 0.5), Vec3d(0, 1, 0), Vec3d(0, 0, 2)});
      masks.push_back({Vec3d(3, -1, 0.5), Vec3d(0, 1, 0), Vec3d(0, 0, 2)});
      break;
  }
  const Rect opening = roof ? roof_opening : facade_opening;
  const double glass = kind == Opening::roof_glazed || kind == Opening::facade_glazed ? kGlass : 0.0;
  if (glass > 0) {
    obj.use("glass");
    if (roof)
      obj.flat(1.5, 1.5, 2.5, 2.5, 3, -1);
    else
      obj.facade(1, 1, 3, 2, 0, +1);
  }
  const std::string sky_json =
      sky == 0 ? fmt::format(R"({{"type": "cie_overcast", "horizontal_illuminance": 10000, "ground_reflectance": {}}})",
                             ground)
               : fmt::format(R"({{"type": "cie", "number": {}, "horizontal_illuminance": 10000, "ground_reflectance": {},
          "sun": {{"altitude": 35, "azimuth": 180}}}})",
                             sky, ground);
  c.files = {{"daylight.json", R"({"meshes": [{"file": "room.obj"}], "sky": )" + sky_json + R"(, "grids": [)" +
                                   grid_json("work_plane", 0, 0, 4, 4, 0.85, 0.25) + "]}"},
             {"room.obj", obj.text()},
             {"room.mtl", fmt::format("newmtl black\nKd 0 0 0\nnewmtl glass\nKd 0 0 0\nd {}\n", 1 - kGlass)}};
  c.choices += std::string(" A black 4 x 4 x 3 m room, ") +
               (ground > 0 ? fmt::format("a ground of reflectance {} (uniform luminance rho E_h / pi, E_h the "
                                         "unobstructed horizontal illuminance; 24 wall points see it through the "
                                         "opening); ",
                                         ground)
                           : std::string("black ground; ")) +
               std::string(sky == 0 ? "the traditional CIE overcast sky"
                                    : "the sky's sun at altitude 35 degrees due south (the facade faces south)") +
               ", 10,000 lx on the unobstructed horizontal. Floor points on a 0.5 m grid and a work plane 0.85 m up "
               "(0.25 m grid, from 0.125 m off the walls). Reference: the sky's luminance integrated over the "
               "opening (400 x 400 cells), masks by ray tests.";
  const double ground_luminance = ground * 10000 / M_PI;
  if (sky == 0) {
    c.reference = [opening, masks, glass, ground_luminance](const Vec3d& x, const Vec3d& n) {
      return overcast_through(10000, opening, masks, x, n, glass, ground_luminance);
    };
  } else {
    const double altitude = 35 * M_PI / 180;
    auto general = std::make_shared<GeneralSky>(sky, Vec3d(0, -std::cos(altitude), std::sin(altitude)));
    // The scale to 10,000 lx (a numerical integral over the sky) when first asked for, so
    // that listing or choosing cases costs nothing.
    auto scale = std::make_shared<std::pair<std::once_flag, double>>();
    c.reference = [general, scale, opening, masks, glass, ground_luminance](const Vec3d& x, const Vec3d& n) {
      std::call_once(scale->first, [&] { scale->second = 10000 / general->horizontal(); });
      return sky_through(*general, scale->second, opening, masks, x, n, glass, ground_luminance);
    };
  }
  c.mesh_points = floor_points(4, 4, 0.5, 0.25);
  if (ground > 0) {
    c.title += ", grey ground";  // a section of its own in the tables
    // The back wall, facing the opening, and a side wall: above the opening's head
    // they look down through it at the ground, below its sill up at the sky.
    for (double z : {0.5, 1.5, 2.5}) {
      for (double x : {0.5, 1.5, 2.5, 3.5}) c.mesh_points.push_back({Vec3d(x, 4, z), Vec3d(0, -1, 0)});
      for (double y : {0.5, 1.5, 2.5, 3.5}) c.mesh_points.push_back({Vec3d(0, y, z), Vec3d(1, 0, 0)});
    }
  }
  c.grids = {"work_plane"};
  return c;
}

}  // namespace

std::vector<Case> cie171_cases() {
  std::vector<Case> out;
  out.push_back(point_over_plane());
  out.push_back(area_source());
  out.push_back(flux_point_source());
  out.push_back(flux_daylight(true));
  out.push_back(flux_daylight(false));
  for (int incidence = 0; incidence <= 80; incidence += 10) out.push_back(glass_at(incidence));
  for (double rho : {0.2, 0.5, 0.8}) out.push_back(diffuse_reflection(rho));
  out.push_back(sun_and_obstruction());
  for (double rho : {0.0, 0.2, 0.5, 0.8, 0.95}) out.push_back(cube(rho));
  for (Opening kind : {Opening::roof, Opening::roof_glazed, Opening::facade, Opening::facade_glazed,
                       Opening::facade_overhang, Opening::facade_fins}) {
    for (int sky = 0; sky <= 15; ++sky) out.push_back(daylight(kind, sky));
    // The externally reflected component: the facade openings over a grey ground.
    if (kind == Opening::facade || kind == Opening::facade_glazed)
      for (int sky : {0, 12}) out.push_back(daylight(kind, sky, 0.2));
  }
  return out;
}

}  // namespace dynrad::validate
