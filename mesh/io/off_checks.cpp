// OFF, and what PLY, OFF and STL share: the format sniffed, counts checked against the
// file's size, ASCII vertices checked, ASCII OFF normalised, binary OFF's faces walked.
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

std::string sniff_format(const std::string& head) {
  if (head.rfind("ply", 0) == 0) return ".ply";
  if (head.rfind("OFF", 0) == 0 || head.rfind("COFF", 0) == 0 || head.rfind("NOFF", 0) == 0 ||
      head.rfind("CNOFF", 0) == 0 || head.rfind("STOFF", 0) == 0)
    return ".off";
  if (head.rfind("solid", 0) == 0) return ".stl";
  return "";
}

std::vector<std::uint32_t> ascii_data_lines(const std::string& text, const std::string& ext) {
  std::vector<std::uint32_t> lines;
  std::istringstream in(text);
  std::uint32_t line_no = 0;
  bool in_data = false;
  int off_header_lines = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    if (in_data) {
      lines.push_back(line_no);
    } else if (ext == ".ply") {
      in_data = line.rfind("end_header", 0) == 0;
    } else if (++off_header_lines == 2) {  // the keyword, then "nv nf ne" (check_declared_counts)
      in_data = true;
    }
  }
  return lines;
}

bool off_is_binary(const std::string& text) {
  std::size_t p = 0;
  if (text.compare(p, 2, "ST") == 0) p += 2;
  if (text.compare(p, 1, "C") == 0) ++p;
  if (text.compare(p, 1, "N") == 0) ++p;
  if (text.compare(p, 3, "OFF") != 0) return false;
  p += 4;
  return p <= text.size() && text.compare(p, 6, "BINARY") == 0 && text.find('\n') > p;
}

std::string strip_comments(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  bool comment = false;
  for (char c : text) {
    if (c == '#') comment = true;
    if (c == '\n') comment = false;
    if (!comment) out.push_back(c);
  }
  return out;
}

bool parse_count(const std::string& token, std::uint64_t& count) {
  if (token.empty() || token.size() > 18 || token.find_first_not_of("0123456789") != std::string::npos) return false;
  count = std::stoull(token);
  return true;
}

bool is_ascii(const std::string& text, const std::string& ext) {
  if (ext == ".off") return !off_is_binary(text);
  if (ext == ".ply") return text.find("format ascii") != std::string::npos;
  return text.rfind("solid", 0) == 0;
}

DeclaredCounts check_declared_counts(const std::string& path, const std::string& text, const std::string& ext,
                                     const PlyHeader& header) {
  std::uint64_t vertices = 0, faces = 0;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> records;  // (count, least bytes per record)
  std::string others;    // PLY elements other than vertex and face, for the message
  std::size_t body = 0;  // offset where element data starts
  if (ext == ".ply") {
    for (const PlyElement& e : header.elements) {
      if (e.name == "vertex") vertices = e.count;
      if (e.name == "face") faces = e.count;
      if (e.name != "vertex" && e.name != "face" && e.count > 0)
        others += ", " + std::to_string(e.count) + " " + e.name + " elements";
      // Every property value takes a byte at least (a digit and a separator in ASCII).
      records.emplace_back(e.count, std::max<std::uint64_t>(1, e.properties.size()));
    }
    body = header.body;
  } else if (ext == ".off") {
    if (off_is_binary(text)) {
      // Binary OFF as OpenMesh reads and writes it: after the first line, three 32-bit
      // little-endian counts (vertices, faces, edges); a vertex is at least 3 floats, a
      // face at least a count and 3 indices. OpenMesh loops over whatever they say.
      body = text.find('\n');
      std::int32_t counts[3] = {0, 0, 0};
      if (body == std::string::npos || text.size() < body + 1 + sizeof counts)
        throw InputError(path, 0, "binary OFF without vertex and face counts: the file is truncated.");
      std::memcpy(counts, text.data() + body + 1, sizeof counts);
      if (counts[0] < 0 || counts[1] < 0)
        throw InputError(path, 0,
                         "binary OFF declares " + std::to_string(counts[0]) + " vertices and " +
                             std::to_string(counts[1]) +
                             " faces: the header is damaged (or big-endian, which "
                             "dynrad does not read; convert the file to PLY).");
      vertices = static_cast<std::uint64_t>(counts[0]);
      faces = static_cast<std::uint64_t>(counts[1]);
      body += 1 + sizeof counts;
      records = {{vertices, 12}, {faces, 16}};
      check_binary_off_faces(path, text, body, vertices, faces);
    } else {
      // OpenMesh takes the whole first line as the keyword and the next three words as
      // the counts, wherever they are. Both are held to one line each here, so that
      // what OpenMesh reads and what is checked (and the line numbers) agree.
      const std::string stripped = strip_comments(text);
      std::istringstream in(stripped);
      std::string magic_line, counts_line;
      std::getline(in, magic_line);
      std::istringstream magic_words(magic_line);
      std::string magic, rest;
      magic_words >> magic >> rest;
      static const std::set<std::string> keywords = {"OFF",   "COFF",   "NOFF",   "CNOFF",
                                                     "STOFF", "STCOFF", "STNOFF", "STCNOFF"};
      if (!keywords.count(magic) || !rest.empty())
        throw InputError(path, 1,
                         "the first line must hold only the keyword (OFF, COFF, NOFF, CNOFF or STOFF), not '" +
                             magic_line + "'. Put the counts on the next line.");
      std::size_t counts_line_no = 1;
      while (std::getline(in, counts_line)) {
        ++counts_line_no;
        if (counts_line.find_first_not_of(" \t\r") != std::string::npos) break;
      }
      std::istringstream count_words(counts_line);
      std::string v, f, e, extra;
      count_words >> v >> f >> e >> extra;
      std::uint64_t edges = 0;
      if (!parse_count(v, vertices) || !parse_count(f, faces) || !parse_count(e, edges) || !extra.empty())
        throw InputError(path, counts_line_no,
                         "the line after the keyword must hold three whole numbers, the vertex, face and edge "
                         "counts (found '" +
                             counts_line + "').");
      body = in.tellg() < 0 ? text.size() : static_cast<std::size_t>(in.tellg());
      records = {{vertices, 3}, {faces, 4}};  // "x y z", and "3 a b c" at the least
    }
  } else {
    return {};  // STL: the count is implied by the size (binary) or absent (ASCII)
  }
  const std::uint64_t room = text.size() > body ? text.size() - body : 0;
  std::uint64_t needed = 0;
  bool fits = true;
  for (const auto& [count, bytes] : records) {
    fits = fits && count <= (room - needed) / bytes;
    if (fits) needed += count * bytes;
  }
  if (!fits)
    throw InputError(path, 0,
                     "the header declares " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                         " faces" + others + ", more than the " + std::to_string(room) +
                         " bytes after it can hold: the file is truncated or its header is damaged.");
  return {vertices, faces};
}

void check_ascii_vertices(const std::string& path, const std::string& text,
                          const std::vector<std::uint32_t>& data_lines, std::size_t count) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    lines.push_back(std::string_view(text).substr(start, end - start));
    start = end + 1;
  }
  for (std::size_t k = 0; k < count && k < data_lines.size(); ++k) {
    const std::string line(lines[data_lines[k] - 1]);
    std::istringstream in(line);
    for (std::string token; in >> token;) {
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0')
        throw InputError(path, data_lines[k], "vertex " + std::to_string(k) + ": '" + token + "' is not a number.");
      if (!std::isfinite(value))
        throw InputError(path, data_lines[k],
                         "vertex " + std::to_string(k) + " has a coordinate that is not finite ('" + token +
                             "'). Fix it in the modelling tool.");
    }
  }
}

void check_binary_off_faces(const std::string& path, const std::string& text, std::size_t body,
                            std::uint64_t vertices, std::uint64_t faces) {
  std::size_t p = 0;
  bool tex = false, colour = false, normal = false;
  if (text.compare(p, 2, "ST") == 0) tex = true, p += 2;
  if (text.compare(p, 1, "C") == 0) colour = true, ++p;
  if (text.compare(p, 1, "N") == 0) normal = true, ++p;
  const std::uint64_t vertex_bytes = 4 * (3 + (normal ? 3 : 0) + (colour ? 3 : 0) + (tex ? 2 : 0));
  const std::uint64_t size = text.size();
  if (vertices > (size - std::min<std::uint64_t>(size, body)) / vertex_bytes)
    throw InputError(path, 0,
                     "binary OFF declares " + std::to_string(vertices) + " vertices of " +
                         std::to_string(vertex_bytes) + " bytes each, more than the file holds: it is truncated.");
  std::uint64_t at = body + vertices * vertex_bytes;
  for (std::uint64_t f = 0; f < faces; ++f) {
    std::uint32_t corners = 0;
    if (at + 4 > size)
      throw InputError(path, 0,
                       "binary OFF declares " + std::to_string(faces) + " faces but the file ends in face " +
                           std::to_string(f) + ": it is truncated.");
    std::memcpy(&corners, text.data() + at, 4);
    const std::uint64_t record = 4 * (1 + static_cast<std::uint64_t>(corners) + (colour ? 3 : 0));
    if (record > size - at)
      throw InputError(path, 0,
                       "binary OFF face " + std::to_string(f) + " declares " + std::to_string(corners) +
                           " corners, more than the rest of the file holds: the file is damaged.");
    at += record;
  }
}

void normalise_ascii_off(const std::string& path, std::string& parsed, const std::vector<std::uint32_t>& data_lines,
                         std::uint64_t vertices, std::uint64_t faces) {
  std::string keyword;
  std::istringstream(parsed.substr(0, parsed.find('\n'))) >> keyword;
  const auto prefix = keyword.substr(0, keyword.size() >= 3 ? keyword.size() - 3 : 0);
  const bool normals = prefix.find('N') != std::string::npos;
  const bool face_rest_read = prefix.find('C') != std::string::npos;
  const std::uint64_t coordinates = normals ? 6 : 3;

  std::vector<std::size_t> line_start = {0};
  for (std::size_t i = 0; i < parsed.size(); ++i)
    if (parsed[i] == '\n') line_start.push_back(i + 1);
  auto line_range = [&](std::size_t line_no) {
    const std::size_t begin = line_start[line_no - 1];
    const std::size_t end = line_no < line_start.size() ? line_start[line_no] - 1 : parsed.size();
    return std::make_pair(begin, end);
  };
  // Token k of a line: where it ends, or npos when the line has fewer.
  auto end_of_token = [&](std::size_t begin, std::size_t end, std::uint64_t k) {
    std::size_t i = begin;
    for (std::uint64_t t = 0; t <= k; ++t) {
      while (i < end && std::isspace(static_cast<unsigned char>(parsed[i]))) ++i;
      if (i == end) return std::string::npos;
      while (i < end && !std::isspace(static_cast<unsigned char>(parsed[i]))) ++i;
    }
    return i;
  };

  for (std::uint64_t v = 0; v < vertices && v < data_lines.size(); ++v) {
    const auto [begin, end] = line_range(data_lines[v]);
    if (end_of_token(begin, end, coordinates - 1) == std::string::npos)
      throw InputError(path, data_lines[v],
                       "vertex " + std::to_string(v) + " must hold " + std::to_string(coordinates) +
                           " numbers on its line (x y z" + (normals ? " and a normal" : "") +
                           "). The file is damaged.");
  }
  for (std::uint64_t f = 0; f < faces && vertices + f < data_lines.size(); ++f) {
    const std::size_t line_no = data_lines[vertices + f];
    const auto [begin, end] = line_range(line_no);
    std::istringstream words(parsed.substr(begin, end - begin));
    std::string count;
    words >> count;
    std::uint64_t n = 0;
    if (!parse_count(count, n))
      throw InputError(path, line_no,
                       "face " + std::to_string(f) + " must start with its number of corners, not '" + count + "'.");
    const std::size_t last = n < end - begin ? end_of_token(begin, end, n) : std::string::npos;
    if (last == std::string::npos) {
      std::uint64_t indices = 0;
      for (std::string t; words >> t;) ++indices;
      throw InputError(path, line_no,
                       "face " + std::to_string(f) + " declares " + std::to_string(n) + " corners but lists " +
                           std::to_string(indices) + ". The file is damaged.");
    }
    // OpenMesh reads each index as far as it parses ("2-4" gives 2, and "-4" becomes the
    // next face's corner count, four billion): every index must be a plain whole number.
    for (std::uint64_t k = 0; k < n; ++k) {
      std::string index;
      words >> index;
      if (index.empty() || !std::all_of(index.begin(), index.end(), [](char c) { return c >= '0' && c <= '9'; }))
        throw InputError(path, line_no,
                         "face " + std::to_string(f) + ": corner " + std::to_string(k) + " is '" + index +
                             "', not a vertex number. The file is damaged.");
    }
    if (!face_rest_read) std::fill(parsed.begin() + static_cast<std::ptrdiff_t>(last),
                                   parsed.begin() + static_cast<std::ptrdiff_t>(end), ' ');
  }
}

}  // namespace dynrad::detail
