// PLY: the header parsed and rewritten for OpenMesh, the body walked before it reads.
#include "mesh/io/openmesh_checks.h"

#include "mesh/core/error.h"
#include "mesh/io/io_util.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <map>
#include <set>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>
#include <string_view>

namespace dynrad::detail {

namespace {

// Header keywords after the first line ("ply"). Blender, MeshLab and assimp skip lines
// with any other keyword, so dynrad does too, with a warning (or refuses them when
// reading strictly).
bool is_ply_keyword(const std::string& key) {
  return key == "format" || key == "element" || key == "property" || key == "end_header" || key == "comment" ||
         key == "obj_info";
}

int ply_type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

}  // namespace

PlyHeader parse_ply_header(const std::string& path, const std::string& text, bool strict) {
  PlyHeader header;
  std::istringstream in(text);
  bool ended = false;
  for (std::string line; std::getline(in, line);) {
    ++header.lines;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    auto bad = [&](const std::string& what) {
      throw InputError(path, header.lines, "PLY header: " + what + " The file is damaged or not really PLY.");
    };
    if (header.lines == 1) {
      if (key != "ply") bad("the first line must be 'ply'.");
    } else if (key == "end_header") {
      header.body = in.tellg() < 0 ? text.size() : static_cast<std::size_t>(in.tellg());
      ended = true;
      break;
    } else if (key == "format") {
      std::string version;
      words >> header.format >> version;
      if (header.format != "ascii" && header.format != "binary_little_endian" && header.format != "binary_big_endian")
        bad("unknown format '" + header.format + "' (ascii, binary_little_endian or binary_big_endian).");
      if (version != "1.0") bad("unknown version '" + version + "' (1.0).");
    } else if (key == "element") {
      PlyElement e;
      std::string count;
      words >> e.name >> count;
      if (e.name.empty() || !parse_count(count, e.count))
        bad("'" + line + "' must be 'element NAME COUNT' with a whole number as the count.");
      header.elements.push_back(e);
    } else if (key == "property") {
      if (header.elements.empty()) bad("a property comes before any element.");
      std::string type, a, b;
      words >> type >> a;
      PlyProperty p;
      if (type == "list") {
        words >> b >> p.name;
        p.count_size = ply_type_size(a);
        p.size = ply_type_size(b);
        if (p.count_size == 0 || p.size == 0 || p.name.empty()) bad("'" + line + "' is not a valid list property.");
      } else {
        p.name = a;
        p.size = ply_type_size(type);
        p.floating = type.rfind("float", 0) == 0 || type == "double";
        if (p.size == 0 || p.name.empty()) bad("'" + line + "' has an unknown type or no name.");
      }
      header.elements.back().properties.push_back(p);
    } else if (!key.empty() && !is_ply_keyword(key)) {
      if (strict) bad("unknown keyword '" + key + "'.");
      // Text is skipped; control characters in a header are damage (binary data where
      // the header should be, a header cut short).
      for (const char c : line)
        if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == '\x7F')
          bad("unknown keyword in a line that is not text.");
      header.warnings.push_back(path + ":" + std::to_string(header.lines) + ": PLY header line '" +
                                (line.size() > 60 ? line.substr(0, 57) + "..." : line) +
                                "' has an unknown keyword (known: format, element, property, comment, obj_info, "
                                "end_header); skipped.");
      continue;
    }
    // OpenMesh reads the header word by word: a word too many would be read as the
    // next keyword. (Comments, obj_info and skipped lines reach it as comments,
    // header_for_openmesh.)
    std::string extra;
    if (key != "comment" && key != "obj_info" && words >> extra)
      bad("unexpected '" + extra + "' at the end of the line.");
  }
  if (!ended) throw InputError(path, 0, "PLY header has no end_header line: the file is truncated or damaged.");
  if (header.format.empty()) throw InputError(path, 0, "PLY header has no format line.");
  return header;
}

std::string header_for_openmesh(const std::string& text, const PlyHeader& header) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (lines.size() < header.lines && start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  std::string format, comments, structure;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::string key;
    std::istringstream(lines[i]) >> key;
    if (key == "format" && format.empty())
      format = lines[i] + "\n";
    else if (key == "element" || key == "property" || key == "end_header" || key == "format")
      structure += lines[i] + "\n";
    else if (key.empty() || key == "comment")
      comments += lines[i] + "\n";
    else  // obj_info, or a line skipped with a warning
      comments += "comment " + lines[i] + "\n";
  }
  return (lines.empty() ? std::string() : lines.front() + "\n") + format + comments + structure;
}

void check_ply_body(const std::string& path, const std::string& text, const PlyHeader& header) {
  auto is_colour = [](const std::string& name) {
    return name == "red" || name == "green" || name == "blue" || name == "diffuse_red" || name == "diffuse_green" ||
           name == "diffuse_blue";
  };
  if (header.body > text.size()) return;
  auto check_colour = [&](const PlyElement& e, const PlyProperty& p, std::uint64_t record, std::size_t line,
                          double value) {
    if (e.name != "face" || !p.floating || !is_colour(p.name) || (value >= 0 && value <= 1)) return;
    std::ostringstream v;
    v << value;
    throw InputError(path, line,
                     "face " + std::to_string(record) + " has colour " + p.name + " = " + v.str() +
                         ", outside [0, 1]. Float colours are display colours from 0 to 1; fix the file, or give "
                         "the faces a material in a scene file.");
  };
  auto refuse_list = [&](const PlyElement& e, const PlyProperty& p, std::uint64_t record, std::size_t line,
                         const std::string& count) {
    throw InputError(path, line,
                     e.name + " " + std::to_string(record) + ": the list '" + p.name + "' declares " + count +
                         " entries, more than the " + (line > 0 ? "line" : "file") + " holds. The file is damaged.");
  };

  if (header.format == "ascii") {
    std::istringstream in(text.substr(header.body));
    std::size_t line_no = header.lines;
    for (const PlyElement& e : header.elements) {
      for (std::uint64_t r = 0; r < e.count; ++r) {
        std::string line;
        do {
          if (!std::getline(in, line)) return;
          ++line_no;
        } while (line.find_first_not_of(" \t\r") == std::string::npos);
        std::vector<std::string> tokens;
        std::istringstream words(line);
        for (std::string t; words >> t;) tokens.push_back(t);
        std::size_t next = 0;
        for (const PlyProperty& p : e.properties) {
          if (next >= tokens.size()) break;  // a short line: the reader reports it
          const std::string& token = tokens[next++];
          if (p.count_size > 0) {
            char* end = nullptr;
            const long long n = std::strtoll(token.c_str(), &end, 10);
            if (*end != '\0' || n < 0 || static_cast<unsigned long long>(n) > tokens.size() - next)
              refuse_list(e, p, r, line_no, token);
            // Each entry a number of the list's type: OpenMesh reads an integer entry into
            // an int, and one that does not fit fails its stream, after which every later
            // count it reads is garbage (a 4 GB list: found by fuzzing).
            for (std::size_t k = next; k < next + static_cast<std::size_t>(n); ++k) {
              const std::string& item = tokens[k];
              char* stop = nullptr;
              bool fits = false;
              if (p.floating) {
                std::strtod(item.c_str(), &stop);
                fits = *stop == '\0';
              } else {
                errno = 0;
                const long long v = std::strtoll(item.c_str(), &stop, 10);
                fits = *stop == '\0' && errno == 0 && v >= std::numeric_limits<std::int32_t>::min() &&
                       v <= std::numeric_limits<std::int32_t>::max();
              }
              if (!fits)
                throw InputError(path, line_no,
                                 e.name + " " + std::to_string(r) + ": entry '" + item + "' of the list '" + p.name +
                                     "' is not " + (p.floating ? "a number" : "a whole number that fits in 32 bits") +
                                     ". The file is damaged.");
            }
            next += static_cast<std::size_t>(n);
            continue;
          }
          char* end = nullptr;
          const double value = std::strtod(token.c_str(), &end);  // strtod reads "nan" and "inf" too
          if (*end != '\0')
            throw InputError(path, line_no,
                             e.name + " " + std::to_string(r) + ": '" + token + "' is not a number (" + p.name + ").");
          check_colour(e, p, r, line_no, value);
        }
        // OpenMesh reads the values as one stream of words, not line by line: a value
        // too many on one line shifts every later record (a face count read from a
        // colour, then billions of indices: found by fuzzing).
        if (next < tokens.size())
          throw InputError(path, line_no,
                           e.name + " " + std::to_string(r) + " holds " + std::to_string(tokens.size()) +
                               " values, more than its properties take (" + std::to_string(next) +
                               "). Is a property line in the header misspelt or missing?");
      }
    }
    return;
  }
  const bool big_endian = header.format == "binary_big_endian";
  std::size_t at = header.body;
  auto read_bytes = [&](int size, unsigned char* out) {  // little-endian into `out`
    if (at + size > text.size()) return false;
    for (int i = 0; i < size; ++i) out[i] = static_cast<unsigned char>(text[at + (big_endian ? size - 1 - i : i)]);
    at += size;
    return true;
  };
  for (const PlyElement& e : header.elements) {
    if (e.properties.empty()) continue;
    for (std::uint64_t r = 0; r < e.count; ++r) {
      for (const PlyProperty& p : e.properties) {
        unsigned char bytes[8] = {};
        if (p.count_size > 0) {
          if (!read_bytes(p.count_size, bytes)) return;
          // Counts are read as unsigned: a negative int count is a huge one, and refused.
          std::uint64_t n = 0;
          for (int i = p.count_size - 1; i >= 0; --i) n = (n << 8) | bytes[i];
          if (n > (text.size() - at) / p.size) refuse_list(e, p, r, 0, std::to_string(n));
          at += n * p.size;
          continue;
        }
        if (!read_bytes(p.size, bytes)) return;
        if (!p.floating) continue;
        double value = 0;  // the bytes are little-endian now, as on every machine we build for
        if (p.size == 4) {
          float f = 0;
          std::memcpy(&f, bytes, 4);
          value = f;
        } else {
          std::memcpy(&value, bytes, 8);
        }
        check_colour(e, p, r, 0, value);
      }
    }
  }
}

}  // namespace dynrad::detail
