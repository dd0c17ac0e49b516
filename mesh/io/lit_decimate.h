// Decimation of a mesh with per-vertex values for viewers, with a bounded colour error.
//
// A mesh written with write_triangles_with_values (mesh/io/export.h) is as fine as its
// values needed while they were computed, often millions of triangles; a viewer wants
// far fewer. This removes vertices by half-edge collapses (OpenMesh's Decimater) where
// that changes neither the surface nor, beyond a bound, what the viewer shows:
//
// - Geometry: a collapse moves a vertex onto a neighbour only where the faces around it
//   lie in one plane (or in the two planes of a straight crease, along the crease), and
//   a boundary vertex only along a straight boundary line. Boundaries stay where they
//   are: the input's separate smooth regions keep meeting without gaps. No face flips,
//   and no face is made narrower than the flatness tolerance (where its plane would be
//   lost in rounding).
// - Values: every vertex of the input, the removed ones too, is remembered by the face
//   of the simplified mesh that covers it. A collapse is refused if, at any of them, the
//   colour the simplified mesh shows (the barycentric interpolation of the display
//   colours of the face's corners) differs from the vertex's own display colour by more
//   than max(colour_units, colour_fraction * value) in any 8-bit channel, or the
//   interpolated quality from its own by more than max(quality_fraction * |value|,
//   quality_floor).
// - Kept vertices keep all their values exactly (display, linear, quality and every
//   scalar); the values of removed vertices are dropped.
//
// Collapses go in order of the error they cause (the smallest first), until the mesh has
// at most max_triangles or no collapse is allowed. Same input, same output.
#pragma once

#include "mesh/io/export.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace dynrad {

struct LitDecimateOptions {
  // Stop when the mesh has at most this many triangles (or earlier, when no collapse is
  // allowed): a mesh that has no more is left as it is; 0 goes as far as the bound allows.
  std::size_t max_triangles = 500000;
  // The display colour bound per 8-bit channel: max(colour_units, colour_fraction * the
  // original value).
  double colour_units = 1.0;
  double colour_fraction = 0.01;
  // The quality bound: max(quality_fraction * |the original value|, quality_floor).
  // A negative floor means 1e-3 of the largest quality in the mesh.
  double quality_fraction = 0.01;
  double quality_floor = -1;
  // How far (as a fraction of the bounding-box diagonal) a vertex may be from the plane
  // of a face and still count as lying in it: input written as floats is flat only up to
  // their rounding (about 1e-7 of the coordinates).
  double flatness = 1e-6;
  // A second guard against flips (OpenMesh's ModNormalFlippingT): no face's normal may
  // turn by more than this in one collapse.
  double max_normal_deviation_degrees = 1.0;
};

struct LitDecimateReport {
  std::size_t triangles_before = 0, triangles_after = 0;
  std::size_t vertices_before = 0, vertices_after = 0;  // after: the vertices triangles use
  std::size_t collapses = 0;
  // Triangles the half-edge mesh could not take (degenerate: no wider than `flatness`;
  // or non-manifold next to others): kept as they are, with their vertices.
  std::size_t triangles_kept_as_they_are = 0;
  bool reached_target = false;  // triangles_after <= max_triangles
  // The largest errors over every vertex of the input, measured after decimation: in
  // 8-bit units (any channel), in quality units, and as a fraction of the bound at that
  // vertex (at most 1).
  double worst_colour_error = 0;
  double worst_quality_error = 0;
  double worst_error_fraction = 0;
  double quality_floor = 0;  // the floor used
  double seconds = 0;
};

// Replaces the mesh given by `positions`, `triangles` and `values` with its decimation.
// `values.display` must hold one colour per position; `linear`, `quality` and each of
// `scalars` one value per position, or none (`quality` empty: no quality bound). Vertices
// no triangle uses are dropped. Kept vertices stay in their order, triangles in the
// order of the input triangles they come from. Throws std::invalid_argument if the
// sizes disagree or a triangle names a vertex that is not there.
LitDecimateReport decimate_lit_mesh(std::vector<Vec3d>& positions, std::vector<std::array<std::uint32_t, 3>>& triangles,
                                    VertexValues& values, const LitDecimateOptions& options = {});

// The same with a label per triangle (e.g. its group and material): an edge between
// triangles of different labels is kept like a boundary (a vertex on it moves only along
// it, where it runs straight), so every label covers what it covered; `labels` follows
// the triangles. Also throws std::invalid_argument if it has not one label per triangle.
LitDecimateReport decimate_lit_mesh(std::vector<Vec3d>& positions, std::vector<std::array<std::uint32_t, 3>>& triangles,
                                    std::vector<std::uint32_t>& labels, VertexValues& values,
                                    const LitDecimateOptions& options = {});

// A scene's lit mesh (its faces over the split's vertices, what write_mesh_with_values
// writes) decimated, with the group and material of every face as its label: a scene
// mesh of its own (one mesh vertex per output vertex; faces keep their material and
// group, origins are the first input face's of that group and material), its split and
// its values, ready for write_mesh_with_values in any format (.glb needs the groups and
// materials, which write_triangles_with_values does not carry).
struct DecimatedLitMesh {
  std::unique_ptr<SceneMesh> scene;
  VertexSplit split;
  VertexValues values;
  LitDecimateReport report;
};
DecimatedLitMesh decimate_lit_scene(const SceneMesh& scene, const VertexSplit& split, const VertexValues& values,
                                    const LitDecimateOptions& options = {});

}  // namespace dynrad
