#include "plugin/cli/validate_report.h"

#include "mesh/io/atomic_file.h"
#include "mesh/io/io_util.h"
#include "plugin/report/html_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <sstream>
#include <tuple>
#include <vector>

namespace dynrad::cli {
using namespace dynrad::report;  // the report's writers (plugin/report/)

namespace {

using json = nlohmann::json;

std::string percent(double v) { return fmt::format("{:.3f}%", 100 * v); }

// Per section (5.2, 5.3, ...; a section's runs over a grey ground apart, by their title),
// in order: runs, points, worst, strict worst, all passed.
struct Section {
  std::string id, title;
  std::size_t runs = 0, points = 0;
  double worst = 0, strict = 0, goal = 0, cie = 0;
  bool passed = true;
};

// An SVG chart of a run's points: each point's error (vertical, %) against its reference
// (horizontal, on a log scale; points whose reference is 0, in a shadow, at the left
// edge), with the goal and CIE 171's tolerance as lines. Where the errors lie relative
// to the light shows what a table cannot: an error in deep shade or at the brightest
// points, one outlier or a spread.
std::string error_chart(const json& points, double goal, double cie) {
  const double width = 640, height = 220, left = 56, right = 24, top = 10, bottom = 36;
  double lo = 1e300, hi = 0, top_error = 1.25 * goal;
  for (const json& p : points) {
    const double ref = p["reference"].get<double>(), error = p["error"].get<double>();
    if (ref > 0) lo = std::min(lo, ref), hi = std::max(hi, ref);
    top_error = std::max(top_error, error);
  }
  if (!(hi > 0)) lo = 1, hi = 10;
  double decade_lo = std::floor(std::log10(lo)), decade_hi = std::ceil(std::log10(hi));
  if (decade_hi <= decade_lo) decade_hi = decade_lo + 1;
  top_error = std::min(top_error, std::max(4 * cie, 1.25 * goal));  // larger errors sit on the top edge
  const double plot_w = width - left - right, plot_h = height - top - bottom;
  auto x_of = [&](double ref) {
    if (!(ref > 0)) return left;
    return left + plot_w * (std::log10(ref) - decade_lo) / (decade_hi - decade_lo);
  };
  auto y_of = [&](double error) { return top + plot_h * (1 - std::min(error, top_error) / top_error); };
  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\" font-size=\"11\">",
      width, height);
  s += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#fafafa\" stroke=\"#999\"/>", left, top,
                   plot_w, plot_h);
  for (double d = decade_lo; d <= decade_hi + 1e-9; d += 1) {
    const double x = left + plot_w * (d - decade_lo) / (decade_hi - decade_lo);
    s += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"#ddd\"/>", x, top, top + plot_h);
    s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{:g}</text>", x, height - bottom + 14,
                     std::pow(10.0, d));
  }
  s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">reference (lx; lm for areas)</text>",
                   left + plot_w / 2, height - 4);
  for (const auto& [level, colour, name] :
       {std::tuple{goal, "#070", "goal"}, std::tuple{cie, "#888", "CIE"}}) {
    if (level > top_error) continue;
    const double y = y_of(level);
    s += fmt::format("<line x1=\"{0}\" y1=\"{2}\" x2=\"{1}\" y2=\"{2}\" stroke=\"{3}\" stroke-dasharray=\"5 3\"/>", left,
                     left + plot_w, y, colour);
    s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\" fill=\"{}\">{} {:g}%</text>", left + plot_w - 4,
                     y - 3, colour, name, 100 * level);
  }
  s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">0%</text>", left - 4, top + plot_h);
  s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{:.2g}%</text>", left - 4, top + 10,
                   100 * top_error);
  s += fmt::format("<text x=\"12\" y=\"{0}\" transform=\"rotate(-90 12 {0})\" text-anchor=\"middle\">error</text>",
                   top + plot_h / 2);
  for (const json& p : points) {
    const double error = p["error"].get<double>();
    s += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"2.2\" fill=\"{}\"/>", x_of(p["reference"].get<double>()),
                     y_of(error), error > goal ? "#c00" : "#246");
  }
  return s + "</svg>";
}

}  // namespace

void write_validation_report(const std::string& path, const json& runs, const std::string& quality) {
  std::vector<Section> sections;
  for (const json& r : runs) {
    if (sections.empty() || sections.back().id != r["case"].get<std::string>() ||
        sections.back().title != r["title"].get<std::string>()) {
      sections.push_back({});
      sections.back().id = r["case"].get<std::string>();
      sections.back().title = r["title"].get<std::string>();
      sections.back().goal = r["goal"].get<double>();
      sections.back().cie = r["cie_tolerance"].get<double>();
    }
    Section& s = sections.back();
    ++s.runs;
    s.points += r["points"].size();
    s.worst = std::max(s.worst, r["worst"].get<double>());
    s.strict = std::max(s.strict, r["strict_worst"].get<double>());
    s.passed = s.passed && r["passed"].get<bool>();
  }
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>dynrad: CIE 171:2006 validation</title>\n"
       "<style>body{font-family:sans-serif;max-width:72em;margin:2em auto;line-height:1.4}"
       "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:0.2em 0.5em;text-align:left}"
       ".over{color:#b00;font-weight:bold}.ok{color:#070}img{max-width:100%}</style></head><body>\n";
  h << "<h1>CIE 171:2006 analytical test cases</h1>\n";
  h << "<p>dynrad " << html_escape(DYNRAD_VERSION) << ", " << date << ", every solve at " << html_escape(quality)
    << ". Each case was written as a scene, lit by <code>dynrad solve</code> and read back by "
       "<code>dynrad probe</code> (the lit mesh) and the solve's work-plane grids; the references share no code with "
       "the solver.</p>\n";
  h << "<p>A point's error is |value &minus; reference| / reference, or where the reference is below 1% of the case's "
       "largest (shade), / that 1%; \"strict\" is against the reference alone. Goals (this project's): 1% for "
       "5.2&ndash;5.8, 2% for 5.9&ndash;5.14; CIE 171's tolerance: 5%. Each run's chart shows every point's error "
       "against its reference (a log scale; points in a shadow, of reference 0, at the left edge), the goal and CIE's "
       "tolerance dashed; points over the goal are red. A run with a work plane shows its false-colour plan too.</p>\n";
  h << "<h2>Summary</h2>\n<table><tr><th>case</th><th>what</th><th>runs</th><th>points</th><th>worst</th>"
       "<th>strict worst</th><th>goal</th><th>CIE</th><th></th></tr>\n";
  for (const Section& s : sections)
    h << "<tr><td>" << html_escape(s.id) << "</td><td>" << html_escape(s.title) << "</td><td>" << s.runs << "</td><td>"
      << s.points << "</td><td>" << percent(s.worst) << "</td><td>" << percent(s.strict) << "</td><td>"
      << percent(s.goal) << "</td><td>" << percent(s.cie) << "</td><td class=\"" << (s.passed ? "ok\">within" : "over\">over")
      << "</td></tr>\n";
  h << "</table>\n<h2>Runs</h2>\n";
  std::string section;
  for (const json& r : runs) {
    const std::string id = r["case"].get<std::string>();
    if (id + " " + r["title"].get<std::string>() != section) {
      section = id + " " + r["title"].get<std::string>();
      h << "<h3>" << html_escape(id + " " + r["title"].get<std::string>()) << "</h3>\n<p>"
        << html_escape(r["choices"].get<std::string>()) << "</p>\n";
    }
    h << "<h4>" << html_escape(r["variant"].get<std::string>().empty() ? id : r["variant"].get<std::string>())
      << "</h4>\n<table>";
    if (!r["failure"].get<std::string>().empty()) {
      h << "<tr><th>failed</th><td class=\"over\">" << html_escape(r["failure"].get<std::string>()) << "</td></tr>";
    } else {
      h << "<tr><th>points</th><td>" << r["points"].size() << "</td></tr><tr><th>worst</th><td class=\""
        << (r["passed"].get<bool>() ? "ok" : "over") << "\">" << percent(r["worst"].get<double>()) << " at "
        << html_escape(r["worst_at"].get<std::string>()) << "</td></tr><tr><th>mean</th><td>"
        << percent(r["mean"].get<double>()) << "</td></tr><tr><th>strict worst</th><td>"
        << percent(r["strict_worst"].get<double>()) << "</td></tr><tr><th>solve and probe</th><td>"
        << fmt::format("{:.1f} s", r["seconds"].get<double>()) << "</td></tr>";
    }
    h << "</table>\n";
    if (r["failure"].get<std::string>().empty() && !r["points"].empty())
      h << "<p>" << error_chart(r["points"], r["goal"].get<double>(), r["cie_tolerance"].get<double>()) << "</p>\n";
    if (r["picture"].is_string())
      h << "<img alt=\"" << html_escape(id + " work plane") << "\" src=\"data:image/png;base64,"
        << base64(detail::read_file(r["picture"].get<std::string>())) << "\">\n";
  }
  h << "</body></html>\n";
  AtomicFile file(path, std::ios::out);
  file.stream() << h.str();
  file.commit();
}

}  // namespace dynrad::cli
