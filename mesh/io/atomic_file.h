// Outputs are written to a temporary file beside the target and renamed over it only
// once complete, so a target is never half-written and an existing file survives any
// failed run untouched. A target that is a symbolic link keeps the link (the file it
// points to is replaced); one that exists and is not a regular file (/dev/null, a named
// pipe) is written directly.
#pragma once

#include <fstream>
#include <string>

namespace dynrad {

class AtomicFile {
 public:
  // Creates the temporary file; throws OutputError naming `target` when its directory
  // does not exist or cannot be written, or when `target` is a directory.
  explicit AtomicFile(std::string target, std::ios::openmode mode = std::ios::binary);
  ~AtomicFile();  // removes the temporary file unless commit() succeeded
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return stream_; }
  const std::string& temp_path() const { return temp_; }
  const std::string& target() const { return target_; }
  // Flushes, closes and renames onto the target; throws OutputError on any failure
  // (the target is then unchanged).
  void commit();

 private:
  std::string target_, temp_;
  std::ofstream stream_;
  bool committed_ = false;
  bool direct_ = false;  // written in place: not a regular file
};

// Fails early, before any long computation, if `target` could not be written.
void check_output_writable(const std::string& target);

}  // namespace dynrad
