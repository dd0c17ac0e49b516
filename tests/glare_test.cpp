// UGR (radiosity/design/glare.h) against values worked out here: CIE 117's position
// index table, the formula by hand for one luminaire of known luminance, and facts the
// tabular method must keep (symmetry, flux scaling, reflectances).
#include "radiosity/design/glare.h"
#include "mesh/core/error.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <memory>

namespace dynrad {
namespace {

using rad::Luminaire;

constexpr double kDegree = M_PI / 180.0;

// --- position index ---------------------------------------------------------------

TEST(GlarePositionIndex, IsOneOnTheLineOfSightAndMatchesTableEntries) {
  EXPECT_DOUBLE_EQ(rad::guth_position_index(0, 0), 1.0);
  // CIE 117 Table 4.1 entries (H/R, T/R) -> p.
  EXPECT_NEAR(rad::guth_position_index(1.0, 0), 7.00, 1e-12);
  EXPECT_NEAR(rad::guth_position_index(0.5, 0), 2.86, 1e-12);
  EXPECT_NEAR(rad::guth_position_index(0.5, 1.0), 3.91, 1e-12);
  EXPECT_NEAR(rad::guth_position_index(0, 2.0), 3.50, 1e-12);
  EXPECT_NEAR(rad::guth_position_index(1.5, 2.0), 12.85, 1e-12);
  EXPECT_NEAR(rad::guth_position_index(1.9, 3.0), 16.00, 1e-12);
  // Either side alike.
  EXPECT_DOUBLE_EQ(rad::guth_position_index(0.5, -1.0), rad::guth_position_index(0.5, 1.0));
  // Halfway between 1.90 (H/R 0.3) and 2.35 (0.4) on the line of sight.
  EXPECT_NEAR(rad::guth_position_index(0.35, 0), 2.125, 1e-12);
  // Between four entries: T/R 0.15, H/R 0.15 -> mean of 1.22, 1.46, 1.30, 1.50.
  EXPECT_NEAR(rad::guth_position_index(0.15, 0.15), (1.22 + 1.46 + 1.30 + 1.50) / 4, 1e-12);
}

TEST(GlarePositionIndex, OutsideTheFieldIsZero) {
  EXPECT_EQ(rad::guth_position_index(1.85, 0), 0.0);   // void cells above the line of sight (brows)
  EXPECT_EQ(rad::guth_position_index(0.5, 3.2), 0.0);  // T/R beyond 3
  EXPECT_EQ(rad::guth_position_index(2.0, 1.0), 0.0);  // H/R beyond 1.9
  EXPECT_EQ(rad::guth_position_index(-0.1, 0), 0.0);   // below the line of sight
  EXPECT_GT(rad::guth_position_index(1.7, 0), 16.0);   // the last entry before the void
}

// Kim, Han & Kim's fit against the table, at the angles of each entry: tau the angle
// of the plane through the line of sight and the source from the vertical, sigma the
// angle from the line of sight.
TEST(GlarePositionIndex, KimFitAgreesWithTheTableWithinItsAccuracy) {
  EXPECT_NEAR(rad::kim_position_index(0, 0), 1.0, 1e-12);
  EXPECT_NEAR(rad::kim_position_index(90, 0), 1.0, 1e-12);
  struct Entry {
    double h, t, p;
  };
  const Entry entries[] = {{0.5, 0, 2.86},   {1.0, 0, 7.00}, {1.5, 0, 13.15}, {0.2, 0.2, 1.50}, {0.3, 0.5, 2.10},
                           {1.0, 1.0, 7.00}, {0, 1.0, 2.11}, {0, 2.0, 3.50},  {0.5, 1.0, 3.91}, {1.0, 2.0, 8.90}};
  for (const Entry& e : entries) {
    const double tau = std::atan2(e.t, e.h) / kDegree;
    const double sigma = std::acos(1 / std::sqrt(1 + e.h * e.h + e.t * e.t)) / kDegree;
    EXPECT_NEAR(rad::kim_position_index(tau, sigma) / rad::guth_position_index(e.h, e.t), 1.0, 0.08)
        << "H/R " << e.h << " T/R " << e.t;
  }
}

// --- one luminaire by hand ----------------------------------------------------------

// Isotropic I cd, a rectangular opening `length` x `width` (no luminous sides).
std::shared_ptr<rad::Photometry> isotropic(double intensity, double length, double width, double height = 0) {
  auto p = std::make_shared<rad::Photometry>();
  p->file = "isotropic";
  p->c_angles = {0};
  p->gamma_angles = {0, 90, 180};
  p->candela = {intensity, intensity, intensity};
  p->length = length;
  p->width = width;
  p->height = height;
  p->flux = rad::integrate_flux(*p);
  return p;
}

Luminaire photometric(const std::string& name, const Vec3d& at, std::shared_ptr<rad::Photometry> p) {
  Luminaire l;
  l.kind = Luminaire::Kind::photometric;
  l.name = name;
  l.position = at;
  l.photometry = std::move(p);
  rad::aim_luminaire(l, Vec3d(0, 0, -1), 0);
  return l;
}

TEST(GlareSource, LuminanceAndSolidAngleOfARectangularOpening) {
  // 0.6 x 0.3 m opening, 1000 cd all round, 3 m ahead and 1 m above the eye: seen at
  // cos(gamma) = 1 / sqrt(10), distance sqrt(10).
  const Luminaire l = photometric("a", Vec3d(0, 3, 2.2), isotropic(1000, 0.6, 0.3));
  const rad::LuminaireAppearance a = rad::luminaire_appearance(l, Vec3d(0, 0, 1.2));
  const double area = 0.18 / std::sqrt(10.0);
  EXPECT_NEAR(a.projected_area, area, 1e-12);
  EXPECT_NEAR(a.luminance, 1000 / area, 1e-6);
  EXPECT_NEAR(a.solid_angle, area / 10, 1e-12);
  // With 0.1 m luminous sides: the side facing the eye is the one across C90 (the
  // opening's 0.6 m length), seen at sin(gamma) = 3 / sqrt(10) and |sin C| = 1.
  const Luminaire box = photometric("b", Vec3d(0, 3, 2.2), isotropic(1000, 0.6, 0.3, 0.1));
  const rad::LuminaireAppearance b = rad::luminaire_appearance(box, Vec3d(0, 0, 1.2));
  EXPECT_NEAR(b.projected_area, area + 0.6 * 0.1 * 3 / std::sqrt(10.0), 1e-12);
}

// A closed room (inward faces) of uniform radiosity B: the indirect illuminance at any
// point in any direction is B, so Lb = B / pi exactly. Optionally a solid wall across
// it at y in [1.5, 1.6].
rad::LitScene uniform_room(double radiosity, bool wall) {
  rad::LitScene scene;
  auto quad = [&](Vec3d a, Vec3d b, Vec3d c, Vec3d d, const Vec3d& towards) {
    // Corners counter-clockwise seen from the side `towards` points to.
    if (OpenMesh::dot(OpenMesh::cross(b - a, c - a), towards) < 0) std::swap(b, d);
    const auto base = static_cast<std::uint32_t>(scene.positions.size());
    for (const Vec3d& p : {a, b, c, d}) scene.positions.push_back(p);
    scene.triangles.push_back({base, base + 1, base + 2});
    scene.triangles.push_back({base, base + 2, base + 3});
  };
  auto box = [&](const Vec3d& lo, const Vec3d& hi, double facing) {  // +1 outward, -1 inward
    for (int axis = 0; axis < 3; ++axis)
      for (int end = 0; end < 2; ++end) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        Vec3d corner[4];
        for (int k = 0; k < 4; ++k) {
          corner[k][axis] = end ? hi[axis] : lo[axis];
          corner[k][u] = (k == 1 || k == 2) ? hi[u] : lo[u];
          corner[k][v] = (k >= 2) ? hi[v] : lo[v];
        }
        Vec3d out(0, 0, 0);
        out[axis] = (end ? 1.0 : -1.0) * facing;
        quad(corner[0], corner[1], corner[2], corner[3], out);
      }
  };
  box(Vec3d(-5, -5, 0), Vec3d(5, 12, 3), -1);
  if (wall) box(Vec3d(-5, 1.5, 0), Vec3d(5, 1.6, 3), 1);
  scene.radiosity.assign(scene.positions.size(), Rgb(radiosity, radiosity, radiosity));
  scene.emission.assign(scene.triangles.size(), Rgb(0, 0, 0));
  scene.photometric = true;
  return scene;
}

rad::GatherOptions quick_gather() {
  rad::GatherOptions g;
  g.side = 8;
  return g;
}

TEST(GlareObserver, OneLuminaireGivesTheFormulaByHand) {
  const double B = 40;  // lm/m^2: Lb = 40 / pi
  rad::LitScene scene = uniform_room(B, false);
  scene.luminaires.push_back(photometric("ahead", Vec3d(0, 3, 2.2), isotropic(1000, 0.6, 0.3)));
  scene.prepare();
  rad::Observer o;
  o.name = "desk";
  o.eye = Vec3d(0, 0, 1.2);
  o.view = Vec3d(0, 0.8, 0.6);  // tilted up: made horizontal (+y)
  o.limit = 19;
  const rad::GlareResult g = rad::observer_glare(scene, o, quick_gather());
  ASSERT_EQ(g.sources.size(), 1u);
  ASSERT_TRUE(g.sources[0].counted) << g.sources[0].note;
  ASSERT_TRUE(g.defined);
  EXPECT_NEAR(g.indirect_illuminance, B, 1e-9);
  EXPECT_NEAR(g.background_luminance, B / M_PI, 1e-9);
  // H/R = 1/3, T/R = 0: a third of the way from 1.90 to 2.35.
  const double p = 1.90 + 0.45 / 3;
  EXPECT_NEAR(g.sources[0].position_index, p, 1e-12);
  const double area = 0.18 / std::sqrt(10.0), L = 1000 / area, omega = area / 10;
  const double ugr = 8 * std::log10(0.25 / (B / M_PI) * L * L * omega / (p * p));
  EXPECT_NEAR(g.ugr, ugr, 1e-9);
  EXPECT_EQ(g.met(), ugr <= 19);
}

TEST(GlareObserver, LuminairesBehindAWallBehindTheEyeOrBelowItAreNotCounted) {
  rad::LitScene scene = uniform_room(40, true);
  scene.luminaires.push_back(photometric("behind wall", Vec3d(0, 3, 2.2), isotropic(1000, 0.6, 0.3)));
  scene.luminaires.push_back(photometric("behind eye", Vec3d(0, -2, 2.2), isotropic(1000, 0.6, 0.3)));
  scene.luminaires.push_back(photometric("below eye", Vec3d(0, 1, 1.0), isotropic(1000, 0.6, 0.3)));
  Luminaire point;
  point.kind = Luminaire::Kind::point;
  point.name = "bulb";
  point.position = Vec3d(0, 1, 2.5);
  point.intensity = 1000;
  scene.luminaires.push_back(point);
  scene.prepare();
  rad::Observer o;
  o.eye = Vec3d(0, 0, 1.2);
  o.view = Vec3d(0, 1, 0);
  o.limit = 19;
  const rad::GlareResult g = rad::observer_glare(scene, o, quick_gather());
  ASSERT_EQ(g.sources.size(), 4u);
  for (const rad::GlareSource& s : g.sources) {
    EXPECT_FALSE(s.counted) << s.luminaire;
    EXPECT_FALSE(s.note.empty()) << s.luminaire;
  }
  EXPECT_NE(g.sources[0].note.find("hidden"), std::string::npos) << g.sources[0].note;
  EXPECT_NE(g.sources[1].note.find("behind"), std::string::npos) << g.sources[1].note;
  EXPECT_NE(g.sources[2].note.find("below eye level"), std::string::npos) << g.sources[2].note;
  EXPECT_NE(g.sources[3].note.find("no luminous area"), std::string::npos) << g.sources[3].note;
  EXPECT_FALSE(g.defined);
  EXPECT_EQ(g.counted, 0);
  EXPECT_FALSE(g.notes.empty());
  EXPECT_TRUE(g.met());  // no glare source: nothing over the limit
  // Without the wall the first one counts.
  rad::LitScene open = uniform_room(40, false);
  open.luminaires = scene.luminaires;
  open.prepare();
  EXPECT_TRUE(rad::observer_glare(open, o, quick_gather()).sources[0].counted);
}

// --- observers in a scene file ------------------------------------------------------

TEST(GlareObservers, ReadsEntriesAndDefaults) {
  test::TempDir dir;
  const std::string path = dir.write("scene.json", R"({"observers": [
      {"position": [1, 2, 1.2], "look_at": [1, 6, 1.2], "UGR": 19},
      {"name": "door", "position": [0, 0, 1.7], "direction": [3, 4, 0]}]})");
  const std::vector<rad::Observer> o = rad::read_observers(path);
  ASSERT_EQ(o.size(), 2u);
  EXPECT_EQ(o[0].name, "observer1");
  EXPECT_NEAR(o[0].view[1], 1.0, 1e-12);
  EXPECT_EQ(o[0].limit, 19);
  EXPECT_EQ(o[1].name, "door");
  EXPECT_NEAR(o[1].view[0], 0.6, 1e-12);
  EXPECT_EQ(o[1].limit, 0);
  EXPECT_TRUE(rad::read_observers(dir.write("other.json", R"({"grids": []})")).empty());
}

TEST(GlareObservers, RejectsBadEntriesNamingTheFileAndEntry) {
  test::TempDir dir;
  const std::string good = R"({"position": [0, 0, 1.2], "direction": [0, 1, 0]})";
  const std::pair<std::string, std::string> cases[] = {
      {R"({"position": [0, 0, 1.2], "direction": [0, 1, 0], "colour": 1})", "unknown key \"colour\""},
      {R"({"direction": [0, 1, 0]})", "needs \"position\""},
      {R"({"position": [0, 0, 1.2]})", "exactly one of"},
      {R"({"position": [0, 0, 1.2], "direction": [0, 1, 0], "look_at": [0, 1, 0]})", "exactly one of"},
      {R"({"position": [0, 0, 1.2], "direction": [0, 0, -1]})", "vertical"},
      {R"({"position": [0, 0, 1.2], "look_at": [0, 0, 1.2]})", "no length"},
      {R"({"position": [0, 0, 1.2], "direction": [0, 1, 0], "UGR": 50})", "at most 40"},
      {R"({"position": [0, "a", 1.2], "direction": [0, 1, 0]})", "position[1] must be a number"},
      {R"({"name": "observer1", "position": [0, 0, 1.2], "direction": [0, 1, 0]})", "two observers"},
  };
  for (const auto& [entry, expected] : cases) {
    const std::string path = dir.write("bad.json", "{\"observers\": [" + good + ", " + entry + "]}");
    try {
      rad::read_observers(path);
      ADD_FAILURE() << "accepted " << entry;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(e.file(), path);
      EXPECT_NE(message.find("observers[1]"), std::string::npos) << message;
      EXPECT_NE(message.find(expected), std::string::npos) << message;
    }
  }
}

// --- tabular method -----------------------------------------------------------------

TEST(GlareTable, RotationallySymmetricLuminaireHasEqualCrosswiseAndEndwise) {
  const rad::Photometry p = rad::read_photometry(test::sample("downlight.ies"));
  const rad::UgrTable t = rad::tabular_ugr(p);
  ASSERT_TRUE(t.defined);
  ASSERT_EQ(t.rooms.size(), 19u);
  ASSERT_EQ(t.crosswise.size(), 19u);
  for (std::size_t r = 0; r < t.rooms.size(); ++r)
    for (std::size_t k = 0; k < 5; ++k) EXPECT_NEAR(t.crosswise[r][k], t.endwise[r][k], 1e-6) << r << " " << k;
}

TEST(GlareTable, DoublingTheFluxRaisesEveryValueByEightLogTwo) {
  const rad::Photometry p = rad::read_photometry(test::sample("downlight.ies"));
  const rad::UgrTable a = rad::tabular_ugr(p), b = rad::tabular_ugr(p, 2 * p.flux);
  EXPECT_DOUBLE_EQ(a.flux, p.flux);
  for (std::size_t r = 0; r < a.rooms.size(); ++r)
    for (std::size_t k = 0; k < 5; ++k) {
      EXPECT_NEAR(b.crosswise[r][k] - a.crosswise[r][k], 8 * std::log10(2.0), 1e-9);
      EXPECT_NEAR(b.endwise[r][k] - a.endwise[r][k], 8 * std::log10(2.0), 1e-9);
    }
}

TEST(GlareTable, HigherReflectancesLowerTheRatingAndValuesArePlausible) {
  const rad::Photometry p = rad::read_photometry(test::sample("downlight.ies"));
  const rad::UgrTable t = rad::tabular_ugr(p);
  // Sets: 0 70/50/20, 1 70/30/20, 2 50/50/20, 3 50/30/20, 4 30/30/20.
  for (const auto& rows : {t.crosswise, t.endwise})
    for (const std::vector<double>& v : rows) {
      EXPECT_LT(v[0], v[1]);  // lighter walls
      EXPECT_LT(v[2], v[3]);
      EXPECT_LT(v[0], v[2]);  // lighter ceiling
      EXPECT_LT(v[1], v[3]);
      EXPECT_LT(v[3], v[4]);
      // A bare LED downlight: a 0.15 m opening of some 50,000 to 68,000 cd/m^2 below
      // 55 degrees. Glaring by office standards (over EN 12464-1's 19) yet within the
      // scale the method is meant for (10 to 30).
      for (double x : v) {
        EXPECT_GT(x, 19.0);
        EXPECT_LT(x, 30.0);
      }
    }
}

TEST(GlareTable, ALuminaireWithoutOpeningHasNoTable) {
  const rad::UgrTable t = rad::tabular_ugr(*isotropic(100, 0, 0));
  EXPECT_FALSE(t.defined);
  EXPECT_TRUE(t.crosswise.empty());
  EXPECT_FALSE(t.notes.empty());
}

// --- dynrad info LUMINAIRE ----------------------------------------------------------

TEST(GlareCli, InfoPrintsThePhotometryAndItsUgrTable) {
  const test::CommandResult r = test::run_dynrad("info '" + test::sample("downlight.ies") + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output.substr(r.output.find('{')));
  EXPECT_EQ(j["format"], "IES LM-63-2002");
  EXPECT_GT(j["flux"].get<double>(), 0);
  EXPECT_TRUE(j["opening"]["round"].get<bool>());
  const nlohmann::json& u = j["ugr_table"];
  EXPECT_TRUE(u["defined"].get<bool>());
  ASSERT_EQ(u["rows"].size(), 19u);
  EXPECT_EQ(u["rows"][0]["x"], 2);
  EXPECT_EQ(u["rows"][18]["y"], 8);
  EXPECT_EQ(u["rows"][5]["crosswise"].size(), 5u);
  EXPECT_EQ(u["rows"][5]["endwise"].size(), 5u);
  const test::CommandResult text = test::run_dynrad("info '" + test::sample("downlight.ies") + "'");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("crosswise"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("12H"), std::string::npos) << text.output;
}

TEST(GlareCli, InfoOnABadPhotometryFileNamesItAndExitsTwo) {
  test::TempDir dir;
  const std::string path = dir.write("broken.ldt", "not a eulumdat file\n");
  const test::CommandResult r = test::run_dynrad("info '" + path + "'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("broken.ldt"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace dynrad
