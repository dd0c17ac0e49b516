// A small paginating document writer over cairo's PDF surface: headings, wrapped
// paragraphs, tables (a header row repeated on every page they span, a colour per cell),
// PNG pictures scaled to the text width and never split, page breaks, and a footer
// "NAME — page k of n" on every page. Blocks are laid out into a list of pages first
// and drawn at the end, when n is known. Text is DejaVu Sans through cairo's toy font
// API, measured with cairo_text_extents for wrapping and column widths.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

typedef struct _cairo cairo_t;
typedef struct _cairo_surface cairo_surface_t;

namespace dynrad::cli {

struct PdfColour {
  double r = 0, g = 0, b = 0;
};

struct PdfCell {
  PdfCell() = default;
  PdfCell(std::string words) : text(std::move(words)) {}  // NOLINT: a plain cell from text
  PdfCell(const char* words) : text(words) {}             // NOLINT
  std::string text;
  PdfColour colour;               // of the text
  std::optional<PdfColour> fill;  // of the cell's background
  bool bold = false;
};

struct PdfTable {
  std::vector<std::string> header;
  std::vector<std::vector<PdfCell>> rows;  // each as long as the header
  std::vector<bool> right_aligned;         // per column (numbers); missing: left
};

struct PdfMetadata {
  std::string title, author, subject, creator;
  std::string created;  // ISO 8601, "2024-05-01T12:00:00"
};

class PdfDocument {
 public:
  // `footer_name` opens every page's footer. Throws std::runtime_error when cairo
  // cannot start.
  explicit PdfDocument(std::string footer_name);
  ~PdfDocument();
  PdfDocument(const PdfDocument&) = delete;
  PdfDocument& operator=(const PdfDocument&) = delete;

  // Level 0: the document's title; 1: a section; 2: a subsection. A heading near the
  // bottom of a page moves to the next, so it stays with what follows it.
  void heading(const std::string& text, int level = 1);
  // Wrapped to the text width; '\n' starts a new line.
  void paragraph(const std::string& text, double size = 10, PdfColour colour = {}, bool bold = false);
  void table(const PdfTable& table);
  // A PNG at the text width (less when it would be more than `max_height` points high,
  // or higher than a page), with `caption` under it, on the next page when the rest of
  // this one is too short. False (and nothing drawn) when the file cannot be read.
  bool picture(const std::string& png_path, const std::string& caption, double max_height = 0);
  void space(double points);
  void page_break();
  // Moves to a new page unless `height` points fit below what is there: keeps the
  // blocks that follow together.
  void keep(double height);

  double text_width() const;
  double text_height() const;  // of a page, between the margins and above the footer
  std::size_t page_count() const { return pages_.size(); }

  // Draws every page with its footer and returns the PDF's bytes. Throws
  // std::runtime_error with cairo's message when it fails. Call once.
  std::string finish(const PdfMetadata& metadata);

 private:
  using Draw = std::function<void(cairo_t*)>;
  void select_font(double size, bool bold) const;
  double advance(const std::string& text, double size, bool bold) const;
  std::vector<std::string> wrap(const std::string& text, double width, double size, bool bold) const;
  // Moves to a new page unless `height` points fit below the cursor.
  void need(double height);
  void new_page();
  void draw(Draw draw) { pages_.back().push_back(std::move(draw)); }

  std::string footer_name_;
  std::string bytes_;
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cairo_ = nullptr;  // measures while laying out, draws in finish()
  std::vector<std::vector<Draw>> pages_;
  double y_ = 0;  // the cursor, points from the page's top
};

}  // namespace dynrad::cli
