// Hostile materials and files through the command line (docs/import-and-repair.md,
// "Hostile input"): missing or broken material libraries, reflectance of one or more,
// unknown PLY header lines, byte-order marks, colours and list entries out of range.
#include "hostile_input_support.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace dynrad {
namespace {

using namespace hostile;
using json = nlohmann::json;
using test::TempDir;

constexpr auto npos = std::string::npos;

// 1-based line of the first `needle` in `text`.
std::size_t line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, npos) << needle;
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + std::min(at, text.size()), '\n'));
}

std::size_t occurrences(const std::string& text, const std::string& needle) {
  std::size_t count = 0;
  for (std::size_t at = text.find(needle); at != npos; at = text.find(needle, at + 1)) ++count;
  return count;
}

// The same vertices lit the same: two runs that must have read the same model.
void expect_same_light(const Solution& a, const Solution& b) {
  ASSERT_EQ(a.radiosity.size(), b.radiosity.size());
  for (std::size_t v = 0; v < a.radiosity.size(); ++v)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(a.radiosity[v][c], b.radiosity[v][c], 1e-6 * std::max(1.0, std::abs(b.radiosity[v][c])))
          << "vertex " << v << " channel " << c;
}

// A material of `info --json`, by name.
json material_named(const json& counts, const std::string& name) {
  for (const json& m : counts["materials"])
    if (m["name"] == name) return m;
  ADD_FAILURE() << "no material '" << name << "' in " << counts.dump(2);
  return json();
}

void expect_refused_strictly(const TempDir& dir, const std::string& input, const std::vector<std::string>& mentions) {
  const std::string out = dir.path("strict.ply");
  const auto r = test::run_dynrad("solve '" + input + "' -o '" + out + "' --strict");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const std::string& text : mentions) EXPECT_NE(r.output.find(text), npos) << r.output;
  EXPECT_FALSE(test::file_exists(out));
}

TEST(HostileInput, MissingMtlLibraryAndUndefinedMaterialsGetTheDefaultMaterial) {
  TempDir dir;
  ObjBuilder model;
  model.room(true, "plaster");  // six `usemtl plaster`, defined nowhere
  model.lamp();                 // defined in model.mtl
  std::string text = model.obj.str();
  text.insert(text.find('\n') + 1, "mtllib gone.mtl\n");  // line 2
  dir.write("model.mtl", model.mtl.str());
  const std::string input = dir.write("model.obj", text);

  const Solution s = solve(dir, input, "--iterations 40");
  expect_sane(s);
  const std::string& log = s.run.output;
  EXPECT_NE(log.find("model.obj:2: material library 'gone.mtl' not found (looked for " + dir.path("gone.mtl")), npos)
      << log;
  EXPECT_EQ(occurrences(log, "'plaster' is used but defined nowhere"), 1u) << log;
  EXPECT_NE(log.find("model.obj:" + std::to_string(line_of(text, "usemtl plaster")) + ": material 'plaster'"), npos)
      << log;
  const json plaster = material_named(info(input), "plaster");
  EXPECT_EQ(plaster["reflectance"], json({0.5, 0.5, 0.5}));
  EXPECT_EQ(plaster["emission"], json({0.0, 0.0, 0.0}));

  // The same light as with plaster defined as the default, grey 0.5.
  TempDir stated_dir;
  stated_dir.write("model.mtl", model.mtl.str());
  stated_dir.write("gone.mtl", "newmtl plaster\nKd 0.5 0.5 0.5\n");
  const Solution stated = solve(stated_dir, stated_dir.write("model.obj", text), "--iterations 40");
  expect_sane(stated);
  EXPECT_EQ(stated.run.output.find("defined nowhere"), npos) << stated.run.output;
  EXPECT_EQ(stated.run.output.find("not found"), npos) << stated.run.output;
  expect_same_light(s, stated);

  expect_refused_strictly(dir, input, {"model.obj:2", "gone.mtl", "not found"});
  dir.write("gone.mtl", "# plaster is still missing\n");
  expect_refused_strictly(dir, input, {"'plaster'", "defined nowhere"});
}

TEST(HostileInput, ReflectanceOfOneOrMoreIsLoweredTo095WithAWarning) {
  TempDir dir;
  ObjBuilder model;
  model.mtl << "newmtl snow\nKd 1 1.2 0.5\n";
  model.room(true, "snow");
  model.lamp();
  const std::string input = model.write(dir);
  const std::string defined_at = dir.path("model.mtl") + ":" + std::to_string(line_of(model.mtl.str(), "newmtl snow"));

  const Solution s = solve(dir, input, "--iterations 40");
  expect_sane(s);
  EXPECT_NE(s.run.output.find("material 'snow' (" + defined_at + "): reflectance (1, 1.2, 0.5) is 1 or more"), npos)
      << s.run.output;
  EXPECT_NE(s.run.output.find("lowered to (0.95, 0.95, 0.5)"), npos) << s.run.output;
  EXPECT_EQ(material_named(info(input), "snow")["reflectance"], json({0.95, 0.95, 0.5}));

  // The same light as Kd 0.95 0.95 0.5 written in the file.
  TempDir stated_dir;
  ObjBuilder stated;
  stated.mtl << "newmtl snow\nKd 0.95 0.95 0.5\n";
  stated.room(true, "snow");
  stated.lamp();
  const Solution exact = solve(stated_dir, stated.write(stated_dir), "--iterations 40");
  expect_sane(exact);
  expect_same_light(s, exact);

  expect_refused_strictly(dir, input, {"'snow'", defined_at, "below 1"});
}

// A furnace of Kd 1 (every face emits E = 1): with the reflectance lowered to 0.95,
// B = E / (1 - 0.95) = 20 everywhere; a reflectance of 1 would have no answer, and 0.9
// would give 10. At 0.95 the discretisation's error is amplified twenty times (1%
// at 0.5 becomes about 1.3% at the worst vertex, 0.25% on average).
TEST(HostileInput, FurnaceOfWhiteMaterialConvergesAtTheLoweredReflectance) {
  TempDir dir;
  ObjBuilder model;
  model.mtl << "newmtl white_glow\nKd 1 1 1\nKe 1 1 1\n";
  model.room(true, "white_glow");
  const Solution s = solve(dir, model.write(dir), "--converge 1e-3 --ambient --patch-size 0.5");
  expect_sane(s);
  Rgb sum;
  for (const Rgb& b : s.radiosity) {
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(b[c], 20.0, 0.025 * 20.0) << "channel " << c;
    sum += b;
  }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c] / s.radiosity.size(), 20.0, 0.005 * 20.0) << "channel " << c;
}

TEST(HostileInput, ReflectanceOfOneInSceneFilesIsLoweredEvenWhenUnusedAndNegativeIsRefused) {
  TempDir dir;
  ObjBuilder model;
  model.room();
  model.lamp();
  model.write(dir);
  auto scene_with = [&](const std::string& materials) {
    return dir.write("s.json", R"({"meshes": [{"file": "model.obj"}], "materials": {)" + materials + "}}");
  };
  for (const std::string value : {"1.0", "[0.5, 1.2, 0.5]"}) {
    const std::string scene = scene_with(R"("unused_chrome": {"reflectance": )" + value + "}");
    const Solution s = solve(dir, scene, "--iterations 5");
    expect_sane(s);
    EXPECT_NE(s.run.output.find("material 'unused_chrome' (" + scene + " (materials.unused_chrome)): reflectance"),
              npos)
        << s.run.output;
    EXPECT_NE(s.run.output.find("lowered to"), npos) << s.run.output;
    expect_refused_strictly(dir, scene, {"'unused_chrome'", "s.json", "below 1"});
  }
  // Used: the walls are lit as reflecting 0.95.
  EXPECT_EQ(material_named(info(scene_with(R"("wall": {"reflectance": 1.5})")), "wall")["reflectance"],
            json({0.95, 0.95, 0.95}));
  // Negative is refused, --strict or not.
  const std::string negative = scene_with(R"("unused_chrome": {"reflectance": -0.1})");
  const auto r = test::run_dynrad("solve '" + negative + "' -o '" + dir.path("out.ply") + "'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'unused_chrome'"), npos) << r.output;
  EXPECT_NE(r.output.find("must not be negative"), npos) << r.output;
  EXPECT_FALSE(test::file_exists(dir.path("out.ply")));
  expect_refused_strictly(dir, negative, {"'unused_chrome'", "must not be negative"});
}

// Lines with unknown keywords are skipped with a warning naming the line; obj_info is a
// PLY keyword and read silently. Neither may shift what OpenMesh reads: a word like
// "element" in them is not a keyword, and a skipped line just before end_header of a
// binary file must not move the data by a byte.
TEST(HostileInput, UnknownPlyHeaderLinesAreSkippedWithAWarning) {
  TempDir dir;
  const std::string ascii = dir.write(
      "h.ply",
      "ply\nformat ascii 1.0\nobj_info scanned: element vertex 99\nfoo bar\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nfoo element 12\nend_header\n"
      "0 0 0\n2 0 0\n0 3 0\n3 0 1 2 128 64 32\n");
  const json counts = info(ascii);
  EXPECT_EQ(counts["faces"].get<int>(), 1);
  EXPECT_EQ(counts["bounds"]["max"], json({2.0, 3.0, 0.0}));
  const Rgb colour = channel_array(counts["materials"][0]["reflectance"]);
  auto linear = [](double byte) { return std::pow((byte / 255 + 0.055) / 1.055, 2.4); };
  EXPECT_NEAR(colour.r, linear(128), 1e-6);
  EXPECT_NEAR(colour.b, linear(32), 1e-6);
  const std::string warnings = counts["warnings"].dump();
  EXPECT_EQ(counts["warnings"].size(), 2u) << warnings;  // obj_info is not warned about
  EXPECT_NE(warnings.find(ascii + ":4: PLY header line 'foo bar' has an unknown keyword"), npos) << warnings;
  EXPECT_NE(warnings.find(ascii + ":14: PLY header line 'foo element 12'"), npos) << warnings;
  EXPECT_EQ(warnings.find("obj_info scanned"), npos) << warnings;

  std::string binary =
      "ply\ncomment before the format\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
      "made_by some scanner\nend_header\n";
  for (float x : {0.f, 0.f, 0.f, 2.f, 0.f, 0.f, 0.f, 3.f, 0.f}) binary.append(reinterpret_cast<const char*>(&x), 4);
  binary += '\3';
  for (std::int32_t i : {0, 1, 2}) binary.append(reinterpret_cast<const char*>(&i), 4);
  const std::string binary_path = dir.write("b.ply", binary);
  const json binary_counts = info(binary_path);
  EXPECT_EQ(binary_counts["bounds"]["max"], json({2.0, 3.0, 0.0}));
  EXPECT_NEAR(binary_counts["total_area"].get<double>(), 3.0, 1e-12);
  EXPECT_NE(binary_counts["warnings"].dump().find(binary_path + ":10: PLY header line 'made_by some scanner'"), npos)
      << binary_counts.dump(2);

  for (const std::string& path : {ascii, binary_path}) {
    const auto r = test::run_dynrad("info '" + path + "' --strict");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("unknown keyword"), npos) << r.output;
  }
  const auto obj_info_only = test::run_dynrad(
      "info --strict '" +
      dir.write("o.ply",
                "ply\nformat ascii 1.0\nobj_info element face 7\nelement vertex 3\nproperty float x\n"
                "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n") +
      "'");
  EXPECT_EQ(obj_info_only.exit_code, 0) << obj_info_only.output;
  EXPECT_EQ(obj_info_only.output.find("warning"), npos) << obj_info_only.output;
}

// UTF-8 text as UTF-16 with a byte-order mark.
std::string utf16(const std::string& utf8, bool big_endian) {
  std::string out;
  auto unit = [&](std::uint32_t u) {
    const char high = static_cast<char>(u >> 8), low = static_cast<char>(u & 0xFF);
    out += big_endian ? std::string{high, low} : std::string{low, high};
  };
  unit(0xFEFF);
  for (std::size_t i = 0; i < utf8.size();) {
    const auto lead = static_cast<unsigned char>(utf8[i]);
    const int length = lead < 0x80 ? 1 : lead < 0xE0 ? 2 : lead < 0xF0 ? 3 : 4;
    std::uint32_t code_point = length == 1 ? lead : lead & (0x7F >> length);
    for (int k = 1; k < length; ++k) code_point = (code_point << 6) | (static_cast<unsigned char>(utf8[i + k]) & 0x3F);
    i += length;
    if (code_point < 0x10000) {
      unit(code_point);
    } else {
      unit(0xD800 + ((code_point - 0x10000) >> 10));
      unit(0xDC00 + ((code_point - 0x10000) & 0x3FF));
    }
  }
  return out;
}

TEST(HostileInput, Utf16AndUtf8ByteOrderMarksAreDecoded) {
  ObjBuilder model;
  model.material("wand_wei\u00df", 0.6, 0);
  model.obj << "# ein Zimmer \U0001F3E0\n";  // outside the BMP: a surrogate pair in UTF-16
  model.room(true, "wand_wei\u00df");
  model.lamp();
  TempDir plain_dir;
  const Solution plain = solve(plain_dir, model.write(plain_dir), "--iterations 30");
  expect_sane(plain);
  for (const std::string encoding : {"utf-8 with mark", "utf-16le", "utf-16be"}) {
    SCOPED_TRACE(encoding);
    auto encode = [&](const std::string& text) {
      if (encoding == "utf-8 with mark") return "\xEF\xBB\xBF" + text;
      return utf16(text, encoding == "utf-16be");
    };
    TempDir dir;
    dir.write("model.mtl", encode(model.mtl.str()));
    const std::string input = dir.write("model.obj", encode(model.obj.str()));
    const Solution s = solve(dir, input, "--iterations 30 --strict");
    expect_sane(s);
    expect_same_light(s, plain);
    EXPECT_NEAR(material_named(info(input), "wand_wei\u00df")["reflectance"][1].get<double>(), 0.6, 1e-12);
  }

  // Damaged UTF-16 is refused: cut in the middle of a character, or a lone surrogate.
  TempDir dir;
  const std::string text = utf16("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", false);
  const auto cut = test::run_dynrad("info '" + dir.write("cut.obj", text.substr(0, text.size() - 1)) + "'");
  EXPECT_EQ(cut.exit_code, 2) << cut.output;
  EXPECT_NE(cut.output.find("middle of a character"), npos) << cut.output;
  const std::string lone = text.substr(0, 2 + 2 * 16) + std::string("\x00\xD8#\x00\n\x00", 6) + text.substr(2 + 2 * 16);
  const auto surrogate = test::run_dynrad("info '" + dir.write("lone.obj", lone) + "'");
  EXPECT_EQ(surrogate.exit_code, 2) << surrogate.output;
  EXPECT_NE(surrogate.output.find("lone.obj:3"), npos) << surrogate.output;
  EXPECT_NE(surrogate.output.find("lone surrogate"), npos) << surrogate.output;
  // UTF-16 without a mark is not guessed at: its zero bytes make it binary data.
  const auto unmarked = test::run_dynrad("info '" + dir.write("plain16.obj", text.substr(2)) + "'");
  EXPECT_EQ(unmarked.exit_code, 2) << unmarked.output;
  EXPECT_NE(unmarked.output.find("binary data"), npos) << unmarked.output;
}

// PLY float colours are display colours from 0 to 1, like byte ones: white is clamped to
// 0.95 with a warning; values outside [0, 1] are refused naming the face (OpenMesh would
// wrap them around: 1.5 became 0.49).
TEST(HostileInput, PlyFloatColoursOutsideZeroToOneAreRefused) {
  TempDir dir;
  auto ply = [&](const std::string& colour) {
    return dir.write("c.ply",
                     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
                     "property float red\nproperty float green\nproperty float blue\nend_header\n"
                     "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0.5 0.5 0.5\n3 0 2 1 " +
                         colour + "\n");
  };
  const json white = info(ply("1 1 1"));
  ASSERT_EQ(white["materials"].size(), 2u) << white.dump(2);
  EXPECT_EQ(white["materials"][1]["reflectance"][0].get<double>(), 0.95);
  EXPECT_NE(white["warnings"].dump().find("clamped"), std::string::npos) << white.dump(2);

  for (const char* colour : {"1.5 0.5 0.5", "0.5 -0.5 0.5", "0.5 0.5 nan", "0.5 0.5 inf"}) {
    const auto r = test::run_dynrad("info '" + ply(colour) + "'");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("c.ply:17"), std::string::npos) << r.output;  // face 1's line
    EXPECT_NE(r.output.find("face 1 has colour"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("outside [0, 1]"), std::string::npos) << r.output;
  }
}

// An ASCII PLY face whose vertex index does not fit in an int is refused naming its line:
// OpenMesh's stream failed on it and then read every later list count as garbage,
// allocating 4 GB (found by the ply fuzz target).
TEST(HostileInput, PlyListEntryTooLargeForAnIntIsRefused) {
  TempDir dir;
  const std::string path = dir.write("big.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                     "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
                                     "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 22222222222222222222 1\n");
  const auto r = test::run_dynrad("info '" + path + "'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("big.ply:14"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("fits in 32 bits"), std::string::npos) << r.output;
  const auto letters = test::run_dynrad(
      "info '" + dir.write("word.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                       "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                       "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 one 2\n") + "'");
  EXPECT_EQ(letters.exit_code, 2) << letters.output;
  EXPECT_NE(letters.output.find("entry 'one'"), std::string::npos) << letters.output;
}

// The same check on binary PLY, where OpenMesh's conversion is the same.
TEST(HostileInput, BinaryPlyFloatColoursAreCheckedToo) {
  TempDir dir;
  auto binary_ply = [&](float red, bool big_endian) {
    std::string text = std::string("ply\nformat binary_") + (big_endian ? "big" : "little") +
                       "_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                       "element face 1\nproperty list uchar int vertex_indices\nproperty float red\n"
                       "property float green\nproperty float blue\nend_header\n";
    auto put = [&](const void* p, std::size_t n) {
      std::string bytes(static_cast<const char*>(p), n);
      if (big_endian) std::reverse(bytes.begin(), bytes.end());
      text += bytes;
    };
    const float points[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    for (float x : points) put(&x, 4);
    text += '\3';
    for (std::int32_t i : {0, 1, 2}) put(&i, 4);
    for (float c : {red, 0.5f, 0.5f}) put(&c, 4);
    return dir.write("b.ply", text);
  };
  for (bool big : {false, true}) {
    EXPECT_EQ(info(binary_ply(0.25f, big))["materials"].size(), 1u);
    const auto r = test::run_dynrad("info '" + binary_ply(3.0f, big) + "'");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("face 0 has colour red = 3"), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace dynrad
