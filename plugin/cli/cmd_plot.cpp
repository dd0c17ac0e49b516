// `dynrad plot REPORT.json -o plot.svg`: the convergence of a solve, from the report
// `dynrad solve --report` writes: the unshot fraction after each shot on a log scale
// (left axis) and the energy transfers so far (right axis, linear) against the shot
// number, one polyline point per shot, with the method, shots, energy transfers and
// stop reason as the caption. Reports without `transfers_history` (older ones) get
// the unshot curve alone.
//
// The SVG is written by hand (a few elements) and atomically.
#include "mesh/io/atomic_file.h"
#include "mesh/core/error.h"
#include "plugin/cli/commands.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>

namespace dynrad::cli {
namespace {

struct PlotOptions {
  std::string report, output;
  int width = 800, height = 500;
};

struct Convergence {
  std::vector<double> unshot;  // after each shot
  std::string method = "?", stopped_by = "?";
  double transfers = -1;
  std::vector<double> transfers_history;  // after each shot; empty when the report has none
  double target = -1;  // the --converge fraction, when the report has it
};

Convergence read_report(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot be read. Check the path; reports are written by dynrad solve --report.");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(
        path, 0,
        fmt::format("is not valid JSON (at byte {}). Pass a report written by dynrad solve --report.", e.byte));
  }
  const auto history = j.is_object() ? j.find("unshot_history") : j.end();
  if (!j.is_object() || history == j.end() || !history->is_array())
    throw InputError(path, 0,
                     "has no 'unshot_history' array, so it is not a solve report. Write one with dynrad solve "
                     "MODEL -o OUT.ply --report REPORT.json.");
  Convergence c;
  for (std::size_t i = 0; i < history->size(); ++i) {
    const auto& value = (*history)[i];
    if (!value.is_number() || !std::isfinite(value.get<double>()) || value.get<double>() < 0)
      throw InputError(path, 0,
                       fmt::format("unshot_history[{}] is not a number >= 0; the report is damaged. Rerun the solve "
                                   "with --report.",
                                   i));
    c.unshot.push_back(value.get<double>());
  }
  if (c.unshot.empty())
    throw InputError(path, 0, "has an empty unshot_history (the solve made no shot), so there is nothing to plot.");
  if (j.contains("method") && j["method"].is_string()) c.method = j["method"].get<std::string>();
  if (j.contains("stopped_by") && j["stopped_by"].is_string()) c.stopped_by = j["stopped_by"].get<std::string>();
  if (j.contains("energy_transfers") && j["energy_transfers"].is_number())
    c.transfers = j["energy_transfers"].get<double>();
  if (j.contains("transfers_history") && j["transfers_history"].is_array() &&
      j["transfers_history"].size() == c.unshot.size()) {
    for (const auto& v : j["transfers_history"]) {
      if (!v.is_number() || v.get<double>() < 0)
        throw InputError(path, 0, "has a transfers_history entry that is not a number >= 0; the report is damaged.");
      c.transfers_history.push_back(v.get<double>());
    }
  }
  if (j.contains("options") && j["options"].is_object() && j["options"].contains("converge") &&
      j["options"]["converge"].is_number())
    c.target = j["options"]["converge"].get<double>();
  return c;
}

std::string escape_xml(const std::string& s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

// The unshot fraction on log10 from the decade below the smallest value to 1 (it
// starts at or below 1); shots linear from 0 to the last.
std::string render_svg(const Convergence& c, int width, int height, const std::string& title) {
  const double left = 80, right = width - (c.transfers_history.empty() ? 30.0 : 90.0), top = 50,
               bottom = height - 60.0;
  // The range holds the curve and the converge target.
  double smallest = *std::min_element(c.unshot.begin(), c.unshot.end());
  if (c.target > 0) smallest = std::min(smallest, c.target);
  smallest = std::max(smallest, 1e-12);
  const int low_decade = static_cast<int>(std::floor(std::log10(smallest)));
  const int high_decade = std::max(0, static_cast<int>(std::ceil(std::log10(std::max(c.unshot.front(), 1e-12)))));
  const int decades = std::max(1, high_decade - low_decade);
  const double shots = static_cast<double>(c.unshot.size());
  auto x_of = [&](double shot) { return left + (right - left) * shot / shots; };
  auto y_of = [&](double value) {
    const double v = std::log10(std::max(value, 1e-12));
    return bottom - (bottom - top) * (v - low_decade) / decades;
  };

  std::string svg = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n"
      "<title>{2}</title>\n<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n",
      width, height, escape_xml(title));
  // Decade grid lines and labels.
  for (int d = low_decade; d <= low_decade + decades; ++d) {
    const double y = y_of(std::pow(10.0, d));
    svg += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#ddd\"/>\n", left, y,
                       right, y);
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\">1e{}</text>\n", left - 6, y + 4, d);
  }
  // Shot ticks: about five round numbers.
  const double raw_step = std::max(1.0, shots / 5);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw_step)));
  const double step = raw_step / magnitude < 2 ? magnitude : raw_step / magnitude < 5 ? 2 * magnitude : 5 * magnitude;
  for (double s = 0; s <= shots + 1e-9; s += step)
    svg +=
        fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{:.0f}</text>\n", x_of(s), bottom + 18, s);
  svg += fmt::format(
      "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" "
      "stroke=\"black\"/>\n",
      left, top, right - left, bottom - top);
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">shot</text>\n", (left + right) / 2,
                     bottom + 40);
  svg += fmt::format(
      "<text x=\"16\" y=\"{:.1f}\" text-anchor=\"middle\" transform=\"rotate(-90 16 {:.1f})\">"
      "unshot fraction of emitted power (log)</text>\n",
      (top + bottom) / 2, (top + bottom) / 2);
  if (c.target > 0) {
    const double y = y_of(c.target);
    svg += fmt::format(
        "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#888\" "
        "stroke-dasharray=\"6 4\"><title>converge target {}</title></line>\n",
        left, y, right, y, c.target);
  }
  // The curve: point k is the state after shot k + 1.
  svg += "<polyline id=\"unshot\" fill=\"none\" stroke=\"#1f5fbf\" stroke-width=\"1.5\" points=\"";
  for (std::size_t k = 0; k < c.unshot.size(); ++k)
    svg += fmt::format("{}{:.2f},{:.2f}", k ? " " : "", x_of(static_cast<double>(k + 1)), y_of(c.unshot[k]));
  svg += "\"/>\n";
  if (!c.transfers_history.empty()) {
    // Energy transfers so far, linear from 0 to the total, on the right axis.
    const double most = std::max(1.0, c.transfers_history.back());
    auto y_transfers = [&](double t) { return bottom - (bottom - top) * t / most; };
    for (int tick = 0; tick <= 4; ++tick)
      svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" fill=\"#bf5f1f\">{:.3g}</text>\n", right + 6,
                         y_transfers(most * tick / 4) + 4, most * tick / 4);
    svg += fmt::format(
        "<text x=\"{0:.1f}\" y=\"{1:.1f}\" text-anchor=\"middle\" fill=\"#bf5f1f\" "
        "transform=\"rotate(90 {0:.1f} {1:.1f})\">energy transfers so far</text>\n",
        static_cast<double>(width) - 14, (top + bottom) / 2);
    svg += "<polyline id=\"transfers\" fill=\"none\" stroke=\"#bf5f1f\" stroke-width=\"1.5\" points=\"";
    for (std::size_t k = 0; k < c.transfers_history.size(); ++k)
      svg += fmt::format("{}{:.2f},{:.2f}", k ? " " : "", x_of(static_cast<double>(k + 1)),
                         y_transfers(c.transfers_history[k]));
    svg += "\"/>\n";
  }
  const std::string caption = fmt::format(
      "{}: {} shots, {} energy transfers, final unshot {:.3g}% ({})", c.method, c.unshot.size(),
      c.transfers >= 0 ? fmt::format("{:.0f}", c.transfers) : std::string("?"), 100 * c.unshot.back(), c.stopped_by);
  svg += fmt::format("<text x=\"{:.1f}\" y=\"30\" font-size=\"14\">{}</text>\n", left, escape_xml(caption));
  svg += "</svg>\n";
  return svg;
}

int run_plot(const PlotOptions& options) {
  const std::string ext = options.output.size() >= 4 ? options.output.substr(options.output.size() - 4) : "";
  if (ext != ".svg") throw InputError(options.output, 0, "plot writes SVG: give the output a .svg extension.");
  check_output_writable(options.output);
  const Convergence c = read_report(options.report);
  AtomicFile file(options.output, std::ios::out);
  file.stream() << render_svg(c, options.width, options.height, "dynrad convergence: " + options.report);
  file.commit();
  spdlog::info("wrote {} ({} shots, final unshot {:.3g}%)", options.output, c.unshot.size(), 100 * c.unshot.back());
  return kExitOk;
}

}  // namespace

Command add_plot_command(CLI::App& app) {
  auto options = std::make_shared<PlotOptions>();
  CLI::App* command =
      app.add_subcommand("plot", "Plot a solve's convergence (unshot fraction and transfers per shot) as SVG");
  command->add_option("report", options->report, "JSON report written by dynrad solve --report")->required();
  command->add_option("-o,--output", options->output, "SVG file to write")->required();
  command->add_option("--width", options->width, "Width in pixels")
      ->capture_default_str()
      ->check(CLI::Range(200, 8000));
  command->add_option("--height", options->height, "Height in pixels")
      ->capture_default_str()
      ->check(CLI::Range(150, 8000));
  return [options] { return run_plot(*options); };
}

}  // namespace dynrad::cli
