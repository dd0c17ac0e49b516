// NumPy's .npy format 1.0 for a float32 matrix: numpy.load() reads it.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace dynrad::cli {

// Little-endian float32, shape (rows, columns), row-major; written atomically
// (OutputError when it cannot be).
void write_npy(const std::string& path, const std::vector<float>& values, std::size_t rows, std::size_t columns);

}  // namespace dynrad::cli
