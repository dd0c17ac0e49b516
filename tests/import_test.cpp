#include "mesh/core/error.h"
#include "mesh/io/import.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace dynrad {
namespace {

ReadOptions strict_reading() {
  ReadOptions options;
  options.strict = true;
  return options;
}

using test::TempDir;

const char* kMtl =
    "newmtl white\nKd 0.7 0.6 0.5\n"
    "newmtl lamp\nKd 0 0 0\nKe 10 20 30\n";

const char* kObj =
    "# two groups, a quad and a triangle\n"
    "mtllib scene.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n"
    "g floor\nusemtl white\n"
    "f 1 2 3 4\n"
    "g light\nusemtl lamp\n"
    "f 1 5 2\n";

TEST(ImportObj, MaterialsGroupsAndPolygonsAreKept) {
  TempDir dir;
  dir.write("scene.mtl", kMtl);
  const PolygonSoup soup = read_model(dir.write("scene.obj", kObj));
  ASSERT_EQ(soup.polygons.size(), 2u);
  EXPECT_EQ(soup.polygons[0].size(), 4u);  // not triangulated by the reader
  EXPECT_EQ(soup.points.size(), 5u);
  const Material& white = soup.materials[soup.material[0]];
  const Material& lamp = soup.materials[soup.material[1]];
  EXPECT_EQ(white.name, "white");
  EXPECT_DOUBLE_EQ(white.reflectance.g, 0.6);
  EXPECT_FALSE(white.emits());
  EXPECT_EQ(lamp.name, "lamp");
  EXPECT_DOUBLE_EQ(lamp.emission.b, 30.0);
  EXPECT_EQ(soup.group_names[soup.group[0]], "floor");
  EXPECT_EQ(soup.group_names[soup.group[1]], "light");
  EXPECT_EQ(soup.origin[0].line, 10u);
  EXPECT_EQ(soup.origin[1].line, 13u);
  EXPECT_NE(white.origin.find("scene.mtl:1"), std::string::npos);
}

TEST(ImportObj, FacesWithoutMaterialGetTheDefaultGrey) {
  TempDir dir;
  const PolygonSoup soup = read_model(dir.write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  ASSERT_EQ(soup.polygons.size(), 1u);
  EXPECT_EQ(soup.materials[soup.material[0]].name, "default");
  EXPECT_DOUBLE_EQ(soup.materials[soup.material[0]].reflectance.r, 0.5);
}

TEST(ImportObj, NegativeIndicesAreRelative) {
  TempDir dir;
  const PolygonSoup soup = read_model(dir.write("rel.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"));
  ASSERT_EQ(soup.polygons.size(), 1u);
  EXPECT_EQ(soup.polygons[0], (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(ImportPly, FaceColoursBecomeLinearReflectance) {
  TempDir dir;
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 2\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\n"
      "property uchar blue\nend_header\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
      "3 0 1 2 128 128 128\n"
      "3 0 2 3 255 255 255\n";
  const PolygonSoup soup = read_model(dir.write("c.ply", ply));
  ASSERT_EQ(soup.polygons.size(), 2u);
  // sRGB 128/255 is linear 0.2158.
  EXPECT_NEAR(soup.materials[soup.material[0]].reflectance.r, 0.2158, 1e-4);
  // White is clamped: no surface reflects everything.
  EXPECT_DOUBLE_EQ(soup.materials[soup.material[1]].reflectance.r, 0.95);
  ASSERT_EQ(soup.warnings.size(), 1u);
  EXPECT_NE(soup.warnings[0].find("clamped"), std::string::npos);
  EXPECT_EQ(soup.origin[1].line, 18u);
}

TEST(ImportOff, QuadsAndPositions) {
  TempDir dir;
  const PolygonSoup soup = read_model(dir.write("q.off", "OFF\n4 1 0\n0 0 0\n2 0 0\n2 3 0\n0 3 0\n4 0 1 2 3\n"));
  ASSERT_EQ(soup.polygons.size(), 1u);
  EXPECT_EQ(soup.polygons[0].size(), 4u);
  EXPECT_NEAR(test::polygon_area(soup), 6.0, 1e-12);
}

TEST(ImportOff, CommentsAreAllowedAndLinesStillCount) {
  TempDir dir;
  const PolygonSoup soup = read_model(
      dir.write("c.off", "OFF\n# a comment line\n3 1 0\n0 0 0 # trailing comment\n1 0 0\n0 1 0\n3 0 1 2\n"));
  ASSERT_EQ(soup.polygons.size(), 1u);
  EXPECT_EQ(soup.origin[0].line, 7u);
  EXPECT_NEAR(test::polygon_area(soup), 0.5, 1e-12);
}

TEST(ImportStl, AsciiAndBinaryGiveTheSameTriangle) {
  TempDir dir;
  const std::string ascii =
      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 4 0 0\nvertex 0 3 0\nendloop\nendfacet\n"
      "endsolid t\n";
  std::string binary(80, ' ');
  const std::uint32_t count = 1;
  binary.append(reinterpret_cast<const char*>(&count), 4);
  const float data[12] = {0, 0, 1, 0, 0, 0, 4, 0, 0, 0, 3, 0};
  binary.append(reinterpret_cast<const char*>(data), sizeof data);
  binary.append(2, '\0');
  for (const std::string& content : {ascii, binary}) {
    const PolygonSoup soup = read_model(dir.write("t.stl", content));
    ASSERT_EQ(soup.polygons.size(), 1u);
    EXPECT_NEAR(test::polygon_area(soup), 6.0, 1e-6);
  }
}

TEST(ImportScene, AssignsMaterialsByGroupAndTransforms) {
  TempDir dir;
  dir.write("scene.mtl", kMtl);
  dir.write("room.obj", kObj);
  dir.write("q.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  const std::string json = R"({
    "meshes": [
      {"file": "room.obj", "groups": {"floor": "lamp"}},
      {"file": "q.off", "material": "panel",
       "transform": {"scale": 2, "rotate_deg": [0, 0, 90], "translate": [10, 0, 0]}}
    ],
    "materials": {
      "panel": {"reflectance": [0.2, 0.3, 0.4]},
      "lamp": {"emission": 5}
    }
  })";
  const PolygonSoup soup = read_input(dir.write("scene.json", json));
  ASSERT_EQ(soup.polygons.size(), 3u);
  // The floor group now uses lamp, whose emission the scene replaced.
  EXPECT_EQ(soup.materials[soup.material[0]].name, "lamp");
  EXPECT_DOUBLE_EQ(soup.materials[soup.material[0]].emission.g, 5.0);
  EXPECT_DOUBLE_EQ(soup.materials[soup.material[0]].reflectance.r, 0.0);  // kept from the MTL
  EXPECT_EQ(soup.materials[soup.material[2]].name, "panel");
  EXPECT_DOUBLE_EQ(soup.materials[soup.material[2]].reflectance.b, 0.4);
  // (1, 0, 0) scaled by 2, turned 90 degrees about z, moved by 10 in x: (10, 2, 0).
  const Vec3d p = soup.points[soup.polygons[2][1]];
  EXPECT_NEAR(p[0], 10.0, 1e-12);
  EXPECT_NEAR(p[1], 2.0, 1e-12);
}

TEST(ImportScene, MirroringKeepsTheFacing) {
  TempDir dir;
  dir.write("q.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const PolygonSoup soup = read_input(dir.write(
      "m.json", R"({"meshes": [{"file": "q.off", "transform": {"scale": [-1, 1, 1]}}]})"));
  const auto& poly = soup.polygons[0];
  const Vec3d n = OpenMesh::cross(soup.points[poly[1]] - soup.points[poly[0]], soup.points[poly[2]] - soup.points[poly[0]]);
  EXPECT_GT(n[2], 0.0);  // still faces +z
}

TEST(ImportScene, UnknownKeysAreErrors) {
  TempDir dir;
  dir.write("q.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string path = dir.write("bad.json", R"({"meshes": [{"file": "q.off", "materal": "x"}]})");
  try {
    read_input(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("materal"), std::string::npos);
    EXPECT_EQ(e.file(), path);
  }
}

TEST(ImportValidation, ReflectanceOfOneIsLoweredOrRefusedWhenStrictNamingTheMaterial) {
  TempDir dir;
  dir.write("m.mtl", "newmtl mirror\nKd 1.0 0.97 0.5\n");
  const std::string obj = dir.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl mirror\nf 1 2 3\n");
  // Leniently: every channel above 0.95 is lowered to it, the others are kept.
  const PolygonSoup soup = read_input(obj);
  const Rgb used = soup.materials[soup.material[0]].reflectance;
  EXPECT_EQ(used.r, kMaxReflectance);
  EXPECT_EQ(used.g, kMaxReflectance);
  EXPECT_EQ(used.b, 0.5);
  ASSERT_EQ(soup.warnings.size(), 1u);
  EXPECT_NE(soup.warnings[0].find("'mirror' (" + dir.path("m.mtl") + ":1)"), std::string::npos) << soup.warnings[0];
  EXPECT_NE(soup.warnings[0].find("lowered to (0.95, 0.95, 0.5)"), std::string::npos) << soup.warnings[0];
  ReadOptions strict;
  strict.strict = true;
  try {
    read_input(obj, strict);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'mirror'"), std::string::npos) << what;
    EXPECT_NE(what.find("m.mtl:1"), std::string::npos) << what;
    EXPECT_NE(what.find("below 1"), std::string::npos) << what;
  }
}

// Found by the OBJ fuzzer: a vertex line led by a vertical tab was a vertex to the line
// check (which splits at any whitespace) but not to tinyobjloader, so a face could refer
// to a vertex that was never read. Control characters are now refused, by line.
TEST(ImportValidation, ControlCharacterIsRefusedWithItsLine) {
  TempDir dir;
  const std::string obj = dir.write("vt.obj", "v 0 0 0\nv 1 0 0\n\vv 0 1 0\nf 1 2 3\n");
  try {
    read_input(obj);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3u) << e.what();
    EXPECT_NE(std::string(e.what()).find("0x0B"), std::string::npos) << e.what();
  }
  // Tabs stay fine.
  const PolygonSoup soup = read_input(dir.write("tab.obj", "v 0 0 0\nv\t1 0 0\n\tv 0 1 0\nf 1 2 3\n"));
  EXPECT_EQ(soup.points.size(), 3u);
  EXPECT_EQ(soup.polygons.size(), 1u);
}

TEST(ImportValidation, UndefinedMaterialGetsTheDefaultUnlessASceneDefinesIt) {
  TempDir dir;
  const std::string obj = dir.write(
      "u.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl ghost\nf 1 2 3\nusemtl other\nf 1 3 2\nusemtl ghost\nf 2 1 3\n");
  const PolygonSoup lenient = read_input(obj);
  for (std::size_t p = 0; p < lenient.polygons.size(); ++p) {
    const Material& m = lenient.materials[lenient.material[p]];
    EXPECT_TRUE(m.defined);
    EXPECT_EQ(m.reflectance, Rgb(0.5));
    EXPECT_FALSE(m.emits());
  }
  // One warning per name, at its first use.
  ASSERT_EQ(lenient.warnings.size(), 2u);
  EXPECT_EQ(lenient.warnings[0].rfind(obj + ":4: material 'ghost' is used but defined nowhere", 0), 0u)
      << lenient.warnings[0];
  EXPECT_EQ(lenient.warnings[1].rfind(obj + ":6: material 'other'", 0), 0u) << lenient.warnings[1];
  ReadOptions strict;
  strict.strict = true;
  EXPECT_THROW(read_input(obj, strict), InputError);
  const PolygonSoup soup = read_input(
      dir.write("u.json", R"({"meshes": [{"file": "u.obj"}], "materials": {"ghost": {"emission": 1}, "other": {}}})"),
      strict);
  EXPECT_TRUE(soup.materials[soup.material[0]].emits());
}

// In a scene, a material one file uses without defining it takes the definition of
// another file: it is not defined nowhere.
TEST(ImportScene, MaterialUsedInOneFileIsDefinedByAnother) {
  TempDir dir;
  dir.write("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl wall\nf 1 2 3\n");
  dir.write("b.mtl", "newmtl wall\nKd 0.3 0.3 0.3\n");
  dir.write("b.obj", "mtllib b.mtl\nv 0 0 1\nv 1 0 1\nv 0 1 1\nusemtl wall\nf 1 2 3\n");
  const PolygonSoup soup =
      read_input(dir.write("ab.json", R"({"meshes": [{"file": "a.obj"}, {"file": "b.obj"}]})"), strict_reading());
  ASSERT_EQ(soup.polygons.size(), 2u);
  for (auto m : soup.material) EXPECT_NEAR(soup.materials[m].reflectance.g, 0.3, 1e-12);
  EXPECT_TRUE(soup.warnings.empty());
}

// A plain "OFF" file may end a face line with a colour. OpenMesh reads the rest of a
// face line only when the keyword has 'C', so the colour's first number became the next
// face's corner count; the importer now blanks what follows the indices.
TEST(ImportOff, FaceColoursInPlainOffDoNotShiftTheNextFace) {
  TempDir dir;
  const PolygonSoup soup = read_model(dir.write(
      "fc.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2 255 0 0\n3 0 2 3 0.2 0.4 0.6 1\n"));
  ASSERT_EQ(soup.polygons.size(), 2u);
  EXPECT_EQ(soup.polygons[1].size(), 3u);
  EXPECT_NEAR(test::polygon_area(soup), 1.0, 1e-12);
}

// Found by fuzzing: OpenMesh's OFF reader is one object per process, and reading from a
// stream kept the last file's "binary" flag, so an ASCII OFF read after a binary one was
// parsed as binary (garbage counts, a loop of minutes). In one process, both in turn.
TEST(ImportOff, AsciiAfterBinaryInOneProcess) {
  TempDir dir;
  std::string binary = "OFF BINARY\n";
  auto put = [&](const auto& value) { binary.append(reinterpret_cast<const char*>(&value), sizeof value); };
  for (std::int32_t count : {3, 1, 0}) put(count);
  for (float x : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(x);
  for (std::int32_t i : {3, 0, 1, 2}) put(i);
  const std::string ascii = "OFF\n# a comment\n4 1 0\n0 0 0\n2 0 0\n2 3 0\n0 3 0\n4 0 1 2 3\n";
  for (int round = 0; round < 2; ++round) {
    const PolygonSoup b = read_model(dir.write("b.off", binary));
    ASSERT_EQ(b.polygons.size(), 1u);
    EXPECT_NEAR(test::polygon_area(b), 0.5, 1e-12);
    const PolygonSoup a = read_model(dir.write("a.off", ascii));
    ASSERT_EQ(a.polygons.size(), 1u);
    EXPECT_NEAR(test::polygon_area(a), 6.0, 1e-12);
  }
}

// OpenMesh's PLY reader is one object per process too. The same check for it: binary
// (both byte orders, with and without face colours) and ASCII files read in turn, each
// parsed by its own header.
TEST(ImportPly, FormatsInTurnInOneProcess) {
  TempDir dir;
  auto binary = [](bool big_endian, bool colours) {
    std::string text = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                       " 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                       "element face 1\nproperty list uchar int vertex_indices\n" +
                       (colours ? "property uchar red\nproperty uchar green\nproperty uchar blue\n" : "") +
                       "end_header\n";
    auto put = [&](const auto& value) {
      std::string bytes(reinterpret_cast<const char*>(&value), sizeof value);
      if (big_endian) std::reverse(bytes.begin(), bytes.end());
      text += bytes;
    };
    for (float x : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(x);
    put(std::uint8_t{3});
    for (std::int32_t i : {0, 1, 2}) put(i);
    if (colours)
      for (std::uint8_t c : {std::uint8_t{200}, std::uint8_t{100}, std::uint8_t{50}}) put(c);
    return text;
  };
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n2 0 0\n2 3 0\n0 3 0\n4 0 1 2 3\n";
  for (int round = 0; round < 2; ++round)
    for (bool big : {false, true})
      for (bool colours : {true, false}) {
        const PolygonSoup b = read_model(dir.write("b.ply", binary(big, colours)));
        ASSERT_EQ(b.polygons.size(), 1u) << "big endian " << big << ", colours " << colours;
        EXPECT_NEAR(test::polygon_area(b), 0.5, 1e-12);
        const PolygonSoup a = read_model(dir.write("a.ply", ascii));
        ASSERT_EQ(a.polygons.size(), 1u);
        EXPECT_NEAR(test::polygon_area(a), 6.0, 1e-12);
      }
}

}  // namespace
}  // namespace dynrad
