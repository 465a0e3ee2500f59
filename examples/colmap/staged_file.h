#ifndef TRIGRAV_EXAMPLES_COLMAP_STAGED_FILE_H_
#define TRIGRAV_EXAMPLES_COLMAP_STAGED_FILE_H_

// An output file written in two steps, so that a tool that fails leaves no partial output: the
// contents go to "<path>.tmp" and are flushed to the disk on construction, Commit() renames that
// onto `path` and flushes the folder; destroyed before Commit(), the temporary file is removed.

#include <string>

namespace trigrav::colmap_tools {

class StagedFile {
 public:
  // Throws std::runtime_error naming `path` when the temporary file cannot be written.
  StagedFile(const std::string& path, const std::string& contents);
  ~StagedFile();
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;

  // Throws std::runtime_error naming `path` when the rename fails.
  void Commit();

 private:
  std::string path_;
  bool committed_ = false;
};

}  // namespace trigrav::colmap_tools

#endif  // TRIGRAV_EXAMPLES_COLMAP_STAGED_FILE_H_
