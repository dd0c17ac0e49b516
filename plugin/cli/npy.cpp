// .npy writing (see npy.h).
#include "plugin/cli/npy.h"

#include "mesh/io/atomic_file.h"

#include <fmt/format.h>

#include <cstdint>
#include <ostream>

namespace dynrad::cli {

void write_npy(const std::string& path, const std::vector<float>& values, std::size_t rows, std::size_t columns) {
  AtomicFile file(path);
  std::string header = fmt::format("{{'descr': '<f4', 'fortran_order': False, 'shape': ({}, {}), }}", rows, columns);
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';  // the data starts 64-byte aligned
  header += '\n';
  std::ostream& out = file.stream();
  out.write("\x93NUMPY\x01\x00", 8);
  const auto length = static_cast<std::uint16_t>(header.size());
  const char size[2] = {static_cast<char>(length & 0xff), static_cast<char>(length >> 8)};
  out.write(size, 2);
  out << header;
  out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(float)));
  file.commit();
}

}  // namespace dynrad::cli
