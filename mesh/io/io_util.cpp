#include "mesh/io/io_util.h"

#include "mesh/core/error.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace dynrad::detail {

std::string read_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  auto status = fs::status(path, ec);
  if (ec || !fs::exists(status))
    throw InputError(path, 0, "file not found. Check the path (relative paths start at the current directory).");
  if (fs::is_directory(status))
    throw InputError(path, 0, "is a directory, not a model file.");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(path, 0, std::string("cannot be opened: ") + std::strerror(errno) + ". Check its permissions.");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(path, 0, "read error while loading the file.");
  return buffer.str();
}

namespace {

void append_utf8(std::string& out, std::uint32_t code_point) {
  if (code_point < 0x80) {
    out.push_back(static_cast<char>(code_point));
  } else if (code_point < 0x800) {
    out.push_back(static_cast<char>(0xC0 | (code_point >> 6)));
    out.push_back(static_cast<char>(0x80 | (code_point & 0x3F)));
  } else if (code_point < 0x10000) {
    out.push_back(static_cast<char>(0xE0 | (code_point >> 12)));
    out.push_back(static_cast<char>(0x80 | ((code_point >> 6) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | (code_point & 0x3F)));
  } else {
    out.push_back(static_cast<char>(0xF0 | (code_point >> 18)));
    out.push_back(static_cast<char>(0x80 | ((code_point >> 12) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | ((code_point >> 6) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | (code_point & 0x3F)));
  }
}

std::string decode_utf16(const std::string& bytes, bool big_endian, const std::string& path) {
  if (bytes.size() % 2 != 0)
    throw InputError(path, 0,
                     "is UTF-16 text (it starts with a byte-order mark) but ends in the middle of a character: the "
                     "file is truncated or damaged.");
  auto unit = [&](std::size_t i) {
    const auto first = static_cast<unsigned char>(bytes[i]), second = static_cast<unsigned char>(bytes[i + 1]);
    return static_cast<std::uint32_t>(big_endian ? (first << 8) | second : (second << 8) | first);
  };
  std::string out;
  out.reserve(bytes.size() / 2);
  std::size_t line = 1;
  for (std::size_t i = 2; i < bytes.size(); i += 2) {  // after the mark
    std::uint32_t code_point = unit(i);
    if (code_point >= 0xD800 && code_point <= 0xDFFF) {
      const bool high = code_point <= 0xDBFF;
      const std::uint32_t low = high && i + 3 < bytes.size() ? unit(i + 2) : 0;
      if (!high || low < 0xDC00 || low > 0xDFFF)
        throw InputError(path, line,
                         "is UTF-16 text with a broken character (a lone surrogate): the file is damaged. Save it "
                         "again as UTF-8.");
      code_point = 0x10000 + ((code_point - 0xD800) << 10) + (low - 0xDC00);
      i += 2;
    }
    if (code_point == '\n') ++line;
    append_utf8(out, code_point);
  }
  return out;
}

}  // namespace

std::string decode_text(const std::string& bytes, const std::string& path) {
  auto starts_with = [&bytes](const char* mark, std::size_t size) { return bytes.compare(0, size, mark, size) == 0; };
  if (starts_with("\xEF\xBB\xBF", 3)) return bytes.substr(3);
  if (starts_with("\xFF\xFE", 2)) return decode_utf16(bytes, false, path);
  if (starts_with("\xFE\xFF", 2)) return decode_utf16(bytes, true, path);
  return bytes;
}

std::string read_text_file(const std::string& path) { return decode_text(read_file(path), path); }

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

}  // namespace dynrad::detail
