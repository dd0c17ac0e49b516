#include "plugin/cli/validate_report.h"

#include "mesh/atomic_file.h"
#include "mesh/io_util.h"
#include "plugin/cli/html_report.h"

#include <fmt/format.h>

#include <chrono>
#include <ctime>
#include <map>
#include <sstream>
#include <vector>

namespace dynrad::cli {

namespace {

using json = nlohmann::json;

std::string percent(double v) { return fmt::format("{:.3f}%", 100 * v); }

// Per section (5.2, 5.3, ...), in order: runs, points, worst, strict worst, all passed.
struct Section {
  std::string id, title;
  std::size_t runs = 0, points = 0;
  double worst = 0, strict = 0, goal = 0, cie = 0;
  bool passed = true;
};

}  // namespace

void write_validation_report(const std::string& path, const json& runs, const std::string& quality) {
  std::vector<Section> sections;
  for (const json& r : runs) {
    if (sections.empty() || sections.back().id != r["case"].get<std::string>()) {
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
       "5.2&ndash;5.8, 2% for 5.9&ndash;5.14; CIE 171's tolerance: 5%.</p>\n";
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
    if (id != section) {
      section = id;
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
