// Errors a user can act on. Every message names the file (and line or face where the
// format has them) and says what to do. The command line maps these to exit code 2.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace dynrad {

// Something is wrong with what the user gave us (an input file, a scene, an option).
class InputError : public std::runtime_error {
 public:
  // `line` is 1-based; 0 means the location has no line (binary formats, whole file).
  InputError(std::string file, std::size_t line, const std::string& what);
  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }

 private:
  std::string file_;
  std::size_t line_;
};

// An output could not be written (directory missing, permission, disk full).
class OutputError : public std::runtime_error {
 public:
  OutputError(std::string file, const std::string& what);
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

}  // namespace dynrad
