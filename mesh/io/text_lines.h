// Line by line through a text held in memory, for the readers of text formats.
#pragma once

#include <cstddef>
#include <string_view>

namespace dynrad {

// The line of `text` that starts at `pos`, without its line break ("\n", "\r\n" or a
// lone "\r"), into `line`; `pos` moves past the break. False at the end of the text.
inline bool next_text_line(std::string_view text, std::size_t& pos, std::string_view& line) {
  if (pos >= text.size()) return false;
  const std::size_t end = text.find_first_of("\r\n", pos);
  line = text.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos);
  pos = end == std::string_view::npos ? text.size() : end + 1;
  if (end != std::string_view::npos && text[end] == '\r' && pos < text.size() && text[pos] == '\n') ++pos;
  return true;
}

}  // namespace dynrad
