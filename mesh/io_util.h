// Helpers shared by the readers (internal to mesh/).
#pragma once

#include <string>

namespace dynrad::detail {

// Reads a whole file; throws InputError if it is missing, a directory or unreadable.
std::string read_file(const std::string& path);
// Lower-case extension with the dot (".obj"), or "" when there is none.
std::string extension_of(const std::string& path);
// sRGB-encoded channel in [0, 1] to linear.
double srgb_to_linear(double c);

}  // namespace dynrad::detail
