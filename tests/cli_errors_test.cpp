// Bad input through the command line: each case must print a message naming the file
// (and line where the format has lines), exit with code 2, and leave no output file
// (or leave an existing one untouched).
#include "test_support.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>

namespace dynrad {
namespace {

using test::TempDir;

const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

struct Refusal {
  std::string output;  // what dynrad printed
};

// Runs `dynrad clean INPUT -o OUT [OPTIONS]` twice: with no output file present (none
// may appear) and with an existing one (it must keep its contents).
Refusal expect_refused(const TempDir& dir, const std::string& input, const std::vector<std::string>& must_mention,
                       const std::string& output_name = "out.ply", const std::string& options = "") {
  const std::string out = dir.path(output_name);
  std::filesystem::remove(out);
  const auto result = test::run_dynrad("clean '" + input + "' -o '" + out + "' " + options);
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_FALSE(test::file_exists(out)) << "a failed run left " << out;
  for (const auto& text : must_mention) EXPECT_NE(result.output.find(text), std::string::npos) << result.output;
  // An existing output survives.
  if (std::filesystem::path(out).parent_path() == std::filesystem::path(dir.path(""))) {
    dir.write(output_name, "precious");
    const auto again = test::run_dynrad("clean '" + input + "' -o '" + out + "' " + options);
    EXPECT_EQ(again.exit_code, 2);
    EXPECT_EQ(test::read_text(out), "precious");
    std::filesystem::remove(out);
  }
  // No temporary file is left behind either.
  for (const auto& entry : std::filesystem::directory_iterator(dir.path("")))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  return {result.output};
}

TEST(BadInput, TruncatedBinaryPly) {
  TempDir dir;
  const auto made =
      test::run_dynrad("clean '" + test::sample("cornell_box.obj") + "' -o '" + dir.path("full.ply") + "'");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const std::string full = test::read_text(dir.path("full.ply"));
  const std::string input = dir.write("cut.ply", full.substr(0, full.size() / 2));
  expect_refused(dir, input, {"cut.ply", "truncated"});
}

TEST(BadInput, TruncatedObjNamesTheLine) {
  TempDir dir;
  const std::string input = dir.write("cut.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2");
  expect_refused(dir, input, {"cut.obj:4", "truncated"});
  const std::string vertex = dir.write("cutv.obj", "v 0 0 0\nv 1 0 0\nv 0 1");
  expect_refused(dir, vertex, {"cutv.obj:3"});
}

// A damaged header must not make dynrad allocate or loop until the machine gives up.
TEST(BadInput, ImpossibleElementCountsFailFast) {
  TempDir dir;
  expect_refused(dir, dir.write("huge.off", "OFF\n4000000000 1 0\n0 0 0\n"), {"huge.off", "declares 4000000000"});
  expect_refused(dir,
                 dir.write("huge.ply",
                           "ply\nformat ascii 1.0\nelement vertex 900000000\nproperty float x\n"
                           "property float y\nproperty float z\nend_header\n0 0 0\n"),
                 {"huge.ply", "header is damaged"});
}

// Found by fuzzing (scripts/fuzz.sh): OpenMesh's PLY reader wrote through a property
// that no element precedes (a segfault), and read negative OFF counts as four billion
// (a hang). The headers are now checked first.
TEST(BadInput, DamagedPlyHeadersAreRefusedNamingTheLine) {
  TempDir dir;
  const std::string tail = "property float y\nproperty float z\nelement face 0\nend_header\n0 0 0\n";
  // The fuzzer's input: "element" damaged to "elemeplx", so the properties had no element.
  // Lines with unknown keywords are skipped with a warning (HostileInput tests), so
  // the first property is what is refused; --strict refuses the unknown keyword itself.
  const std::string damaged =
      dir.write("k.ply", "ply\nformat binary_little_endian 1.0\nelemeplx\nertex 4\nproperty float x\n" + tail);
  expect_refused(dir, damaged, {"k.ply:5", "before any element"});
  expect_refused(dir, damaged, {"k.ply:3", "unknown keyword 'elemeplx'"}, "out.ply", "--strict");
  // A header line that is not text is damage, --strict or not.
  expect_refused(
      dir, dir.write("b.ply", "ply\nformat ascii 1.0\nx\x01\x02\x03\nelement vertex 1\nproperty float x\n" + tail),
      {"b.ply:3", "not text"});
  expect_refused(dir, dir.write("p.ply", "ply\nformat ascii 1.0\ncomment no element yet\nproperty float x\n" + tail),
                 {"p.ply:4", "before any element"});
  expect_refused(dir, dir.write("n.ply", "ply\nformat ascii 1.0\nelement vertex -1\nproperty float x\n" + tail),
                 {"n.ply:3", "whole number"});
  // An element dynrad does not use still has to fit in the file.
  expect_refused(dir,
                 dir.write("x.ply",
                           "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                           "property float y\nproperty float z\nelement edge 3000000000\n"
                           "property int vertex1\nelement face 0\nend_header\n0 0 0\n"),
                 {"x.ply", "3000000000 edge elements", "header is damaged"});
  expect_refused(dir, dir.write("t.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quaternion x\n" + tail),
                 {"t.ply:4", "unknown type"});
  expect_refused(dir, dir.write("e.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"),
                 {"e.ply", "no end_header"});
}

TEST(BadInput, NegativeOrHugeOffCountsFailFast) {
  TempDir dir;
  // The fuzzer's input, shortened: a face count of -2 made OpenMesh loop 2^32 times.
  expect_refused(dir, dir.write("neg.off", "COFF\n4 -2 0\n0 0 0 255 0 0 255\n1 0 0 0 0 255 255\n"),
                 {"neg.off:2", "whole numbers", "'4 -2 0'"});
  // Would overflow 64 bits when multiplied by the bytes a face needs.
  expect_refused(dir, dir.write("big.off", "OFF\n3 18446744073709551615 0\n0 0 0\n1 0 0\n0 1 0\n"),
                 {"big.off", "whole numbers"});
  expect_refused(dir, dir.write("wide.off", "OFF\n3 999999999999999999 0\n0 0 0\n1 0 0\n0 1 0\n"),
                 {"wide.off", "declares 3 vertices and 999999999999999999 faces"});
}

// Binary OFF as OpenMesh writes it (little-endian counts after "OFF BINARY"). It was
// read from memory as if it were text and always refused; damaged counts made
// OpenMesh loop for minutes.
TEST(BadInput, BinaryOffIsReadAndItsCountsChecked) {
  TempDir dir;
  auto binary_off = [](std::int32_t vertices, std::int32_t faces) {
    std::string text = "OFF BINARY\n";
    auto put = [&](const auto& value) { text.append(reinterpret_cast<const char*>(&value), sizeof value); };
    for (std::int32_t count : {vertices, faces, 0}) put(count);
    for (float x : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(x);
    for (std::int32_t i : {3, 0, 1, 2}) put(i);
    return text;
  };
  const auto ok = test::run_dynrad("info --json '" + dir.write("ok.off", binary_off(3, 1)) + "'");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_EQ(nlohmann::json::parse(ok.output)["faces"].get<int>(), 1);
  expect_refused(dir, dir.write("many.off", binary_off(2000000000, 1)), {"many.off", "declares 2000000000 vertices"});
  expect_refused(dir, dir.write("neg.off", binary_off(3, -5)), {"neg.off", "-5 faces"});
  // Found by fuzzing (CI, stop 22): a face declaring 4294901760 corners in a 128-byte
  // file; OpenMesh appended that many indices until the fuzzer's timeout.
  std::string corners = binary_off(3, 1);
  const std::uint32_t damaged = 0xFFFF0000u;
  corners.replace(corners.size() - 16, 4, reinterpret_cast<const char*>(&damaged), 4);
  expect_refused(dir, dir.write("corners.off", corners), {"corners.off", "face 0 declares 4294901760 corners"});
  // With 'C' a vertex carries a colour and so does a face (three 32-bit values each):
  // the walk over the records must not refuse a whole file.
  std::string coloured = "COFF BINARY\n";
  auto put = [&](const auto& value) { coloured.append(reinterpret_cast<const char*>(&value), sizeof value); };
  for (std::int32_t count : {3, 1, 0}) put(count);
  for (int v = 0; v < 3; ++v) {
    for (float x : {float(v == 1), float(v == 2), 0.f}) put(x);
    for (std::int32_t c : {200, 100, 50}) put(c);
  }
  for (std::int32_t i : {3, 0, 1, 2, 200, 100, 50}) put(i);
  const auto with_colour = test::run_dynrad("info --json '" + dir.write("colour.off", coloured) + "'");
  ASSERT_EQ(with_colour.exit_code, 0) << with_colour.output;
  EXPECT_EQ(nlohmann::json::parse(with_colour.output)["faces"].get<int>(), 1);
  expect_refused(dir, dir.write("short_colour.off", coloured.substr(0, coloured.size() - 4)),
                 {"short_colour.off", "face 0 declares 3 corners"});
}

// Found by fuzzing: OpenMesh believes a face's corner count and appends that many
// indices whatever the line or file holds (2 GB and counting); a PLY "format" line with
// a damaged version made its header reader loop for ever.
TEST(BadInput, CornerCountsBeyondTheDataAreRefused) {
  TempDir dir;
  expect_refused(dir, dir.write("long.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2222222222 0 1 2\n"),
                 {"long.off:6", "declares 2222222222 corners but lists 3"});
  expect_refused(dir, dir.write("word.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n0.5 0 1 2\n"),
                 {"word.off:6", "number of corners, not '0.5'"});
  const std::string header =
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list int int vertex_indices\nend_header\n";
  expect_refused(dir, dir.write("list.ply", "ply\nformat ascii 1.0\n" + header + "0 0 0\n1 0 0\n0 1 0\n9999 0 1 2\n"),
                 {"list.ply:13", "declares 9999 entries"});
  std::string binary = "ply\nformat binary_little_endian 1.0\n" + header;
  for (float x : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) binary.append(reinterpret_cast<const char*>(&x), 4);
  for (std::int32_t i : {-1, 0, 1, 2}) binary.append(reinterpret_cast<const char*>(&i), 4);
  expect_refused(dir, dir.write("list_bin.ply", binary), {"list_bin.ply", "face 0", "declares 4294967295 entries"});
  // Found by fuzzing (2026-12-01): a misspelt property line ("proper1y", read as a
  // comment) left a face line with a value too many and a "2-5"; OpenMesh reads words,
  // not lines, took a face count of -5 and appended indices until 7 GB.
  const std::string shifted = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                              "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                              "proper1y uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
                              "0 0 0\n1 0 0\n0 1 0\n";
  expect_refused(dir, dir.write("dash.ply", shifted + "3 0 1 2 255 2-5\n"), {"dash.ply:16", "'2-5' is not a number"});
  expect_refused(dir, dir.write("extra.ply", shifted + "3 0 1 2 255 20 90\n"),
                 {"extra.ply:16", "face 0 holds 7 values", "misspelt"});
  expect_refused(dir, dir.write("version.ply", "ply\nformat binary_little_endian ndices\nend_header\n"),
                 {"version.ply:2", "unknown version 'ndices'"});
  expect_refused(dir, dir.write("extra.ply", "ply\nformat ascii 1.0\nelement vertex 3 4\n"),
                 {"extra.ply:3", "unexpected '4'"});
}

// Found by fuzzing: OpenMesh reads an OFF vertex's coordinates from the token stream,
// so a vertex line with two numbers took its third from the next line and shifted every
// later line; a face then declared billions of corners (a 3 GB allocation). Each vertex
// line must now hold its coordinates.
TEST(BadInput, ShortOffVertexLinesAreRefusedNamingTheLine) {
  TempDir dir;
  expect_refused(dir, dir.write("short.off", "COFF\n4 2 0\n0 0 5 255 0 0 255\n1 0 \n4 2 0\n0 0 5\n3 0 1 2\n3 0 2 3\n"),
                 {"short.off:4", "vertex 1 must hold 3 numbers"});
  expect_refused(dir, dir.write("normals.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0\n0 1 0 0 0 1\n3 0 1 2\n"),
                 {"normals.off:4", "vertex 1 must hold 6 numbers"});
  // Also found by fuzzing: OpenMesh read the index "2-4" as 2, then "-4" as the next
  // face's corner count (four billion).
  expect_refused(dir, dir.write("dash.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2-4\n3 0 2 3\n"),
                 {"dash.off:7", "corner 2 is '2-4'"});
}

// Found by fuzzing: OpenMesh takes the whole first line as the keyword and the next
// three words as counts, wherever they are; "COFF\x12 8 2 0" then had it read counts
// from past the end and allocate 4 GB. Keyword and counts now have a line each.
TEST(BadInput, OffKeywordAndCountsMustHaveALineEach) {
  TempDir dir;
  expect_refused(dir,
                 dir.write("k.off",
                           "COFF\x12"
                           "8 2 0\n#c\n"),
                 {"k.off:1", "only the keyword"});
  // Found by fuzzing: "BINARY" not where OpenMesh looks for it, so it read the file as
  // ASCII while the checks took it for binary (a 4-billion-face loop).
  expect_refused(dir, dir.write("b.off", std::string("OFFOGF BINARY 0.6\n\0\0\0\0 comm0\n0.3, 0\n", 26)),
                 {"b.off:1", "only the keyword"});
  expect_refused(dir, dir.write("one.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                 {"one.off:1", "Put the counts on the next line"});
  expect_refused(dir, dir.write("two.off", "OFF\n# counts\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                 {"two.off:3", "three whole numbers"});
  const auto ok = test::run_dynrad("info '" +
                                   dir.write("ok.off",
                                             "NOFF\n\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n"
                                             "0 1 0 0 0 1\n3 0 1 2\n") +
                                   "'");
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
}

// Found by fuzzing: a number beyond double's range made the JSON library throw an
// exception that was not a parse error, which ended dynrad with "internal error".
TEST(BadInput, SceneNumberBeyondDoubleRangeIsAnInputError) {
  TempDir dir;
  dir.write("t.obj", kTriangleObj);
  expect_refused(dir, dir.write("big.json", R"({"meshes": [{"file": "t.obj", "transform": {"scale": 1e3083}}]})"),
                 {"big.json", "invalid JSON", "1e3083"});
}

TEST(BadInput, MislabelledFiles) {
  TempDir dir;
  expect_refused(dir, dir.write("text.ply", kTriangleObj), {"text.ply", "mislabelled"});
  expect_refused(dir, dir.write("text.off", "ply\nformat ascii 1.0\n"), {"text.off", "looks like .ply"});
  expect_refused(dir, dir.write("binary.obj", std::string("\x01\x02\0\x03", 4)), {"binary.obj", "binary data"});
}

TEST(BadInput, NanAndInfinityNameTheLine) {
  TempDir dir;
  expect_refused(dir, dir.write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"), {"nan.obj:2", "not finite"});
  expect_refused(dir, dir.write("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n"), {"inf.obj:3"});
  const auto off =
      expect_refused(dir, dir.write("inf.off", "OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n"), {"inf.off"});
  EXPECT_NE(off.output.find("inf.off:4"), std::string::npos) << off.output;
}

TEST(BadInput, OutOfRangeIndices) {
  TempDir dir;
  expect_refused(dir, dir.write("idx.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), {"idx.obj:4", "vertex 9"});
  const auto off = expect_refused(dir, dir.write("idx.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"), {"idx.off"});
  EXPECT_NE(off.output.find("vertex 7"), std::string::npos) << off.output;
}

TEST(BadInput, EmptyScenes) {
  TempDir dir;
  expect_refused(dir, dir.write("empty.obj", "# nothing here\n"), {"empty.obj", "no faces"});
  expect_refused(dir, dir.write("empty.ply", ""), {"empty.ply", "empty"});
  expect_refused(dir, dir.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"), {"flat.obj", "degenerate"});
}

// Without --strict a missing library is a warning (HostileInput tests).
TEST(BadInput, MissingMtlNamesTheObjLineWithStrict) {
  TempDir dir;
  expect_refused(dir, dir.write("m.obj", std::string("mtllib gone.mtl\n") + kTriangleObj),
                 {"m.obj:1", "gone.mtl", "not found"}, "out.ply", "--strict");
  expect_refused(dir, dir.write("u.obj", std::string(kTriangleObj) + "usemtl ghost\nf 1 3 2\n"),
                 {"u.obj", "'ghost'", "u.obj:5", "defined nowhere"}, "out.ply", "--strict");
}

TEST(BadInput, UnreadableInput) {
  TempDir dir;
  expect_refused(dir, dir.path("does-not-exist.obj"), {"does-not-exist.obj", "not found"});
  std::filesystem::create_directory(dir.path("folder.obj"));
  expect_refused(dir, dir.path("folder.obj"), {"folder.obj", "directory"});
  expect_refused(dir, dir.write("model.xyz9", "x"), {"model.xyz9", "unsupported"});
  // Formats assimp reads are read through it; a broken one is refused with its reason.
  expect_refused(dir, dir.write("model.fbx", "x"), {"model.fbx", "could not be read (assimp"});
}

TEST(BadInput, UnwritableOutput) {
  TempDir dir;
  const std::string input = dir.write("ok.obj", kTriangleObj);
  const auto r = test::run_dynrad("clean '" + input + "' -o '" + dir.path("no/such/dir/out.ply") + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("does not exist"), std::string::npos) << r.output;
  std::filesystem::create_directory(dir.path("adir.ply"));
  const auto d = test::run_dynrad("clean '" + input + "' -o '" + dir.path("adir.ply") + "'");
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.output.find("is a directory"), std::string::npos) << d.output;
  const auto ext = test::run_dynrad("clean '" + input + "' -o '" + dir.path("out.xyz") + "'");
  EXPECT_EQ(ext.exit_code, 2);
  EXPECT_FALSE(test::file_exists(dir.path("out.xyz")));
}

// Without --strict it is lowered to 0.95 with a warning (HostileInput tests); a
// negative reflectance is refused either way.
TEST(BadInput, ReflectanceOfOneOrMoreNamesTheMaterialWithStrict) {
  TempDir dir;
  dir.write("r.mtl", "newmtl glowing_white\nKd 1.0 1.0 1.0\nnewmtl anti\nKd 0.5 -0.1 0.5\n");
  const std::string white = dir.write("r.obj", std::string("mtllib r.mtl\nusemtl glowing_white\n") + kTriangleObj);
  expect_refused(dir, white, {"glowing_white", "r.mtl:1", "below 1"}, "out.ply", "--strict");
  const std::string negative = dir.write("n.obj", std::string("mtllib r.mtl\nusemtl anti\n") + kTriangleObj);
  expect_refused(dir, negative, {"'anti'", "r.mtl:3", "must not be negative"});
  expect_refused(dir, negative, {"'anti'", "r.mtl:3", "must not be negative"}, "out.ply", "--strict");
}

TEST(BadInput, BrokenSceneFiles) {
  TempDir dir;
  dir.write("t.obj", kTriangleObj);
  expect_refused(dir, dir.write("syntax.json", "{\n  \"meshes\": [\n    {\"file\": \"t.obj\",}\n  ]\n}\n"),
                 {"syntax.json:3", "invalid JSON"});
  expect_refused(dir, dir.write("key.json", R"({"meshes": [{"file": "t.obj"}], "lights": []})"),
                 {"key.json", "unknown key \"lights\""});
  expect_refused(dir, dir.write("missing.json", R"({"meshes": [{"file": "nope.obj"}]})"), {"nope.obj", "not found"});
}

TEST(CommandLine, InfoReportsCountsAndJson) {
  const auto text = test::run_dynrad("info '" + test::sample("globillum_room.obj") + "'");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("60 triangles"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("light"), std::string::npos);
  const auto json = test::run_dynrad("info --json '" + test::sample("globillum_room.obj") + "'");
  ASSERT_EQ(json.exit_code, 0) << json.output;
  const auto j = nlohmann::json::parse(json.output);
  EXPECT_EQ(j["faces"].get<int>(), 60);
  EXPECT_NEAR(j["total_area"].get<double>(), 216.0, 1e-9);
  EXPECT_NEAR(j["emitting_area"].get<double>(), 0.25, 1e-12);
  EXPECT_NEAR(j["emitted_power"][0].get<double>(), 0.25 * 31.416, 1e-9);
  EXPECT_EQ(j["repairs"]["total"].get<int>(), 0);
  EXPECT_EQ(j["materials"].size(), 4u);
}

TEST(CommandLine, BadOptionsExitWithCode2) {
  EXPECT_EQ(test::run_dynrad("info").exit_code, 2);
  EXPECT_EQ(test::run_dynrad("frobnicate x").exit_code, 2);
  EXPECT_EQ(test::run_dynrad("--help").exit_code, 0);
}

}  // namespace
}  // namespace dynrad

namespace dynrad {
namespace {

// Found by fuzzing: a binary STL whose two triangles meet with one of them collinear to
// CGAL's exact predicates; the hidden-part rays asked CGAL to intersect a ray with it (a
// precondition failure, an abort in checked builds). Degenerate triangles now block no
// ray. The file loads, or is refused, but never crashes.
TEST(BadInput, DegenerateTrianglesFromAnStlDoNotStopImprinting) {
  test::TempDir dir;
  const std::string hex =
      "62696e61727920736565642020202020202020202020202020202020202020202020202020202020202020202020202020202020"
      "202020202020202020202020202020202020202020202020202020200200000000000000000000000000803f0000000000000000"
      "a40030656e646c6f6f70202d310a206f75746572206c6f6f700a2020766572746578205b203000310a2020766572746178203020"
      "3120300a202076657274657800000000000000000000803f803f0000";
  std::string bytes;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2)
    bytes.push_back(static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  ASSERT_EQ(bytes.size(), 184u);
  const auto r = test::run_dynrad("info '" + dir.write("fuzz.stl", bytes) + "'");
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2) << r.output;
}

}  // namespace
}  // namespace dynrad
