#include "mesh/io/atomic_file.h"

#include "mesh/core/error.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace dynrad {
namespace {

std::string temp_name_for(const std::string& target) {
  namespace fs = std::filesystem;
  static std::atomic<unsigned> counter{0};
  const fs::path path(target);
  const std::string name = "." + path.filename().string() + ".dynrad-" + std::to_string(::getpid()) + "-" +
                           std::to_string(counter++) + ".tmp";
  return (path.parent_path() / name).string();
}

void check_target(const std::string& target) {
  namespace fs = std::filesystem;
  const fs::path path(target);
  if (path.filename().empty()) throw OutputError(target, "is not a file name.");
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw OutputError(target, "is a directory; give a file name such as out.ply.");
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  if (!fs::is_directory(dir, ec))
    throw OutputError(target, "cannot be written: directory '" + dir.string() + "' does not exist. Create it first.");
}

// An existing target that is not a regular file nor a directory: /dev/null, a named
// pipe. It is written in place; a rename would replace the device or pipe with a file.
bool is_special_file(const std::string& target) {
  std::error_code ec;
  const auto status = std::filesystem::status(target, ec);
  return !ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
         !std::filesystem::is_directory(status);
}

}  // namespace

AtomicFile::AtomicFile(std::string target, std::ios::openmode mode) : target_(std::move(target)) {
  namespace fs = std::filesystem;
  check_target(target_);
  std::error_code ec;
  // A symbolic link stays a link: the file it points to is replaced, beside itself.
  if (fs::is_symlink(target_, ec)) {
    const fs::path resolved = fs::weakly_canonical(target_, ec);
    if (!ec) {
      target_ = resolved.string();
      check_target(target_);
    }
  }
  direct_ = is_special_file(target_);  // (renamed over, as root even /dev/null would go)
  temp_ = direct_ ? target_ : temp_name_for(target_);
  stream_.open(temp_, mode | std::ios::out | std::ios::trunc);
  if (!stream_)
    throw OutputError(target_, std::string("cannot be written: ") + std::strerror(errno) +
                                   ". Check the directory's permissions and free space.");
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  stream_.close();
  if (!direct_) std::remove(temp_.c_str());
}

void AtomicFile::commit() {
  stream_.flush();
  const bool written = static_cast<bool>(stream_);
  stream_.close();
  if (!written || stream_.fail()) {
    if (direct_) throw OutputError(target_, "writing failed.");
    std::remove(temp_.c_str());
    throw OutputError(target_, "writing failed (disk full?). The previous file, if any, is unchanged.");
  }
  if (direct_) {
    committed_ = true;
    return;
  }
  if (std::rename(temp_.c_str(), target_.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(temp_.c_str());
    throw OutputError(target_, "could not replace the file: " + why + ". The previous file, if any, is unchanged.");
  }
  committed_ = true;
}

void check_output_writable(const std::string& target) {
  if (is_special_file(target)) return;  // not opened ahead: a pipe's reader would get an empty stream
  AtomicFile probe(target);
}

}  // namespace dynrad
