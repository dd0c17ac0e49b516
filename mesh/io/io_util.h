// Helpers shared by the file readers (mesh/ and the readers in layers above it).
#pragma once

#include <string>

namespace dynrad::detail {

// Reads a whole file; throws InputError if it is missing, a directory or unreadable.
std::string read_file(const std::string& path);
// A text file's bytes as UTF-8, by its byte-order mark: a UTF-8 mark is dropped, UTF-16
// with a mark (little- or big-endian, as Windows tools save "Unicode" text) is decoded;
// without a mark the bytes are returned as they are. Line breaks are kept, so line
// numbers stay those of the file. Throws InputError naming `path` (and the line) for
// UTF-16 that ends in the middle of a character or holds a lone surrogate: damaged.
std::string decode_text(const std::string& bytes, const std::string& path);
// read_file, then decode_text.
std::string read_text_file(const std::string& path);
// Lower-case extension with the dot (".obj"), or "" when there is none.
std::string extension_of(const std::string& path);
// sRGB-encoded channel in [0, 1] to linear.
double srgb_to_linear(double c);

}  // namespace dynrad::detail
