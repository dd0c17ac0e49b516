// MeshLab (Debian's 2020.09, the viewer most of our users open results in) must read
// what we write: vertex colours as uchar red/green/blue and per-vertex quality. This
// loads and re-saves an exported file with meshlabserver and compares.
#include "test_support.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <gtest/gtest.h>

namespace dynrad {
namespace {

using ReadMesh = OpenMesh::TriMesh_ArrayKernelT<>;

TEST(MeshLab, ReadsOurColoursAndQuality) {
  test::TempDir dir;
  const std::string ours = dir.path("ours.ply");
  const std::string theirs = dir.path("meshlab.ply");
  const auto made = test::run_dynrad("clean '" + test::sample("cornell_box.obj") + "' -o '" + ours + "'");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const auto ml = test::run_shell("xvfb-run -a meshlabserver -i '" + ours + "' -o '" + theirs + "' -m vc vq");
  ASSERT_EQ(ml.exit_code, 0) << "meshlabserver failed (CI installs meshlab and xvfb):\n" << ml.output;

  ReadMesh a, b;
  for (ReadMesh* m : {&a, &b}) m->request_vertex_colors();
  OpenMesh::IO::Options io = OpenMesh::IO::Options::VertexColor | OpenMesh::IO::Options::Custom;
  ASSERT_TRUE(OpenMesh::IO::read_mesh(a, ours, io));
  io = OpenMesh::IO::Options::VertexColor | OpenMesh::IO::Options::Custom;
  ASSERT_TRUE(OpenMesh::IO::read_mesh(b, theirs, io));
  ASSERT_EQ(a.n_vertices(), b.n_vertices());
  ASSERT_EQ(a.n_faces(), b.n_faces());
  OpenMesh::VPropHandleT<float> qa, qb;
  ASSERT_TRUE(a.get_property_handle(qa, "quality"));
  ASSERT_TRUE(b.get_property_handle(qb, "quality")) << "MeshLab dropped the quality property";
  std::size_t non_grey = 0;
  for (auto v : a.vertices()) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(a.color(v)[c], b.color(v)[c]);
    EXPECT_FLOAT_EQ(a.property(qa, v), b.property(qb, v));
    non_grey += a.color(v)[0] != a.color(v)[1];
  }
  EXPECT_GT(non_grey, 0u);  // the red and green walls really are coloured
}

}  // namespace
}  // namespace dynrad
