// Writing an 8-bit RGB PNG (libpng), atomically.
#pragma once

#include "radiosity/preview.h"

#include <string>

namespace dynrad::cli {

// Throws OutputError when the file cannot be written.
void write_png(const std::string& path, const rad::Image& image);

}  // namespace dynrad::cli
