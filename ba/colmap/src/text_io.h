#ifndef TRIGRAV_COLMAP_SRC_TEXT_IO_H_
#define TRIGRAV_COLMAP_SRC_TEXT_IO_H_

// Numbers in text files, independent of the locale: written with 17 significant digits (every
// double reads back bit-exact, as COLMAP's own writer), parsed with std::from_chars. Parse errors
// throw std::runtime_error "<where>: <what> is not <kind>: \"token\"".

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace trigrav {
namespace colmap {
namespace internal {

std::string FormatDouble(double value);
// Whitespace-separated tokens of a line.
std::vector<std::string_view> SplitWhitespace(std::string_view line);
// The line without leading and trailing spaces, tabs and '\r'.
std::string_view Trim(std::string_view line);

double ParseDouble(std::string_view token, const std::string& what, const std::string& where);
std::int64_t ParseInt(std::string_view token, const std::string& what, const std::string& where);
std::uint64_t ParseUint(std::string_view token, const std::string& what, const std::string& where);
// ParseUint, throwing unless the value fits in `max_value`.
std::uint64_t ParseUintAtMost(std::string_view token,
                              std::uint64_t max_value,
                              const std::string& what,
                              const std::string& where);

}  // namespace internal
}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_SRC_TEXT_IO_H_
