#include "mesh/io/atomic_file.h"
#include "mesh/core/error.h"
#include "mesh/io/export.h"
#include "mesh/load.h"
#include "radiosity/analysis/tonemap.h"
#include "test_support.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <set>

namespace dynrad {
namespace {

using ReadMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// Values that differ per output vertex, so a permutation would be caught.
VertexValues values_for(const SceneMesh& scene, const VertexSplit& split) {
  std::vector<Rgb> linear;
  for (std::size_t i = 0; i < split.size(); ++i) {
    const Vec3d p = scene.mesh().point(split.source[i]);
    linear.emplace_back(0.001 * p[0] + 0.01 * i, 0.002 * p[1], 0.5 + 0.0001 * i);
  }
  return rad::tone_map(std::move(linear), 0.7, "radiosity");
}

void expect_round_trip(const std::string& path, bool ascii) {
  LoadedScene scene = load_scene(test::sample("cornell_box.obj"));
  const VertexSplit split = split_vertices(*scene.mesh);
  const VertexValues values = values_for(*scene.mesh, split);
  WriteOptions options;
  options.ascii = ascii;
  write_mesh_with_values(path, *scene.mesh, split, values, options);

  ReadMesh back;
  back.request_vertex_colors();
  OpenMesh::IO::Options io = OpenMesh::IO::Options::VertexColor | OpenMesh::IO::Options::Custom;
  ASSERT_TRUE(OpenMesh::IO::read_mesh(back, path, io));
  ASSERT_EQ(back.n_vertices(), split.size());
  ASSERT_EQ(back.n_faces(), scene.mesh->face_count());
  OpenMesh::VPropHandleT<float> r, g, b, q;
  ASSERT_TRUE(back.get_property_handle(r, "radiosity_r"));
  ASSERT_TRUE(back.get_property_handle(g, "radiosity_g"));
  ASSERT_TRUE(back.get_property_handle(b, "radiosity_b"));
  ASSERT_TRUE(back.get_property_handle(q, "quality"));
  for (std::size_t i = 0; i < split.size(); ++i) {
    OpenMesh::VertexHandle v(static_cast<int>(i));
    const Vec3d expected = scene.mesh->mesh().point(split.source[i]);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back.point(v)[c], expected[c], 1e-3);
    EXPECT_EQ(back.color(v)[0], values.display[i][0]);
    EXPECT_EQ(back.color(v)[1], values.display[i][1]);
    EXPECT_EQ(back.color(v)[2], values.display[i][2]);
    EXPECT_NEAR(back.property(r, v), values.linear[i].r, 1e-6);
    EXPECT_NEAR(back.property(g, v), values.linear[i].g, 1e-6);
    EXPECT_NEAR(back.property(b, v), values.linear[i].b, 1e-6);
    EXPECT_NEAR(back.property(q, v), values.linear[i].luminance(), 1e-6);
  }
}

TEST(Export, BinaryPlyRoundTrip) {
  test::TempDir dir;
  expect_round_trip(dir.path("out.ply"), false);
  EXPECT_NE(test::read_text(dir.path("out.ply")).find("format binary_little_endian"), std::string::npos);
}

TEST(Export, AsciiPlyRoundTrip) {
  test::TempDir dir;
  expect_round_trip(dir.path("out.ply"), true);
  EXPECT_NE(test::read_text(dir.path("out.ply")).find("format ascii"), std::string::npos);
}

TEST(Export, OffCarriesPositionsAndColours) {
  test::TempDir dir;
  LoadedScene scene = load_scene(test::sample("globillum_room.obj"));
  const VertexSplit split = split_vertices(*scene.mesh);
  const VertexValues values = values_for(*scene.mesh, split);
  const std::string path = dir.path("out.off");
  write_mesh_with_values(path, *scene.mesh, split, values);
  EXPECT_EQ(test::read_text(path).rfind("COFF", 0), 0u);
  ReadMesh back;
  back.request_vertex_colors();
  OpenMesh::IO::Options io = OpenMesh::IO::Options::VertexColor;
  ASSERT_TRUE(OpenMesh::IO::read_mesh(back, path, io));
  ASSERT_EQ(back.n_vertices(), split.size());
  for (std::size_t i = 0; i < split.size(); ++i) {
    OpenMesh::VertexHandle v(static_cast<int>(i));
    EXPECT_EQ(back.color(v)[0], values.display[i][0]);
    EXPECT_EQ(back.color(v)[2], values.display[i][2]);
  }
}

TEST(VertexSplit, EachSurfaceAtACornerGetsItsOwnVertex) {
  LoadedScene scene = load_scene(test::sample("globillum_room.obj"));
  const SceneMesh& mesh = *scene.mesh;
  const VertexSplit split = split_vertices(mesh);
  // Every corner of an output vertex belongs to faces of one material and one plane.
  std::vector<int> first_face(split.size(), -1);
  for (auto f : mesh.mesh().faces())
    for (int k = 0; k < 3; ++k) {
      const auto out = split.corner[3 * f.idx() + k];
      if (first_face[out] < 0) {
        first_face[out] = f.idx();
        continue;
      }
      const FaceHandle g(first_face[out]);
      EXPECT_EQ(mesh.material_id(f), mesh.material_id(g));
      EXPECT_GT(OpenMesh::dot(mesh.normal(f), mesh.normal(g)), 0.99);
    }
  // The room's 8 corners each touch 3 surfaces.
  const Bounds b = mesh.bounds();
  for (auto v : mesh.mesh().vertices()) {
    const Vec3d p = mesh.mesh().point(v);
    int on_bounds = 0;
    for (int c = 0; c < 3; ++c) on_bounds += (p[c] == b.lo[c] || p[c] == b.hi[c]);
    if (on_bounds != 3) continue;
    std::size_t copies = 0;
    for (auto s : split.source) copies += (s == v);
    EXPECT_EQ(copies, 3u);
  }
}

TEST(VertexSplit, SmoothSameMaterialNeighboursShareVertices) {
  LoadedScene scene = load_scene(test::sample("paper_sphere_room.obj"));
  const VertexSplit split = split_vertices(*scene.mesh, 30.0);
  // The sphere (80 triangles, 42 vertices) is smooth at 30 degrees: no vertex is split
  // there. Count the output vertices that come from sphere faces.
  std::set<std::uint32_t> sphere_outputs;
  for (auto f : scene.mesh->mesh().faces())
    if (scene.mesh->material(f).name == "sphere")
      for (int k = 0; k < 3; ++k) sphere_outputs.insert(split.corner[3 * f.idx() + k]);
  EXPECT_EQ(sphere_outputs.size(), 42u);
}

TEST(AtomicFile, AFailedWriteLeavesTheOldFileAndNoTemporary) {
  test::TempDir dir;
  const std::string target = dir.write("keep.ply", "old contents");
  {
    AtomicFile file(target);
    file.stream() << "half a new file";
    // no commit: an error happened
  }
  EXPECT_EQ(test::read_text(target), "old contents");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path("")), {}), 1);
  {
    AtomicFile file(target);
    file.stream() << "new contents";
    file.commit();
  }
  EXPECT_EQ(test::read_text(target), "new contents");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path("")), {}), 1);
}

// A link stays a link (the file it points to gets the new contents); a named pipe (as
// /dev/null, /dev/stdout) is written in place, not replaced by a file, and is not
// opened ahead by the early writability check.
TEST(AtomicFile, LinksAreKeptAndPipesWrittenInPlace) {
  namespace fs = std::filesystem;
  test::TempDir dir;
  const std::string real = dir.write("real.ply", "old contents");
  fs::create_symlink(real, dir.path("link.ply"));
  check_output_writable(dir.path("link.ply"));
  {
    AtomicFile file(dir.path("link.ply"));
    file.stream() << "new contents";
    file.commit();
  }
  EXPECT_TRUE(fs::is_symlink(dir.path("link.ply")));
  EXPECT_EQ(test::read_text(real), "new contents");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path("")), {}), 2);  // no temporary left

  const std::string pipe = dir.path("pipe");
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  check_output_writable(pipe);  // must not block: nothing reads yet
  const int reader = ::open(pipe.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  {
    AtomicFile file(pipe, std::ios::out);
    file.stream() << "through the pipe";
    file.commit();
  }
  std::string received;
  char buffer[256];
  for (ssize_t n; (n = ::read(reader, buffer, sizeof buffer)) > 0;) received.append(buffer, static_cast<std::size_t>(n));
  ::close(reader);
  EXPECT_EQ(received, "through the pipe");  // a rename would have left the reader with nothing
  EXPECT_TRUE(fs::is_fifo(pipe));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path("")), {}), 3);
}

TEST(AtomicFile, MissingDirectoryIsAClearError) {
  try {
    AtomicFile file("/nonexistent-dynrad-dir/out.ply");
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
  }
}

}  // namespace
}  // namespace dynrad
