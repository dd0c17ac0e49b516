// The mesh path tracer (tests/reference/mesh_tracer.h), the reference for triangle
// meshes, against closed forms (a point light's direct light, one bounce off a floor,
// the furnace), against the independent box tracer in a furnished room, and for
// reproducibility; its PLY reader and the mesh_reference tool on small files.
#include "reference/mesh_tracer.h"
#include "reference/box_tracer.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace dynrad_test {
namespace {

namespace mt = mesh_tracer;
namespace box = reference;

constexpr double kPi = 3.14159265358979323846;

mt::Vec3 add(const mt::Vec3& a, const mt::Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }

// The parallelogram o, o + u, o + u + v, o + v as two triangles whose front faces u x v.
void add_quad(mt::Scene& scene, const mt::Vec3& o, const mt::Vec3& u, const mt::Vec3& v, double rho,
              double exitance = 0) {
  const mt::Vec3 ou = add(o, u), ouv = add(ou, v), ov = add(o, v);
  const mt::Rgb r{rho, rho, rho}, m{exitance, exitance, exitance};
  scene.triangles.push_back({{o, ou, ouv}, r, m});
  scene.triangles.push_back({{o, ouv, ov}, r, m});
}

// The rectangle [x0, x1] x [y0, y1] at height z, facing +z (up) or -z.
void add_horizontal(mt::Scene& scene, double x0, double x1, double y0, double y1, double z, bool up, double rho,
                    double exitance = 0) {
  if (up)
    add_quad(scene, {x0, y0, z}, {x1 - x0, 0, 0}, {0, y1 - y0, 0}, rho, exitance);
  else
    add_quad(scene, {x0, y0, z}, {0, y1 - y0, 0}, {x1 - x0, 0, 0}, rho, exitance);
}

// The six faces of the box [lo, hi]: pointing in (a room) or out (a solid), each
// (walls, floor, ceiling) reflecting and emitting as given. A solid's bottom is left
// out when it stands on the floor (no light reaches it).
struct FaceValues {
  double walls = 0, floor = 0, ceiling = 0;
};
void add_box(mt::Scene& scene, const mt::Vec3& lo, const mt::Vec3& hi, bool room, FaceValues rho,
             FaceValues exitance = {}, bool bottom = true) {
  const double dx = hi.x - lo.x, dy = hi.y - lo.y, dz = hi.z - lo.z;
  // For a room: floor up, ceiling down, each wall facing into the box.
  auto face = [&](const mt::Vec3& o, const mt::Vec3& u, const mt::Vec3& v, double r, double m) {
    if (room)
      add_quad(scene, o, u, v, r, m);
    else
      add_quad(scene, o, v, u, r, m);  // the other way round: facing out
  };
  if (bottom || room) face(lo, {dx, 0, 0}, {0, dy, 0}, rho.floor, exitance.floor);
  face({lo.x, lo.y, hi.z}, {0, dy, 0}, {dx, 0, 0}, rho.ceiling, exitance.ceiling);
  face(lo, {0, dy, 0}, {0, 0, dz}, rho.walls, exitance.walls);                  // x = lo.x
  face({hi.x, lo.y, lo.z}, {0, 0, dz}, {0, dy, 0}, rho.walls, exitance.walls);  // x = hi.x
  face(lo, {0, 0, dz}, {dx, 0, 0}, rho.walls, exitance.walls);                  // y = lo.y
  face({lo.x, hi.y, lo.z}, {dx, 0, 0}, {0, 0, dz}, rho.walls, exitance.walls);  // y = hi.y
}

mt::TraceOptions to_relative_error(double target, int threads = 0) {
  mt::TraceOptions options;
  options.target_relative_error = target;
  options.threads = threads;
  return options;
}

double sigmas_apart(double a, double a_error, double b, double b_error) {
  return std::abs(a - b) / std::hypot(a_error, b_error);
}

// ---------------------------------------------------------------------------------
// Direct light.

TEST(MeshTracer, PointLightDirectIsExactAndShadowsAreBlack) {
  mt::Scene scene;
  add_horizontal(scene, -50, 50, -50, 50, 0, true, 0.5);
  // A plate at z = 1.5 from (2, -1) to (3, 1), once facing up and once down: a
  // shadow does not care which side faces the light.
  add_horizontal(scene, 2, 3, -1, 0, 1.5, true, 0.5);
  add_horizontal(scene, 2, 3, 0, 1, 1.5, false, 0.5);
  const mt::Vec3 light{0.3, -0.2, 2.5};
  const double flux = 1000, intensity = flux / (4 * kPi);
  scene.lights.push_back({light, flux});
  const mt::Tracer tracer(scene);

  for (const mt::Vec3& p :
       {mt::Vec3{0, 0, 0.8}, mt::Vec3{1.3, 0.7, 0.8}, mt::Vec3{-7, 4, 0.1}, mt::Vec3{0.3, -0.2, 2}}) {
    const double dx = light.x - p.x, dy = light.y - p.y, dz = light.z - p.z;
    const double d2 = dx * dx + dy * dy + dz * dz;
    const double up = intensity * (dz / std::sqrt(d2)) / d2;
    EXPECT_NEAR(tracer.direct_illuminance(p, {0, 0, 1}), up, 1e-9 * up) << p.x << " " << p.y;
    // Tilted normals: cos to the normal, and nothing from behind.
    const mt::Vec3 n{1, 0, 1};
    const double tilted = intensity * ((dx + dz) / std::sqrt(2 * d2)) / d2;
    EXPECT_NEAR(tracer.direct_illuminance(p, n), std::max(0.0, tilted), 1e-9 * up);
    EXPECT_EQ(tracer.direct_illuminance(p, {0, 0, -1}), 0.0);
  }
  // Under the plate (the line to the light crosses z = 1.5 inside it), both halves.
  for (const mt::Vec3& p : {mt::Vec3{4, -0.5, 0.8}, mt::Vec3{4, 0.5, 0.8}, mt::Vec3{4.5, 0.9, 0.2}}) {
    const double t = (1.5 - light.z) / (p.z - light.z);
    const double x = light.x + t * (p.x - light.x), y = light.y + t * (p.y - light.y);
    ASSERT_TRUE(x > 2 && x < 3 && y > -1 && y < 1) << "the test's point is not in the shadow";
    EXPECT_EQ(tracer.direct_illuminance(p, {0, 0, 1}), 0.0) << p.x << " " << p.y;
  }
  // Just outside the shadow's edge, lit again.
  EXPECT_GT(tracer.direct_illuminance({6, 0, 0.8}, {0, 0, 1}), 0.0);

  // The estimate's direct part is the same number.
  const mt::Estimate e = tracer.illuminance({1.3, 0.7, 0.8}, {0, 0, 1}, to_relative_error(0.01));
  EXPECT_EQ(e.direct, tracer.direct_illuminance({1.3, 0.7, 0.8}, {0, 0, 1}));
  EXPECT_DOUBLE_EQ(e.value, e.direct + e.indirect);
}

// A point facing down between a point light and a floor of reflectance rho (nothing
// else, so one bounce): H = rho I h z^2 integral_0^inf du / ((u + h^2)^1.5 (u + z^2)^2),
// h the light's height and z the point's, both on the same vertical. With s = z tan(t):
// H = 2 rho I h integral_0^(pi/2) sin t cos t / (z^2 tan^2 t + h^2)^1.5 dt.
double one_bounce_under_a_light(double rho, double intensity, double h, double z) {
  const int n = 200000;  // Simpson: far below the tracer's errors
  const double step = (kPi / 2) / n;
  auto f = [&](double t) {
    const double tan_t = std::tan(t);
    if (!std::isfinite(tan_t)) return 0.0;
    return std::sin(t) * std::cos(t) / std::pow(z * z * tan_t * tan_t + h * h, 1.5);
  };
  double sum = f(0) + f(kPi / 2);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * f(i * step);
  return 2 * rho * intensity * h * sum * step / 3;
}

TEST(MeshTracer, OneBounceOffAFloorIsTheClosedForm) {
  const double rho = 0.6, flux = 2000, h = 3, z = 1;
  mt::Scene scene;
  add_horizontal(scene, -60, 60, -60, 60, 0, true, rho);
  scene.lights.push_back({{0, 0, h}, flux});
  const mt::Tracer tracer(scene);
  const double expected = one_bounce_under_a_light(rho, flux / (4 * kPi), h, z);
  const mt::Estimate e = tracer.illuminance({0, 0, z}, {0, 0, -1}, to_relative_error(3e-3));
  EXPECT_EQ(e.direct, 0.0);  // facing away from the light
  EXPECT_LE(e.std_error, 3.5e-3 * e.value);
  EXPECT_LE(std::abs(e.value - expected), 4 * e.std_error) << e.value << " +- " << e.std_error << " vs " << expected;

  // Colour: a red floor reflects only red, and illuminance is its luminance.
  mt::Scene red = scene;
  for (mt::Triangle& t : red.triangles) t.reflectance = {rho, 0, 0};
  const mt::Estimate r = mt::Tracer(red).illuminance({0, 0, z}, {0, 0, -1}, to_relative_error(3e-3));
  EXPECT_LE(std::abs(r.value - mt::kLuminanceWeights[0] * expected), 4 * r.std_error) << r.value;

  // The floor turned over: its back faces the point and the light, and absorbs.
  mt::Scene flipped;
  add_horizontal(flipped, -60, 60, -60, 60, 0, false, rho);
  flipped.lights = scene.lights;
  const mt::Estimate back = mt::Tracer(flipped).illuminance({0, 0, z}, {0, 0, -1}, to_relative_error(3e-3));
  EXPECT_EQ(back.value, 0.0);
  EXPECT_EQ(back.std_error, 0.0);
}

// ---------------------------------------------------------------------------------
// Against the box tracer: a furnished room under an emitting ceiling rectangle.

TEST(MeshTracer, AgreesWithTheBoxTracerInAFurnishedRoom) {
  const double walls = 0.5, floor = 0.3, ceiling = 0.7, table = 0.6, exitance = 100;
  const double ex0 = 1.5, ex1 = 2.5, ey0 = 1, ey1 = 2;  // the emitter in the ceiling at z = 2.5

  box::BoxScene b;
  const int room = b.add_room({0, 0, 0}, {4, 3, 2.5}, box::Reflectances::walls_floor_ceiling(walls, floor, ceiling));
  b.add_emitter(room, box::Face::plus_z, {ex0, ey0, 2.5}, {ex1, ey1, 2.5}, exitance);
  b.add_solid({2.6, 0.5, 0}, {3.4, 1.3, 0.7}, box::Reflectances::uniform(table));

  mt::Scene m;  // the room's floor and walls, facing in
  add_horizontal(m, 0, 4, 0, 3, 0, true, floor);
  add_quad(m, {0, 0, 0}, {0, 3, 0}, {0, 0, 2.5}, walls);
  add_quad(m, {4, 0, 0}, {0, 0, 2.5}, {0, 3, 0}, walls);
  add_quad(m, {0, 0, 0}, {0, 0, 2.5}, {4, 0, 0}, walls);
  add_quad(m, {0, 3, 0}, {4, 0, 0}, {0, 0, 2.5}, walls);
  // The ceiling in nine pieces, the middle one emitting.
  const double xs[4] = {0, ex0, ex1, 4}, ys[4] = {0, ey0, ey1, 3};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const bool lamp = i == 1 && j == 1;
      add_horizontal(m, xs[i], xs[i + 1], ys[j], ys[j + 1], 2.5, false, lamp ? 0 : ceiling, lamp ? exitance : 0);
    }
  add_box(m, {2.6, 0.5, 0}, {3.4, 1.3, 0.7}, false, {table, table, table}, {}, false);
  const mt::Tracer tracer(m);

  struct Query {
    mt::Vec3 p, n;
  };
  const Query queries[] = {
      {{1.0, 1.0, 0.8}, {0, 0, 1}},   // work plane
      {{3.0, 2.4, 0.8}, {0, 0, 1}},   // work plane, by the table
      {{3.0, 0.9, 0.9}, {0, 0, 1}},   // over the table top
      {{3.7, 0.3, 0.3}, {0, 0, 1}},   // beside the table, partly in its shadow
      {{2.0, 1.5, 1.6}, {0, 0, -1}},  // facing down: all reflected light
      {{0.3, 1.5, 1.2}, {1, 0, 0}},   // facing across the room
  };
  box::TraceOptions box_options;
  box_options.target_relative_error = 3e-3;
  for (const Query& q : queries) {
    const box::Estimate expected = box::irradiance(b, {q.p.x, q.p.y, q.p.z}, {q.n.x, q.n.y, q.n.z}, box_options);
    const mt::Estimate got = tracer.illuminance(q.p, q.n, to_relative_error(3e-3));
    EXPECT_LE(sigmas_apart(got.value, got.std_error, expected.value, expected.std_error), 4)
        << "at (" << q.p.x << ", " << q.p.y << ", " << q.p.z << "): mesh " << got.value << " +- " << got.std_error
        << ", box " << expected.value << " +- " << expected.std_error;
    EXPECT_LE(got.std_error, 3.5e-3 * got.value);
  }
}

// ---------------------------------------------------------------------------------
// The furnace: every face emits M and reflects rho, so radiosity is M / (1 - rho)
// everywhere and so is the irradiance at any point, facing any way.

TEST(MeshTracer, FurnaceIrradianceIsExitanceOverOneMinusReflectance) {
  const double m = 1, rho = 0.5, expected = m / (1 - rho);
  mt::Scene scene;
  add_box(scene, {0, 0, 0}, {3, 2, 2.5}, true, {rho, rho, rho}, {m, m, m});
  add_box(scene, {1, 0.5, 0.8}, {1.6, 1.2, 1.3}, false, {rho, rho, rho}, {m, m, m});  // floating
  const mt::Tracer tracer(scene);
  const mt::Vec3 points[] = {{0.5, 0.5, 0.5}, {1.3, 0.9, 0.6}, {2.9, 1.9, 2.4}, {1.3, 0.4, 1}, {0.01, 1, 1.2}};
  const mt::Vec3 normals[] = {{0, 0, 1}, {0, 0, 1}, {-1, -1, -1}, {0, 1, 0}, {1, 0.2, 0}};
  for (int i = 0; i < 5; ++i) {
    const mt::Estimate e = tracer.illuminance(points[i], normals[i], to_relative_error(1e-3));
    EXPECT_LE(std::abs(e.value - expected), 4 * e.std_error) << i << ": " << e.value << " +- " << e.std_error;
    EXPECT_LE(std::abs(e.value - expected), 3e-3 * expected) << i << ": " << e.value;
    EXPECT_GT(e.paths, 0);
  }
}

// ---------------------------------------------------------------------------------
// Reproducibility and the stopping rule.

TEST(MeshTracer, SameSeedSameAnswerOnAnyNumberOfThreads) {
  mt::Scene scene;
  add_box(scene, {0, 0, 0}, {4, 3, 2.5}, true, {0.5, 0.3, 0.7});
  add_box(scene, {2.6, 0.5, 0}, {3.4, 1.3, 0.7}, false, {0.6, 0.6, 0.6}, {}, false);
  add_horizontal(scene, 1, 2, 1, 2, 2.49, false, 0, 50);
  scene.lights.push_back({{1, 2, 2.2}, 800});
  const mt::Tracer tracer(scene);
  const std::vector<mt::Vec3> points = {{1, 1, 0.8}, {3, 2.4, 0.8}, {3, 0.9, 0.9}, {0.2, 0.2, 0.2}};
  mt::TraceOptions options = to_relative_error(2e-2, 1);
  const std::vector<mt::Estimate> one = tracer.illuminance(points, {0, 0, 1}, options);
  options.threads = 2;
  const std::vector<mt::Estimate> two = tracer.illuminance(points, {0, 0, 1}, options);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(one[i].value, two[i].value);
    EXPECT_EQ(one[i].std_error, two[i].std_error);
    EXPECT_EQ(one[i].paths, two[i].paths);
    // One point alone, its replicates on one or two threads: the same as in the list.
    for (int threads : {1, 2}) {
      options.threads = threads;
      const mt::Estimate alone = tracer.illuminance(points[i], {0, 0, 1}, options, i);
      EXPECT_EQ(alone.value, one[i].value);
      EXPECT_EQ(alone.std_error, one[i].std_error);
    }
    EXPECT_LE(one[i].std_error, 2e-2 * one[i].value);
  }
  // Another seed: another estimate of the same thing.
  options.seed = 2;
  const mt::Estimate other = tracer.illuminance(points[0], {0, 0, 1}, options, 0);
  EXPECT_NE(other.value, one[0].value);
  EXPECT_LE(sigmas_apart(other.value, other.std_error, one[0].value, one[0].std_error), 4);
}

TEST(MeshTracer, RejectsBadScenesAndOptions) {
  mt::Scene empty;
  EXPECT_THROW(mt::Tracer{empty}, std::invalid_argument);
  mt::Scene bright;
  add_horizontal(bright, 0, 1, 0, 1, 0, true, 1.5);
  EXPECT_THROW(mt::Tracer{bright}, std::invalid_argument);
  mt::Scene flat;
  flat.triangles.push_back({{mt::Vec3{0, 0, 0}, mt::Vec3{1, 1, 1}, mt::Vec3{2, 2, 2}}, {0.5, 0.5, 0.5}, {}});
  EXPECT_THROW(mt::Tracer{flat}, std::invalid_argument);  // nothing of non-zero area
  add_horizontal(flat, 0, 1, 0, 1, 0, true, 0.5);
  const mt::Tracer tracer(flat);
  EXPECT_EQ(tracer.degenerate_triangles(), 1u);
  EXPECT_EQ(tracer.triangle_count(), 2u);
  mt::TraceOptions bad;
  bad.min_replicates = 1;
  EXPECT_THROW(tracer.illuminance({0.5, 0.5, 1}, {0, 0, 1}, bad), std::invalid_argument);
  EXPECT_THROW(tracer.illuminance({0.5, 0.5, 1}, {0, 0, 0}, {}), std::invalid_argument);
}

// ---------------------------------------------------------------------------------
// The PLY reader.

class TempDir {
 public:
  TempDir() {
    path_ = std::filesystem::temp_directory_path() /
            ("mesh_tracer_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

const char* const kPlyHeader =
    "element vertex 4\n"
    "property float x\nproperty float y\nproperty float z\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "property float reflectance_r\nproperty float reflectance_g\nproperty float reflectance_b\n"
    "property float quality\n"
    "element face 2\nproperty list uchar int vertex_indices\nend_header\n";

struct PlyVertex {
  float x, y, z;
  unsigned char rgb[3];
  float rho[3];
  float quality;
};
const PlyVertex kVertices[4] = {{0, 0, 0, {1, 2, 3}, {0.2f, 0.3f, 0.4f}, 0.3f},
                                {2, 0, 0, {1, 2, 3}, {0.5f, 0.3f, 0.4f}, 0.3f},
                                {2, 1, 0, {1, 2, 3}, {0.8f, 0.3f, 0.1f}, 0.3f},
                                {0, 1, 0.5f, {1, 2, 3}, {0.2f, 0.6f, 0.4f}, 0.3f}};
const int kFaces[2][3] = {{0, 1, 2}, {0, 2, 3}};

// The test mesh as binary PLY of the given byte order.
std::string binary_ply(bool little) {
  std::string out = std::string("ply\nformat ") + (little ? "binary_little_endian" : "binary_big_endian") + " 1.0\n" +
                    "comment written by the test\n" + kPlyHeader;
  const std::uint16_t one = 1;
  const bool host_little = *reinterpret_cast<const unsigned char*>(&one) == 1;
  auto put = [&](const void* p, std::size_t n) {
    std::string bytes(static_cast<const char*>(p), n);
    if (host_little != little) std::reverse(bytes.begin(), bytes.end());
    out += bytes;
  };
  for (const PlyVertex& v : kVertices) {
    put(&v.x, 4), put(&v.y, 4), put(&v.z, 4);
    for (unsigned char c : v.rgb) put(&c, 1);
    for (float r : v.rho) put(&r, 4);
    put(&v.quality, 4);
  }
  for (const auto& f : kFaces) {
    const unsigned char three = 3;
    put(&three, 1);
    for (int i : f) put(&i, 4);
  }
  return out;
}

std::string ascii_ply() {
  std::ostringstream out;
  out << "ply\nformat ascii 1.0\n" << kPlyHeader;
  for (const PlyVertex& v : kVertices)
    out << v.x << " " << v.y << " " << v.z << " 1 2 3 " << v.rho[0] << " " << v.rho[1] << " " << v.rho[2] << " "
        << v.quality << "\n";
  for (const auto& f : kFaces) out << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
  return out.str();
}

void expect_test_mesh(const mt::Scene& s) {
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[1].corners[2].z, 0.5);
  EXPECT_EQ(s.triangles[0].corners[1].x, 2.0);
  // The mean of the three corners' reflectance.
  EXPECT_NEAR(s.triangles[0].reflectance[0], (0.2 + 0.5 + 0.8) / 3, 1e-7);
  EXPECT_NEAR(s.triangles[1].reflectance[1], (0.3 + 0.3 + 0.6) / 3, 1e-7);
  EXPECT_NEAR(s.triangles[1].reflectance[2], (0.4 + 0.1 + 0.4) / 3, 1e-7);
  EXPECT_TRUE(s.lights.empty());
}

TEST(MeshTracerPly, ReadsAsciiAndBinaryOfBothByteOrders) {
  const TempDir dir;
  write_text(dir.file("a.ply"), ascii_ply());
  write_text(dir.file("le.ply"), binary_ply(true));
  write_text(dir.file("be.ply"), binary_ply(false));
  expect_test_mesh(mt::read_ply(dir.file("a.ply")));
  expect_test_mesh(mt::read_ply(dir.file("le.ply")));
  expect_test_mesh(mt::read_ply(dir.file("be.ply")));
}

// The message names the file and contains `what`.
void expect_ply_error(const std::string& path, const std::string& what) {
  try {
    mt::read_ply(path);
    ADD_FAILURE() << path << " was read";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  }
}

TEST(MeshTracerPly, ErrorsNameTheFileAndTheProblem) {
  const TempDir dir;
  expect_ply_error(dir.file("missing.ply"), "cannot open");
  write_text(dir.file("obj.ply"), "v 0 0 0\n");
  expect_ply_error(dir.file("obj.ply"), "not a PLY file");
  std::string quad = ascii_ply();
  quad.replace(quad.rfind("3 0 2 3"), 7, "4 0 1 2 3");
  write_text(dir.file("quad.ply"), quad);
  expect_ply_error(dir.file("quad.ply"), "face 1 has 4 corners");
  std::string far = ascii_ply();
  far.replace(far.rfind("3 0 2 3"), 7, "3 0 2 9");
  write_text(dir.file("far.ply"), far);
  expect_ply_error(dir.file("far.ply"), "face 1 uses vertex 9, but there are 4 vertices");
  std::string plain = ascii_ply();
  plain.replace(plain.find("reflectance_g"), 13, "glossiness_gg");
  write_text(dir.file("plain.ply"), plain);
  expect_ply_error(dir.file("plain.ply"), "no \"reflectance_g\" property");
  const std::string binary = binary_ply(true);
  write_text(dir.file("short.ply"), binary.substr(0, binary.size() - 5));
  expect_ply_error(dir.file("short.ply"), "ends early");
}

// ---------------------------------------------------------------------------------
// The tool, on a room whose surfaces are black: its answers are the exact direct light.

struct ToolRun {
  int status = 0;
  std::string output;  // stdout and stderr
};

ToolRun run_tool(const std::string& arguments, const std::string& log) {
  const std::string command = std::string(MESH_REFERENCE_EXE) + " " + arguments + " > " + log + " 2>&1";
  ToolRun r;
  const int status = std::system(command.c_str());
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  r.output = text.str();
  return r;
}

TEST(MeshReference, WritesOneLinePerUnmaskedPointAndRefusesBadInput) {
  const TempDir dir;
  // A black room, 4 x 3 x 2.5, as ASCII PLY (counter-clockwise from inside).
  mt::Scene room;
  add_box(room, {0, 0, 0}, {4, 3, 2.5}, true, {0, 0, 0});
  std::ostringstream ply;
  ply << "ply\nformat ascii 1.0\nelement vertex " << 3 * room.triangles.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nproperty float reflectance_r\n"
         "property float reflectance_g\nproperty float reflectance_b\nelement face "
      << room.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const mt::Triangle& t : room.triangles)
    for (const mt::Vec3& c : t.corners) ply << c.x << " " << c.y << " " << c.z << " 0 0 0\n";
  for (std::size_t i = 0; i < room.triangles.size(); ++i)
    ply << "3 " << 3 * i << " " << 3 * i + 1 << " " << 3 * i + 2 << "\n";
  write_text(dir.file("room.ply"), ply.str());
  write_text(dir.file("lamps.json"),
             R"({"meshes": [{"file": "room.ifc"}], "luminaires": [)"
             R"({"type": "point", "lumens": 1200, "position": [2, 1.5, 2.2], "name": "one"}]})");
  write_text(dir.file("grid.csv"),
             "x,y,z,illuminance_lx,direct_lx,indirect_lx,masked\n"
             "1,1,0.8,5,5,0,0\n"
             "3.5,2.5,0.8,0,0,0,1\n"
             "2,1.5,0.8,9,9,0,0\n");
  const std::string common = dir.file("room.ply") + " --lights " + dir.file("lamps.json") + " --points " +
                             dir.file("grid.csv") + " --threads 2 --seed 3";
  const ToolRun ok = run_tool(common + " -o " + dir.file("out.txt"), dir.file("log.txt"));
  ASSERT_EQ(ok.status, 0) << ok.output;
  std::ifstream in(dir.file("out.txt"));
  std::string line;
  std::vector<std::vector<double>> rows;
  bool has_command = false, has_seed = false;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0) {
      has_command = has_command || line.find("# command: mesh_reference") == 0;
      has_seed = has_seed || line.find("seed 3") != std::string::npos;
      continue;
    }
    std::istringstream fields(line);
    std::vector<double> row;
    for (double v; fields >> v;) row.push_back(v);
    rows.push_back(row);
  }
  EXPECT_TRUE(has_command);
  EXPECT_TRUE(has_seed);
  ASSERT_EQ(rows.size(), 2u);
  const double intensity = 1200 / (4 * kPi);
  const double xs[2] = {1, 2}, ys[2] = {1, 1.5};
  for (int i = 0; i < 2; ++i) {
    ASSERT_EQ(rows[i].size(), 8u);
    EXPECT_EQ(rows[i][0], xs[i]);
    EXPECT_EQ(rows[i][1], ys[i]);
    const double dx = 2 - xs[i], dy = 1.5 - ys[i], dz = 1.4, d2 = dx * dx + dy * dy + dz * dz;
    const double exact = intensity * dz / std::sqrt(d2) / d2;
    EXPECT_NEAR(rows[i][3], exact, 1e-6 * exact);  // black walls: direct light only
    EXPECT_EQ(rows[i][4], 0.0);
    EXPECT_NEAR(rows[i][5], exact, 1e-6 * exact);
    EXPECT_EQ(rows[i][6], 0.0);
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.txt.tmp")));

  // Errors: exit non-zero, name the file and the problem, write nothing.
  write_text(dir.file("spot.json"), R"({"luminaires": [{"type": "spot", "lumens": 1, "position": [1, 1, 2]}]})");
  write_text(dir.file("bad.json"), R"({"luminaires": [)");
  write_text(dir.file("masked.csv"), "x,y,z,illuminance_lx,direct_lx,indirect_lx,masked\n1,1,0.8,0,0,0,1\n");
  struct Case {
    std::string arguments, expected;
  };
  const std::string out = " -o " + dir.file("bad_out.txt");
  const Case cases[] = {
      {dir.file("none.ply") + " --lights " + dir.file("lamps.json") + " --points " + dir.file("grid.csv") + out,
       dir.file("none.ply") + ": cannot open"},
      {dir.file("room.ply") + " --lights " + dir.file("spot.json") + " --points " + dir.file("grid.csv") + out,
       "only isotropic \"point\" luminaires"},
      {dir.file("room.ply") + " --lights " + dir.file("bad.json") + " --points " + dir.file("grid.csv") + out,
       dir.file("bad.json") + ": invalid JSON"},
      {dir.file("room.ply") + " --lights " + dir.file("lamps.json") + " --points " + dir.file("masked.csv") + out,
       dir.file("masked.csv") + ": no points"},
      {dir.file("room.ply") + " --lights " + dir.file("lamps.json") + out, "no --points"},
  };
  for (const Case& c : cases) {
    const ToolRun r = run_tool(c.arguments, dir.file("log.txt"));
    EXPECT_NE(r.status, 0) << c.arguments;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("bad_out.txt")));
    EXPECT_FALSE(std::filesystem::exists(dir.file("bad_out.txt.tmp")));
  }
}

}  // namespace
}  // namespace dynrad_test
