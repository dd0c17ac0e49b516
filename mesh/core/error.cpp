#include "mesh/core/error.h"

#include <utility>

namespace dynrad {

namespace {
std::string located(const std::string& file, std::size_t line, const std::string& what) {
  std::string where = file;
  if (line > 0) where += ":" + std::to_string(line);
  return where + ": " + what;
}
}  // namespace

InputError::InputError(std::string file, std::size_t line, const std::string& what)
    : std::runtime_error(located(file, line, what)), file_(std::move(file)), line_(line) {}

OutputError::OutputError(std::string file, const std::string& what)
    : std::runtime_error(file + ": " + what), file_(std::move(file)) {}

}  // namespace dynrad
