#include "plugin/report/view_output.h"

#include "mesh/io/atomic_file.h"
#include "plugin/report/grid_picture.h"
#include "plugin/report/png.h"
#include "plugin/report/text.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>

namespace dynrad::report {

rad::Image luminance_picture(const rad::RenderedView& rendered, const rad::View& view, bool photometric, double* top_out) {
  std::vector<double> lit;
  for (std::size_t p = 0; p < rendered.kind.size(); ++p)
    if (rendered.kind[p] == rad::PixelKind::front && !rendered.emitter[p]) lit.push_back(rendered.luminance(p));
  double peak = 0;
  if (!lit.empty()) {
    const std::size_t k = std::min(lit.size() - 1, static_cast<std::size_t>(0.98 * static_cast<double>(lit.size())));
    std::nth_element(lit.begin(), lit.begin() + static_cast<long>(k), lit.end());
    peak = lit[k];
  }
  double top = 1, step = 0.2;
  legend_scale(peak, top, step);
  if (top_out) *top_out = top;

  const int header = 56, margin = 12, legend_w = 130;
  rad::Image image;
  image.width = margin + rendered.width + margin + legend_w;
  image.height = header + std::max(rendered.height, 240) + margin;
  image.rgb.assign(static_cast<std::size_t>(image.width) * image.height * 3, 255);
  for (int y = 0; y < rendered.height; ++y)
    for (int x = 0; x < rendered.width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * rendered.width + x;
      std::array<std::uint8_t, 3> c{0, 0, 0};
      if (rendered.kind[p] == rad::PixelKind::front) c = false_colour(rendered.luminance(p) / top);
      else if (rendered.kind[p] == rad::PixelKind::back) c = {70, 70, 70};
      put_pixel(image, margin + x, header + y, c);
    }
  draw_legend(image, margin + rendered.width + margin, header + 10, std::max(rendered.height, 240) - 20, top, step,
              photometric ? "cd/m\xc2\xb2" : "W/(m\xc2\xb2 sr)", true);
  const TextRenderer text(13), title(16);
  title.draw(image, margin, 22, fmt::format("{}: luminance", view.name), {0, 0, 0});
  text.draw(image, margin, 42, view.description, {60, 60, 60});
  return image;
}

void check_view_outputs(const std::string& prefix, const std::vector<rad::View>& declared, bool automatic,
                        const std::string& html) {
  for (const rad::View& v : declared) {
    check_output_writable(prefix + "_view_" + v.name + ".png");
    check_output_writable(prefix + "_view_" + v.name + "_luminance.png");
  }
  if (automatic) check_output_writable(prefix + "_view_plan_storey1.png");
  if (!html.empty()) check_output_writable(html);
}

std::vector<ViewPictures> write_views(const std::string& prefix, const rad::LitScene& scene,
                                      const std::vector<rad::View>& views, double exposure) {
  std::vector<ViewPictures> out;
  const double white = 0.9 / exposure;
  for (const rad::View& v : views) {
    ViewPictures pictures;
    pictures.view = v;
    const rad::RenderedView rendered = rad::render_view(scene, v.camera, v.width, v.height);
    const bool plan = v.kind == rad::View::Kind::plan;
    // A plan's cut through walls in near-black, as plans are drawn; in a view, the back
    // of a face in dark red, so a flipped face stands out.
    pictures.colour = rad::colour_image(rendered, exposure, plan ? std::array<std::uint8_t, 3>{35, 35, 35}
                                                                 : std::array<std::uint8_t, 3>{90, 0, 0},
                                        plan ? std::array<std::uint8_t, 3>{255, 255, 255}
                                             : std::array<std::uint8_t, 3>{0, 0, 0});
    pictures.luminance = luminance_picture(rendered, v, scene.photometric, &pictures.luminance_top);
    std::size_t lit = 0;
    for (std::size_t p = 0; p < rendered.kind.size(); ++p)
      lit += rendered.kind[p] == rad::PixelKind::front && rendered.radiosity[p].luminance() >= 0.01 * white;
    pictures.lit_fraction = static_cast<double>(lit) / static_cast<double>(rendered.kind.size());
    pictures.colour_file = prefix + "_view_" + v.name + ".png";
    pictures.luminance_file = prefix + "_view_" + v.name + "_luminance.png";
    write_png(pictures.colour_file, pictures.colour);
    write_png(pictures.luminance_file, pictures.luminance);
    spdlog::info("view {} ({}): {}; {:.0f}% of it lit; wrote {} and {}", v.name, rad::kind_name(v.kind),
                 v.description, 100 * pictures.lit_fraction, pictures.colour_file, pictures.luminance_file);
    out.push_back(std::move(pictures));
  }
  return out;
}

nlohmann::json views_json(const std::vector<ViewPictures>& views) {
  nlohmann::json out = nlohmann::json::array();
  for (const ViewPictures& p : views) {
    const rad::Camera& c = p.view.camera;
    nlohmann::json j = {{"name", p.view.name},
                        {"kind", rad::kind_name(p.view.kind)},
                        {"description", p.view.description},
                        {"position", {c.eye[0], c.eye[1], c.eye[2]}},
                        {"look_at", {c.target[0], c.target[1], c.target[2]}},
                        {"width", p.view.width},
                        {"height", p.view.height},
                        {"lit_fraction", p.lit_fraction},
                        {"luminance_legend_top", p.luminance_top},
                        {"picture", p.colour_file},
                        {"luminance_picture", p.luminance_file}};
    if (c.orthographic) j["view_height"] = c.view_height;
    else j["fov"] = c.fov_degrees;
    out.push_back(j);
  }
  return out;
}

std::vector<Viewpoint> viewpoints(const rad::View& start, const std::vector<rad::View>& others) {
  std::vector<Viewpoint> out;
  auto add = [&](const rad::View& v) {
    if (v.camera.orthographic) return;
    for (const Viewpoint& p : out)
      if (p.name == v.name) return;
    Viewpoint p;
    p.name = v.name;
    p.eye = v.camera.eye;
    p.target = v.camera.target;
    p.up = v.camera.up;
    p.fov_degrees = v.camera.fov_degrees;
    p.aspect = v.height > 0 ? static_cast<double>(v.width) / v.height : 4.0 / 3.0;
    out.push_back(p);
  };
  add(start);
  for (const rad::View& v : others) add(v);
  return out;
}

}  // namespace dynrad::report
