// Checks of PLY and OFF files before OpenMesh reads them (mesh/io/read_openmesh.cpp).
// OpenMesh's readers trust what a file declares: counts, list lengths, header lines.
// A damaged or hostile file then makes them crash, loop or allocate without bound, or
// read one value as another. Each check here refuses such a file with a message that
// names the file, the line or element, and what to do.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dynrad::detail {

// A PLY header, parsed and checked before OpenMesh sees it: OpenMesh's reader writes
// through a property line that no element line precedes (a crash), and reads counts
// that do not fit its 32-bit integers as whatever they wrap to.
struct PlyProperty {
  std::string name;
  int size = 0;        // bytes of a scalar, or of each list item
  int count_size = 0;  // bytes of a list's count; 0 for scalars
  bool floating = false;
};
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};
struct PlyHeader {
  std::string format;  // ascii, binary_little_endian, binary_big_endian
  std::vector<PlyElement> elements;
  std::size_t body = 0;   // offset of the first byte after end_header's line
  std::size_t lines = 0;  // lines up to and including end_header
  std::vector<std::string> warnings;  // lines skipped: neither a PLY keyword nor a comment
};

// A damaged header can declare billions of elements; readers would then allocate or
// loop until the machine gives up. Refuse counts the file's size cannot hold.
struct DeclaredCounts {
  std::uint64_t vertices = 0, faces = 0;
};

// What the first bytes say the file is, to catch mislabelled files before a reader
// produces a confusing failure.
std::string sniff_format(const std::string& head);

// For line-based ASCII formats: the 1-based line of every data line after the header
// (OFF: after the counts line, skipping comments; PLY: after end_header), so messages
// about vertex k or face f can name their line.
std::vector<std::uint32_t> ascii_data_lines(const std::string& text, const std::string& ext);

// Whether OpenMesh reads an OFF file as binary: its first line is [ST][C][N]OFF, any one
// character, then BINARY. Anything else it reads as ASCII, so the checks must too.
bool off_is_binary(const std::string& text);

// Comments ('#' to the end of the line) replaced by nothing, line breaks kept.
std::string strip_comments(const std::string& text);

// A count: digits only (OpenMesh reads "-2" as 4294967294), at most 18 of them so that
// sums of counts cannot overflow. Whether the file can hold them is checked later.
bool parse_count(const std::string& token, std::uint64_t& count);

// PLY's header parsed and checked (see PlyHeader); with strict, unknown header lines are refused.
PlyHeader parse_ply_header(const std::string& path, const std::string& text, bool strict);

// The header as OpenMesh should read it (the body is not part of it), with as many
// lines as the file's, so that line numbers stay those of the file:
// - "ply", then the format line: OpenMesh reads the second and third words after "ply"
//   as the format, whatever line they are on;
// - then comments, obj_info and skipped lines, all as comments, and blank lines:
//   OpenMesh reads a comment to the end of its line but any other line word by word,
//   where a word like "element" would be taken as a keyword;
// - then element and property lines in their order, and end_header. In binary files
//   OpenMesh finds the data by assuming that the line before end_header ends right
//   after its last word, which a comment line (read with its line break) or a blank
//   line breaks by a byte.
std::string header_for_openmesh(const std::string& text, const PlyHeader& header);

// Binary OFF as OpenMesh 9 reads it, every value 4 bytes: a vertex is x y z, then a
// normal (3) with 'N' in the keyword, a colour (3) with 'C', texture coordinates (2)
// with "ST"; a face is its corner count n, n indices, and a colour (3) with 'C' (read
// because dynrad asks for face colours). OpenMesh takes n as it comes and reads n indices
// past the end of the file (a damaged count of 4 billion ran until the fuzzer's
// timeout), so each face's record is walked here and must fit in the file.
void check_binary_off_faces(const std::string& path, const std::string& text, std::size_t body,
                            std::uint64_t vertices, std::uint64_t faces);

// The vertex and face counts the header declares, refused where the file's size cannot hold them.
DeclaredCounts check_declared_counts(const std::string& path, const std::string& text, const std::string& ext,
                                     const PlyHeader& header);

// Each of the first `count` data lines must hold finite numbers only.
void check_ascii_vertices(const std::string& path, const std::string& text,
                          const std::vector<std::uint32_t>& data_lines, std::size_t count);

// Walks the PLY body (ASCII or binary) before OpenMesh does, for two things OpenMesh
// gets wrong:
// - a list count is believed whatever it says: OpenMesh appends that many indices,
//   reading past the line or the end of the file, until memory runs out;
// - float face colours become bytes without clamping (1.5 becomes 126/255, -0.5
//   becomes 129/255), so a colour outside [0, 1] would silently become another.
// Both are refused naming the element. A body that simply ends early ends the walk
// quietly: the reader's own truncation checks then name what is missing.
void check_ply_body(const std::string& path, const std::string& text, const PlyHeader& header);

// ASCII OFF as OpenMesh reads it: each vertex takes three coordinates (six with 'N')
// from the token stream, wherever the line breaks fall, then the rest of its line; each
// face takes its corner count and that many indices from the token stream, and the
// rest of its line only when the keyword has 'C'. So a short vertex line shifts
// everything after it, a corner count is believed (OpenMesh appends that many indices
// until memory runs out), and a colour after a face in a plain "OFF" file is read as
// the next face's corner count. Here every vertex and face line is checked to hold
// what it declares, and without 'C' whatever follows a face's indices is blanked out
// of `parsed` (face colours are not read), so OpenMesh reads what the lines say.
void normalise_ascii_off(const std::string& path, std::string& parsed, const std::vector<std::uint32_t>& data_lines,
                         std::uint64_t vertices, std::uint64_t faces);


bool is_ascii(const std::string& text, const std::string& ext);

}  // namespace dynrad::detail
