// 8-bit RGB PNG (libpng): encoded in memory (for a report that embeds it) or written
// to a file atomically.
#pragma once

#include "radiosity/analysis/render.h"

#include <string>

namespace dynrad::report {

// The PNG file's bytes.
std::string encode_png(const rad::Image& image);

// Throws OutputError when the file cannot be written.
void write_png(const std::string& path, const rad::Image& image);

}  // namespace dynrad::report
