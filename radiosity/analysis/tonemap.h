// Display encoding of linear values: exposure, clamp, sRGB transfer curve. Viewers
// (MeshLab, Blender's byte colours) read vertex colours as sRGB, so writing linear
// radiosity straight into bytes makes everything look too dark.
#pragma once

#include "mesh/io/export.h"
#include "mesh/core/types.h"

#include <array>
#include <cstdint>
#include <vector>

namespace dynrad::rad {

// Linear [0, 1] to an sRGB-encoded byte (values outside are clamped).
std::uint8_t encode_srgb(double linear);

// An exposure that maps the 99th percentile of the luminances marked in `include` to
// 0.9 before encoding, so a few very bright vertices (emitters) do not darken the
// rest. Returns 1 when nothing is included or everything is black. With `area` (per
// vertex, see vertex_areas), the percentile is of surface area rather than of vertices:
// the same picture however finely the solver refined where it is bright (a ceiling
// above a lamp holds many small elements, an evenly lit wall few).
double auto_exposure(const std::vector<Rgb>& linear, const std::vector<char>& include,
                     const std::vector<double>& area = {});

// A third of the area of each triangle around each vertex.
std::vector<double> vertex_areas(const std::vector<Vec3d>& positions,
                                 const std::vector<std::array<std::uint32_t, 3>>& triangles);

// Fills display colours (exposure, then sRGB) and quality (luminance, linear and
// unexposed) for the given linear values.
VertexValues tone_map(std::vector<Rgb> linear, double exposure, const std::string& name);

}  // namespace dynrad::rad
