#ifndef TRIGRAV_EXAMPLES_COMMON_TOOL_FLAGS_H_
#define TRIGRAV_EXAMPLES_COMMON_TOOL_FLAGS_H_

// The tools' flag parsing (header only): one call at the top of main,
//
//   trigrav::examples::ParseToolFlags("what the tool does", __FILE__, &argc, &argv);
//
// in place of gflags::SetUsageMessage and gflags::ParseCommandLineFlags. Flags parse as with
// gflags; only the help differs (gflags 2.2.2 offers no setting for either):
// - --help and --helpshort list the tool's own flags, those defined in `tool_file` (the file of
//   its main), not the flags of glog and gflags linked into it; --helpfull lists every flag.
//   gflags'
//   --help lists every flag and its --helpshort only the flags of a file named like the binary.
// - defaults of double flags are printed with the fewest digits that read back the same value
//   (0.9999, where gflags prints %.17g: 0.99990000000000001).
// The help goes to stdout and the tool exits with status 0. The other help flags (--helpon,
// --helpmatch, --helppackage, --helpxml, --version) are gflags'.

#include <gflags/gflags.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace trigrav::examples {

namespace tool_flags_internal {

// A double as gflags prints it (%.17g) at the fewest significant digits that read back the same
// value; other text unchanged.
inline std::string ShortestDouble(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0') return text;
  char shortest[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(shortest, sizeof(shortest), "%.*g", digits, value);
    if (std::strtod(shortest, nullptr) == value) break;
  }
  return shortest;
}

inline bool HelpFlagSet(const char* name) {
  std::string value;
  return gflags::GetCommandLineOption(name, &value) && value == "true";
}

// Usage line, then the flags (all, or those of `tool_file`) grouped by file as gflags does.
inline void PrintHelp(const char* tool_file, bool all_flags) {
  std::printf("%s: %s\n", gflags::ProgramInvocationShortName(), gflags::ProgramUsage());
  std::vector<gflags::CommandLineFlagInfo> flags;
  gflags::GetAllFlags(&flags);  // sorted by file, then name
  std::string file;
  for (gflags::CommandLineFlagInfo& flag : flags) {
    if (!all_flags && flag.filename != tool_file) continue;
    if (flag.filename != file) {
      file = flag.filename;
      std::printf("\n  Flags from %s:\n", file.c_str());
    }
    if (flag.type == "double") {
      flag.default_value = ShortestDouble(flag.default_value);
      flag.current_value = ShortestDouble(flag.current_value);
    }
    std::printf("%s", gflags::DescribeOneFlag(flag).c_str());
  }
  if (!all_flags) std::printf("\n  --helpfull: every flag, also gflags' and glog's.\n");
}

}  // namespace tool_flags_internal

// Sets the usage message and parses the flags, removing them from argv; handles the help flags
// (above) and exits after printing help.
inline void ParseToolFlags(const char* usage, const char* tool_file, int* argc, char*** argv) {
  gflags::SetUsageMessage(usage);
  gflags::ParseCommandLineNonHelpFlags(argc, argv, /*remove_flags=*/true);
  const bool all_flags = tool_flags_internal::HelpFlagSet("helpfull");
  if (all_flags || tool_flags_internal::HelpFlagSet("help") ||
      tool_flags_internal::HelpFlagSet("helpshort")) {
    tool_flags_internal::PrintHelp(tool_file, all_flags);
    std::exit(0);
  }
  gflags::HandleCommandLineHelpFlags();
}

}  // namespace trigrav::examples

#endif  // TRIGRAV_EXAMPLES_COMMON_TOOL_FLAGS_H_
