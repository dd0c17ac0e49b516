#include "plugin/cli/pdf_document.h"

#include <cairo-pdf.h>
#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace dynrad::cli {
namespace {

// Tables of at most this many rows are kept on one page.
constexpr std::size_t kKeptRows = 12;

// A4 portrait in points, and the frame the text keeps inside.
constexpr double kPageWidth = 595.276, kPageHeight = 841.89;
constexpr double kMargin = 50;
constexpr double kTop = kMargin, kBottom = kPageHeight - kMargin - 12;  // the footer sits below kBottom
constexpr double kFooterBaseline = kPageHeight - 30;
constexpr double kLineSpacing = 1.3;  // line height over font size
constexpr double kAscent = 0.95;      // baseline below a line's top, over font size (DejaVu Sans: 0.93)

// Tables.
constexpr double kTableSize = 8.5, kCellPadX = 4, kCellPadY = 2.5;
constexpr double kTableLine = kTableSize * 1.22;
const PdfColour kHeaderFill{0.88, 0.89, 0.91}, kRule{0.62, 0.64, 0.68}, kGrey{0.35, 0.35, 0.38};

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void set_colour(cairo_t* cr, const PdfColour& c) { cairo_set_source_rgb(cr, c.r, c.g, c.b); }

void font(cairo_t* cr, double size, bool bold) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

// A text line drawn with its baseline at (x, baseline).
void show(cairo_t* cr, double x, double baseline, const std::string& text, double size, bool bold,
          const PdfColour& colour) {
  font(cr, size, bold);
  set_colour(cr, colour);
  cairo_move_to(cr, x, baseline);
  cairo_show_text(cr, text.c_str());
}

// Byte length of the UTF-8 character starting at text[i].
std::size_t char_length(const std::string& text, std::size_t i) {
  const auto lead = static_cast<unsigned char>(text[i]);
  const std::size_t n = lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 1;
  return std::min(n, text.size() - i);
}

}  // namespace

PdfDocument::PdfDocument(std::string footer_name) : footer_name_(std::move(footer_name)) {
  surface_ = cairo_pdf_surface_create_for_stream(append, &bytes_, kPageWidth, kPageHeight);
  cairo_ = cairo_create(surface_);
  if (cairo_status(cairo_) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(std::string("cairo could not start a PDF: ") +
                             cairo_status_to_string(cairo_status(cairo_)));
  new_page();
}

PdfDocument::~PdfDocument() {
  cairo_destroy(cairo_);
  cairo_surface_destroy(surface_);
}

double PdfDocument::text_width() const { return kPageWidth - 2 * kMargin; }
double PdfDocument::text_height() const { return kBottom - kTop; }

void PdfDocument::select_font(double size, bool bold) const { font(cairo_, size, bold); }

double PdfDocument::advance(const std::string& text, double size, bool bold) const {
  select_font(size, bold);
  cairo_text_extents_t extents;
  cairo_text_extents(cairo_, text.c_str(), &extents);
  return extents.x_advance;
}

std::vector<std::string> PdfDocument::wrap(const std::string& text, double width, double size, bool bold) const {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find('\n', start);
    const std::string part = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
    std::string line;
    std::size_t p = 0;
    while (p < part.size()) {
      if (part[p] == ' ') {
        ++p;
        continue;
      }
      std::size_t q = part.find(' ', p);
      if (q == std::string::npos) q = part.size();
      std::string word = part.substr(p, q - p);
      p = q;
      const std::string joined = line.empty() ? word : line + " " + word;
      if (advance(joined, size, bold) <= width) {
        line = joined;
        continue;
      }
      if (!line.empty()) lines.push_back(line);
      // A word wider than the line is cut between characters, at least one per line.
      while (advance(word, size, bold) > width) {
        std::size_t cut = char_length(word, 0);
        for (std::size_t next = cut; next < word.size(); next += char_length(word, next)) {
          if (advance(word.substr(0, next), size, bold) > width) break;
          cut = next;
        }
        if (cut >= word.size()) break;
        lines.push_back(word.substr(0, cut));
        word.erase(0, cut);
      }
      line = word;
    }
    lines.push_back(line);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return lines;
}

void PdfDocument::new_page() {
  pages_.emplace_back();
  y_ = kTop;
}

void PdfDocument::need(double height) {
  if (y_ + height > kBottom && y_ > kTop) new_page();
}

void PdfDocument::keep(double height) { need(height); }

void PdfDocument::page_break() {
  if (!pages_.back().empty()) new_page();
}

void PdfDocument::space(double points) {
  if (y_ > kTop) y_ = std::min(y_ + points, kBottom);
}

void PdfDocument::heading(const std::string& text, int level) {
  const double size = level <= 0 ? 20 : level == 1 ? 14 : 11.5;
  const PdfColour colour = level <= 0 ? PdfColour{0.08, 0.17, 0.35} : PdfColour{0.1, 0.1, 0.12};
  space(level <= 1 ? 12 : 8);
  const std::vector<std::string> lines = wrap(text, text_width(), size, true);
  const double line = size * kLineSpacing;
  // Room for the heading and a few lines of what follows it.
  need(lines.size() * line + 70);
  for (const std::string& l : lines) {
    const double baseline = y_ + size * kAscent;
    draw([=](cairo_t* cr) { show(cr, kMargin, baseline, l, size, true, colour); });
    y_ += line;
  }
  if (level == 1) {
    const double y = y_ + 1;
    draw([=](cairo_t* cr) {
      set_colour(cr, kRule);
      cairo_set_line_width(cr, 0.6);
      cairo_move_to(cr, kMargin, y);
      cairo_line_to(cr, kPageWidth - kMargin, y);
      cairo_stroke(cr);
    });
  }
  y_ += level <= 1 ? 6 : 3;
}

void PdfDocument::paragraph(const std::string& text, double size, PdfColour colour, bool bold) {
  const double line = size * kLineSpacing;
  for (const std::string& l : wrap(text, text_width(), size, bold)) {
    need(line);
    const double baseline = y_ + size * kAscent;
    if (!l.empty()) draw([=](cairo_t* cr) { show(cr, kMargin, baseline, l, size, bold, colour); });
    y_ += line;
  }
  y_ += size * 0.45;
}

void PdfDocument::table(const PdfTable& table) {
  const std::size_t columns = table.header.size();
  if (columns == 0) return;
  const double width = text_width();
  // Each column's natural width (its longest text on one line), the same without the
  // header's (headers wrap first), and its least (its longest word, within reason).
  std::vector<double> natural(columns, 0), body(columns, 0), least(columns, 0);
  auto measure = [&](std::size_t c, const std::string& text, bool bold, bool header) {
    const double whole = advance(text, kTableSize, bold) + 2 * kCellPadX;
    natural[c] = std::max(natural[c], whole);
    if (!header) body[c] = std::max(body[c], whole);
    std::size_t p = 0;
    while (p <= text.size()) {
      std::size_t q = text.find_first_of(" \n", p);
      if (q == std::string::npos) q = text.size();
      least[c] =
          std::max(least[c], std::min(advance(text.substr(p, q - p), kTableSize, bold) + 2 * kCellPadX, 0.3 * width));
      p = q + 1;
    }
  };
  for (std::size_t c = 0; c < columns; ++c) measure(c, table.header[c], true, true);
  for (const auto& row : table.rows)
    for (std::size_t c = 0; c < columns && c < row.size(); ++c) measure(c, row[c].text, row[c].bold, false);
  for (std::size_t c = 0; c < columns; ++c) body[c] = std::max(body[c], least[c]);

  // When the table is too wide, headers wrap first (the spare width widens the columns
  // whose headers want it most); when that is not enough, the widest columns give way:
  // each is capped at one common width (found by bisection), never below its least.
  auto sum = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s;
  };
  std::vector<double> widths = natural;
  const double natural_sum = sum(natural), body_sum = sum(body), least_sum = sum(least);
  if (natural_sum <= width) {
    // as they are
  } else if (body_sum <= width) {
    for (std::size_t c = 0; c < columns; ++c)
      widths[c] = body[c] + (width - body_sum) * (natural[c] - body[c]) / (natural_sum - body_sum);
  } else if (least_sum >= width) {
    for (std::size_t c = 0; c < columns; ++c) widths[c] = least[c] * width / least_sum;
  } else {
    auto capped = [&](double cap, std::size_t c) { return std::max(least[c], std::min(body[c], cap)); };
    double low = 0, high = *std::max_element(body.begin(), body.end());
    for (int i = 0; i < 60; ++i) {
      const double cap = (low + high) / 2;
      double total = 0;
      for (std::size_t c = 0; c < columns; ++c) total += capped(cap, c);
      (total > width ? high : low) = cap;
    }
    for (std::size_t c = 0; c < columns; ++c) widths[c] = capped(low, c);
  }

  struct Laid {
    std::vector<std::vector<std::string>> cells;
    double height = 0;
  };
  auto lay = [&](const std::vector<PdfCell>& row) {
    Laid laid;
    std::size_t most = 1;
    for (std::size_t c = 0; c < columns; ++c) {
      const PdfCell cell = c < row.size() ? row[c] : PdfCell();
      laid.cells.push_back(wrap(cell.text, widths[c] - 2 * kCellPadX, kTableSize, cell.bold));
      most = std::max(most, laid.cells.back().size());
    }
    laid.height = most * kTableLine + 2 * kCellPadY;
    return laid;
  };
  std::vector<PdfCell> header_row;
  for (const std::string& h : table.header) {
    PdfCell cell(h);
    cell.bold = true;
    cell.fill = kHeaderFill;
    header_row.push_back(cell);
  }
  auto place = [&](const std::vector<PdfCell>& row, const Laid& laid) {
    double x = kMargin;
    const double top = y_;
    for (std::size_t c = 0; c < columns; ++c) {
      const PdfCell cell = c < row.size() ? row[c] : PdfCell();
      const bool right = c < table.right_aligned.size() && table.right_aligned[c] && !laid.cells[c].empty();
      std::vector<double> offsets;
      for (const std::string& line : laid.cells[c])
        offsets.push_back(right ? widths[c] - kCellPadX - advance(line, kTableSize, cell.bold) : kCellPadX);
      const double w = widths[c], height = laid.height;
      draw([=, lines = laid.cells[c]](cairo_t* cr) {
        if (cell.fill) {
          set_colour(cr, *cell.fill);
          cairo_rectangle(cr, x, top, w, height);
          cairo_fill(cr);
        }
        set_colour(cr, kRule);
        cairo_set_line_width(cr, 0.5);
        cairo_rectangle(cr, x, top, w, height);
        cairo_stroke(cr);
        for (std::size_t i = 0; i < lines.size(); ++i)
          show(cr, x + offsets[i], top + kCellPadY + i * kTableLine + kTableSize * kAscent, lines[i], kTableSize,
               cell.bold, cell.colour);
      });
      x += w;
    }
    y_ += laid.height;
  };

  const Laid header = lay(header_row);
  std::vector<Laid> rows;
  for (const auto& row : table.rows) rows.push_back(lay(row));
  // A short table that fits on a page is not split: it starts on the next one.
  double whole = header.height;
  for (const Laid& row : rows) whole += row.height;
  need(rows.size() <= kKeptRows && whole <= text_height() ? whole
                                                          : header.height + (rows.empty() ? 0 : rows.front().height));
  place(header_row, header);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (y_ + rows[r].height > kBottom) {
      new_page();
      place(header_row, header);
    }
    place(table.rows[r], rows[r]);
  }
  y_ += 10;
}

bool PdfDocument::picture(const std::string& png_path, const std::string& caption, double max_height) {
  std::shared_ptr<cairo_surface_t> image(cairo_image_surface_create_from_png(png_path.c_str()), cairo_surface_destroy);
  const int w = cairo_image_surface_get_width(image.get()), h = cairo_image_surface_get_height(image.get());
  if (cairo_surface_status(image.get()) != CAIRO_STATUS_SUCCESS || w <= 0 || h <= 0) return false;
  constexpr double kCaptionSize = 8.5;
  const std::vector<std::string> caption_lines =
      caption.empty() ? std::vector<std::string>{} : wrap(caption, text_width(), kCaptionSize, false);
  const double caption_height = caption_lines.size() * kCaptionSize * kLineSpacing;
  double tallest = text_height() - caption_height - 6;
  if (max_height > 0) tallest = std::min(tallest, max_height);
  double scale = std::min(text_width() / w, tallest / h);
  // Rather than leave a large gap, a picture shrinks a little into the rest of the page.
  const double rest = kBottom - y_ - 4 - caption_height;
  if (h * scale > rest && rest >= 0.75 * h * scale) scale = rest / h;
  const double drawn_w = w * scale, drawn_h = h * scale;
  need(drawn_h + 4 + caption_height);
  const double x = kMargin + (text_width() - drawn_w) / 2, top = y_;
  draw([=](cairo_t* cr) {
    cairo_save(cr);
    cairo_translate(cr, x, top);
    cairo_scale(cr, scale, scale);
    cairo_set_source_surface(cr, image.get(), 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_GOOD);
    cairo_paint(cr);
    cairo_restore(cr);
    set_colour(cr, kRule);
    cairo_set_line_width(cr, 0.5);
    cairo_rectangle(cr, x, top, drawn_w, drawn_h);
    cairo_stroke(cr);
  });
  y_ += drawn_h + 4;
  for (const std::string& line : caption_lines) {
    const double baseline = y_ + kCaptionSize * kAscent;
    const double left = kMargin + (text_width() - advance(line, kCaptionSize, false)) / 2;
    draw([=](cairo_t* cr) { show(cr, left, baseline, line, kCaptionSize, false, kGrey); });
    y_ += kCaptionSize * kLineSpacing;
  }
  y_ += 10;
  return true;
}

std::string PdfDocument::finish(const PdfMetadata& metadata) {
  const std::pair<cairo_pdf_metadata_t, const std::string*> fields[] = {
      {CAIRO_PDF_METADATA_TITLE, &metadata.title},
      {CAIRO_PDF_METADATA_AUTHOR, &metadata.author},
      {CAIRO_PDF_METADATA_SUBJECT, &metadata.subject},
      {CAIRO_PDF_METADATA_CREATOR, &metadata.creator},
      {CAIRO_PDF_METADATA_CREATE_DATE, &metadata.created}};
  for (const auto& [field, value] : fields)
    if (!value->empty()) cairo_pdf_surface_set_metadata(surface_, field, value->c_str());
  const std::size_t n = pages_.size();
  for (std::size_t k = 0; k < n; ++k) {
    for (const Draw& d : pages_[k]) d(cairo_);
    const std::string footer = fmt::format("{} — page {} of {}", footer_name_, k + 1, n);
    font(cairo_, 8, false);
    cairo_text_extents_t extents;
    cairo_text_extents(cairo_, footer.c_str(), &extents);
    set_colour(cairo_, kRule);
    cairo_set_line_width(cairo_, 0.5);
    cairo_move_to(cairo_, kMargin, kFooterBaseline - 12);
    cairo_line_to(cairo_, kPageWidth - kMargin, kFooterBaseline - 12);
    cairo_stroke(cairo_);
    show(cairo_, (kPageWidth - extents.x_advance) / 2, kFooterBaseline, footer, 8, false, kGrey);
    cairo_show_page(cairo_);
  }
  cairo_surface_finish(surface_);
  cairo_status_t status = cairo_status(cairo_);
  if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_status(surface_);
  if (status != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(std::string("cairo failed drawing the PDF: ") + cairo_status_to_string(status));
  return bytes_;
}

}  // namespace dynrad::cli
