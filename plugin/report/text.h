// Text drawn into an RGB image with FreeType and the DejaVu Sans font (Debian's
// fonts-dejavu-core), for the figures and legends of report pictures.
#pragma once

#include "radiosity/analysis/render.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>

namespace dynrad::report {

class TextRenderer {
 public:
  // Loads the font; throws std::runtime_error naming the file when it cannot.
  explicit TextRenderer(int pixel_height);
  ~TextRenderer();
  TextRenderer(const TextRenderer&) = delete;
  TextRenderer& operator=(const TextRenderer&) = delete;

  // Draws `text` (UTF-8; ASCII and Latin-1 letters) with its baseline at y, starting at
  // x; returns the advance in pixels.
  int draw(rad::Image& image, int x, int y, const std::string& text, std::array<std::uint8_t, 3> colour) const;
  int width(const std::string& text) const;
  int height() const { return pixel_height_; }

  // The font file used: the first of DejaVu Sans's usual paths that exists.
  static std::string font_path();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int pixel_height_;
};

}  // namespace dynrad::report
