// FreeType rasterises each glyph to an 8-bit coverage bitmap; it is blended into the
// image with the colour.
#include "plugin/report/text.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <filesystem>
#include <stdexcept>
#include <vector>

namespace dynrad::report {

namespace {

// UTF-8 to code points (invalid bytes become '?').
std::vector<char32_t> decode(const std::string& text) {
  std::vector<char32_t> out;
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    int extra = c < 0x80 ? 0 : (c >> 5) == 6 ? 1 : (c >> 4) == 14 ? 2 : (c >> 3) == 30 ? 3 : -1;
    if (extra < 0 || i + extra >= text.size() + (extra == 0 ? 1 : 0)) {
      out.push_back('?');
      ++i;
      continue;
    }
    char32_t cp = extra == 0 ? c : c & (0x3F >> extra);
    for (int k = 1; k <= extra; ++k) cp = (cp << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
    out.push_back(cp);
    i += static_cast<std::size_t>(extra) + 1;
  }
  return out;
}

}  // namespace

struct TextRenderer::Impl {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
};

std::string TextRenderer::font_path() {
  for (const char* p : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/dejavu/DejaVuSans.ttf",
                        "/usr/share/fonts/TTF/DejaVuSans.ttf"})
    if (std::filesystem::exists(p)) return p;
  return "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
}

TextRenderer::TextRenderer(int pixel_height) : impl_(std::make_unique<Impl>()), pixel_height_(pixel_height) {
  if (FT_Init_FreeType(&impl_->library)) throw std::runtime_error("FreeType could not start");
  const std::string path = font_path();
  if (FT_New_Face(impl_->library, path.c_str(), 0, &impl_->face)) {
    FT_Done_FreeType(impl_->library);
    throw std::runtime_error("cannot read the font " + path + " (install fonts-dejavu-core: scripts/install-deps.sh)");
  }
  FT_Set_Pixel_Sizes(impl_->face, 0, static_cast<FT_UInt>(pixel_height));
}

TextRenderer::~TextRenderer() {
  if (impl_->face) FT_Done_Face(impl_->face);
  if (impl_->library) FT_Done_FreeType(impl_->library);
}

int TextRenderer::width(const std::string& text) const {
  int advance = 0;
  for (char32_t cp : decode(text))
    if (!FT_Load_Char(impl_->face, cp, FT_LOAD_DEFAULT)) advance += static_cast<int>(impl_->face->glyph->advance.x >> 6);
  return advance;
}

int TextRenderer::draw(rad::Image& image, int x, int y, const std::string& text,
                       std::array<std::uint8_t, 3> colour) const {
  int pen = x;
  for (char32_t cp : decode(text)) {
    if (FT_Load_Char(impl_->face, cp, FT_LOAD_RENDER)) continue;
    const FT_GlyphSlot g = impl_->face->glyph;
    const FT_Bitmap& bm = g->bitmap;
    for (unsigned row = 0; row < bm.rows; ++row)
      for (unsigned col = 0; col < bm.width; ++col) {
        const int px = pen + g->bitmap_left + static_cast<int>(col), py = y - g->bitmap_top + static_cast<int>(row);
        if (px < 0 || py < 0 || px >= image.width || py >= image.height) continue;
        const double a = bm.buffer[row * static_cast<unsigned>(bm.pitch) + col] / 255.0;
        std::uint8_t* dst = &image.rgb[3 * (static_cast<std::size_t>(py) * image.width + px)];
        for (int c = 0; c < 3; ++c) dst[c] = static_cast<std::uint8_t>(dst[c] * (1 - a) + colour[c] * a + 0.5);
      }
    pen += static_cast<int>(g->advance.x >> 6);
  }
  return pen - x;
}

}  // namespace dynrad::report
