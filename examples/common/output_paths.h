#ifndef TRIGRAV_EXAMPLES_COMMON_OUTPUT_PATHS_H_
#define TRIGRAV_EXAMPLES_COMMON_OUTPUT_PATHS_H_

// The tools' guard against losing their input (header only): an output must not be, lie inside or
// contain an input or another output. Paths are compared as the file system resolves them:
// symbolic links, "./x" and "x", "..", and for existing entries the device and inode (hard links,
// bind mounts). The files gflags read through --flagfile are inputs too. Tools check this with
// their flags, before any work; a conflict exits like a bad flag (require_flag.h).

#include <gflags/gflags.h>
#include <sys/stat.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "common/require_flag.h"

namespace trigrav::examples {

// A path a tool reads or writes; `what` names it in messages (a flag, or "poses.csv of
// --output_dir").
struct ToolPath {
  enum Kind { kFile, kFolder };  // a folder: everything below it is read, or written
  std::string what;
  std::string path;
  Kind kind = kFile;
};

namespace output_paths_internal {

// The absolute path with symbolic links, "." and ".." resolved as far as it exists, no trailing
// separator.
inline std::filesystem::path Resolve(const std::string& path) {
  std::error_code error;
  std::filesystem::path resolved =
      std::filesystem::weakly_canonical(std::filesystem::absolute(path, error), error);
  if (error) resolved = std::filesystem::absolute(path, error).lexically_normal();
  if (!resolved.has_filename() && resolved.has_relative_path()) resolved = resolved.parent_path();
  return resolved;
}

inline bool SameEntry(const std::filesystem::path& a, const std::filesystem::path& b) {
  struct stat info_a, info_b;
  if (::stat(a.c_str(), &info_a) != 0 || ::stat(b.c_str(), &info_b) != 0) return a == b;
  return info_a.st_dev == info_b.st_dev && info_a.st_ino == info_b.st_ino;
}

}  // namespace output_paths_internal

// True when `path` is `folder` or lies below it.
inline bool IsWithin(const std::string& path, const std::string& folder) {
  const std::filesystem::path resolved_folder = output_paths_internal::Resolve(folder);
  for (std::filesystem::path above = output_paths_internal::Resolve(path);;
       above = above.parent_path()) {
    if (above == resolved_folder || output_paths_internal::SameEntry(above, resolved_folder)) {
      return true;
    }
    if (!above.has_relative_path()) return false;  // the root
  }
}

// The first conflict of an output with an input or with another output, as a message; "" when
// there is none.
inline std::string OutputConflict(const std::vector<ToolPath>& inputs,
                                  const std::vector<ToolPath>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const ToolPath& output = outputs[i];
    std::vector<const ToolPath*> others;
    for (const ToolPath& input : inputs) others.push_back(&input);
    for (std::size_t j = i + 1; j < outputs.size(); ++j) others.push_back(&outputs[j]);
    for (const ToolPath* other : others) {
      const char* relation = nullptr;
      if (output_paths_internal::SameEntry(output_paths_internal::Resolve(output.path),
                                           output_paths_internal::Resolve(other->path))) {
        relation = "is the same path as";
      } else if (other->kind == ToolPath::kFolder && IsWithin(output.path, other->path)) {
        relation = "lies inside";
      } else if (output.kind == ToolPath::kFolder && IsWithin(other->path, output.path)) {
        relation = "contains";
      }
      if (relation != nullptr) {
        return output.what + " (" + output.path + ") " + relation + " " + other->what + " (" +
               other->path + "): an output must not be, lie inside or contain an input or " +
               "another output; nothing was done";
      }
    }
  }
  return "";
}

// The files read through gflags' --flagfile (a comma-separated list), as inputs.
inline std::vector<ToolPath> FlagfileInputs() {
  std::string value;
  std::vector<ToolPath> inputs;
  if (!gflags::GetCommandLineOption("flagfile", &value)) return inputs;
  std::istringstream list(value);
  for (std::string file; std::getline(list, file, ',');) {
    if (!file.empty()) inputs.push_back({"--flagfile", file});
  }
  return inputs;
}

// Exits with kBadFlagExitCode, printing the conflict, when an output is, lies inside or contains
// an input (--flagfile's files included) or another output.
inline void RequireOutputsApartFromInputs(std::vector<ToolPath> inputs,
                                          const std::vector<ToolPath>& outputs) {
  for (ToolPath& flagfile : FlagfileInputs()) inputs.push_back(std::move(flagfile));
  const std::string conflict = OutputConflict(inputs, outputs);
  RequireFlag(conflict.empty(), conflict);
}

}  // namespace trigrav::examples

#endif  // TRIGRAV_EXAMPLES_COMMON_OUTPUT_PATHS_H_
