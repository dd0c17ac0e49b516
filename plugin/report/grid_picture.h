// A calculation grid as a false-colour plan: smooth colours between the points, iso-lines
// at the legend's steps, a legend in the scene's units and the grid's figures printed
// above it.
#pragma once

#include "plugin/report/text.h"
#include "radiosity/analysis/grid.h"
#include "radiosity/analysis/render.h"

#include <string>

namespace dynrad::report {

// The colour of t in [0, 1] on the false-colour scale: dark blue, blue, cyan, green,
// yellow, red.
std::array<std::uint8_t, 3> false_colour(double t);
// Its colours at t = 0, 0.2, ..., 1 (linear in between), for other renderers of the same
// scale (the walk-through page).
const std::array<std::array<double, 3>, 6>& false_colour_stops();

// The legend's top (a round number at or above `peak`: 1, 2, 2.5 or 5 times a power of
// ten) and its step (a fifth or a tenth of it).
void legend_scale(double peak, double& top, double& step);

// Sets one pixel; outside the image, nothing.
void put_pixel(rad::Image& image, int x, int y, std::array<std::uint8_t, 3> colour);

// A vertical false-colour bar `height` pixels high with its top-left corner at (x, y),
// ticks and values every `step` (labelled every second one when there are many) up to
// `top` ("top+" when `open_top`: brighter values show the top colour), and `unit` above.
void draw_legend(rad::Image& image, int x, int y, int height, double top, double step, const std::string& unit,
                 bool open_top);

// "target Eavg >= 500 lx, U0 >= 0.6: met" or "...: NOT met (U0 0.41 < 0.6)"; empty
// when the grid has no target.
std::string target_text(const rad::GridResult& grid, const std::string& unit);

// `unit`: "lx" or "W/m2".
rad::Image grid_picture(const rad::GridResult& grid, const std::string& unit);

}  // namespace dynrad::report
