#include "plugin/report/grid_picture.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace dynrad::report {

const std::array<std::array<double, 3>, 6>& false_colour_stops() {
  static const std::array<std::array<double, 3>, 6> stops{{{0.05, 0.05, 0.45},
                                                           {0.0, 0.35, 1.0},
                                                           {0.0, 0.85, 0.9},
                                                           {0.2, 0.8, 0.2},
                                                           {1.0, 0.9, 0.0},
                                                           {0.9, 0.1, 0.1}}};
  return stops;
}

std::array<std::uint8_t, 3> false_colour(double t) {
  const auto& stops = false_colour_stops();
  t = std::clamp(t, 0.0, 1.0) * 5;
  const int k = std::min(4, static_cast<int>(t));
  const double f = t - k;
  std::array<std::uint8_t, 3> out{};
  for (int c = 0; c < 3; ++c)
    out[c] = static_cast<std::uint8_t>(255 * (stops[k][c] * (1 - f) + stops[k + 1][c] * f) + 0.5);
  return out;
}

void legend_scale(double peak, double& top, double& step) {
  if (!(peak > 0)) {
    top = 1;
    step = 0.2;
    return;
  }
  const double power = std::pow(10.0, std::floor(std::log10(peak)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * power >= peak * (1 - 1e-12)) {
      top = m * power;
      break;
    }
  step = top / (top / power == 2.5 ? 5 : top / power == 1 || top / power == 10 ? 10 : top / power == 2 ? 8 : 5);
}

void put_pixel(rad::Image& image, int x, int y, std::array<std::uint8_t, 3> colour) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
  std::uint8_t* d = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
  d[0] = colour[0];
  d[1] = colour[1];
  d[2] = colour[2];
}

void draw_legend(rad::Image& image, int x, int y, int height, double top, double step, const std::string& unit,
                 bool open_top) {
  const TextRenderer text(13), title(17);
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < 18; ++col)
      put_pixel(image, x + col, y + row, false_colour(1.0 - static_cast<double>(row) / (height - 1)));
  const int steps = static_cast<int>(std::lround(top / step));
  for (int k = 0; k <= steps; ++k) {
    const int tick = y + static_cast<int>(std::lround((1.0 - static_cast<double>(k) / steps) * (height - 1)));
    for (int col = 18; col < 24; ++col) put_pixel(image, x + col, tick, {30, 30, 30});
    if (k % 2 == 0 || steps <= 6)
      text.draw(image, x + 28, tick + 5, fmt::format("{:g}{}", k * step, open_top && k == steps ? "+" : ""),
                {20, 20, 20});
  }
  title.draw(image, x, y - 14, unit, {20, 20, 20});
}

rad::Image grid_picture(const rad::GridResult& grid, const std::string& unit) {
  const rad::GridCells& cells = grid.cells;
  const long nx = std::max(1L, cells.nx), ny = std::max(1L, cells.ny);
  const int ppc = std::clamp(static_cast<int>(640 / std::max(nx, ny)), 4, 64);
  const int map_w = static_cast<int>(nx) * ppc, map_h = static_cast<int>(ny) * ppc;
  const int header = 118, margin = 16, legend_w = 150;
  rad::Image image;
  image.width = margin + map_w + margin + legend_w;
  image.height = header + std::max(map_h, 300) + margin;
  image.rgb.assign(static_cast<std::size_t>(image.width) * image.height * 3, 255);

  // Values by cell; -1: no point (outside the polygon), -2: masked (inside a solid).
  std::vector<double> value(static_cast<std::size_t>(nx * ny), -1.0);
  for (const rad::GridPointResult& p : grid.points)
    value[static_cast<std::size_t>(p.cell[1] * nx + p.cell[0])] = p.masked ? -2.0 : p.illuminance;
  auto at = [&](long i, long j) { return value[static_cast<std::size_t>(j * nx + i)]; };
  double top = 1, step = 0.2;
  legend_scale(grid.e_max, top, step);

  // Each pixel: bilinear between the neighbouring cell centres that have values.
  std::vector<double> pixel(static_cast<std::size_t>(map_w) * map_h, -1.0);
  for (int py = 0; py < map_h; ++py)
    for (int px = 0; px < map_w; ++px) {
      const double fx = (px + 0.5) / ppc - 0.5, fy = (map_h - py - 0.5) / ppc - 0.5;  // plane y grows upwards
      const long ci = std::clamp(static_cast<long>(std::floor(fx + 0.5)), 0L, nx - 1);
      const long cj = std::clamp(static_cast<long>(std::floor(fy + 0.5)), 0L, ny - 1);
      const double own = at(ci, cj);
      if (own < 0) {
        pixel[static_cast<std::size_t>(py) * map_w + px] = own;
        continue;
      }
      const long i0 = static_cast<long>(std::floor(fx)), j0 = static_cast<long>(std::floor(fy));
      double sum = 0, weight = 0;
      for (long dj = 0; dj < 2; ++dj)
        for (long di = 0; di < 2; ++di) {
          const long i = i0 + di, j = j0 + dj;
          if (i < 0 || j < 0 || i >= nx || j >= ny || at(i, j) < 0) continue;
          const double w = (di ? fx - i0 : 1 - (fx - i0)) * (dj ? fy - j0 : 1 - (fy - j0));
          sum += w * at(i, j);
          weight += w;
        }
      pixel[static_cast<std::size_t>(py) * map_w + px] = weight > 0 ? sum / weight : own;
    }
  auto put = [&](int x, int y, std::array<std::uint8_t, 3> c) { put_pixel(image, x, y, c); };
  for (int py = 0; py < map_h; ++py)
    for (int px = 0; px < map_w; ++px) {
      const double v = pixel[static_cast<std::size_t>(py) * map_w + px];
      std::array<std::uint8_t, 3> c{255, 255, 255};
      if (v == -2.0) c = ((px + py) / 4) % 2 ? std::array<std::uint8_t, 3>{150, 150, 150}
                                              : std::array<std::uint8_t, 3>{200, 200, 200};  // masked: hatched
      else if (v >= 0) c = false_colour(v / top);
      // Iso-lines: where the level changes between this pixel and the next one.
      if (v >= 0) {
        const long level = static_cast<long>(std::floor(v / step));
        for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
          if (px + dx >= map_w || py + dy >= map_h) continue;
          const double w = pixel[static_cast<std::size_t>(py + dy) * map_w + px + dx];
          if (w >= 0 && static_cast<long>(std::floor(w / step)) != level) c = {30, 30, 30};
        }
      }
      put(margin + px, header + py, c);
    }

  draw_legend(image, margin + map_w + margin, header + 10, std::max(map_h, 300) - 20, top, step, unit, false);
  const TextRenderer text(13), title(17);

  // Figures.
  const double h = grid.spec.height;
  title.draw(image, margin, 24,
             fmt::format("{}: {} points at {:.3g} spacing, height {:.3g}", grid.spec.name, grid.count, grid.spacing, h),
             {0, 0, 0});
  text.draw(image, margin, 46,
            fmt::format("Eavg {:.4g} {}   Emin {:.4g}   Emax {:.4g}", grid.e_avg, unit, grid.e_min, grid.e_max),
            {0, 0, 0});
  text.draw(image, margin, 66,
            fmt::format("U0 = Emin/Eavg {:.2f}   Emin/Emax {:.2f}{}", grid.u0, grid.min_over_max,
                        grid.masked ? fmt::format("   {} points inside solids (hatched)", grid.masked) : ""),
            {0, 0, 0});
  if (grid.outside > 0)
    text.draw(image, margin + 330, 66,
              fmt::format("DF avg {:.2f}% (SC {:.2f}, ERC {:.2f}, IRC {:.2f})   min {:.2f}%", grid.df_avg,
                          grid.sky_component, grid.externally_reflected, grid.internally_reflected, grid.df_min),
              {0, 0, 0});
  const std::string target = target_text(grid, unit);
  if (!target.empty())
    text.draw(image, margin, 88, target, grid.meets_target() ? std::array<std::uint8_t, 3>{0, 110, 0}
                                                             : std::array<std::uint8_t, 3>{190, 0, 0});
  return image;
}

std::string target_text(const rad::GridResult& grid, const std::string& unit) {
  const rad::GridSpec& g = grid.spec;
  if (g.target_eavg <= 0 && g.target_u0 <= 0) return "";
  std::string wanted, missed;
  if (g.target_eavg > 0) {
    wanted = fmt::format("Eavg \u2265 {:g} {}", g.target_eavg, unit);
    if (grid.e_avg < g.target_eavg) missed = fmt::format("Eavg {:.4g} < {:g}", grid.e_avg, g.target_eavg);
  }
  if (g.target_u0 > 0) {
    wanted += fmt::format("{}U0 \u2265 {:g}", wanted.empty() ? "" : ", ", g.target_u0);
    if (grid.u0 < g.target_u0)
      missed += fmt::format("{}U0 {:.2f} < {:g}", missed.empty() ? "" : ", ", grid.u0, g.target_u0);
  }
  return "target " + wanted + (missed.empty() ? ": met" : ": NOT met (" + missed + ")");
}

}  // namespace dynrad::report
