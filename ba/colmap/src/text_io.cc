#include "text_io.h"

#include <array>
#include <charconv>
#include <stdexcept>

namespace trigrav {
namespace colmap {
namespace internal {
namespace {

[[noreturn]] void ThrowNotA(const char* kind,
                            std::string_view token,
                            const std::string& what,
                            const std::string& where) {
  throw std::runtime_error(where + ": " + what + " is not " + kind + ": \"" + std::string(token) +
                           "\"");
}

template <typename T>
T ParseNumber(std::string_view token,
              const char* kind,
              const std::string& what,
              const std::string& where) {
  T value{};
  const char* end = token.data() + token.size();
  const std::from_chars_result result = std::from_chars(token.data(), end, value);
  if (token.empty() || result.ec != std::errc() || result.ptr != end) {
    ThrowNotA(kind, token, what, where);
  }
  return value;
}

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

}  // namespace

std::string FormatDouble(double value) {
  std::array<char, 32> buffer;
  const std::to_chars_result result = std::to_chars(buffer.data(), buffer.data() + buffer.size(),
                                                    value, std::chars_format::general, 17);
  return std::string(buffer.data(), result.ptr);
}

std::vector<std::string_view> SplitWhitespace(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && IsSpace(line[i])) ++i;
    const std::size_t begin = i;
    while (i < line.size() && !IsSpace(line[i])) ++i;
    if (i > begin) tokens.push_back(line.substr(begin, i - begin));
  }
  return tokens;
}

std::string_view Trim(std::string_view line) {
  while (!line.empty() && IsSpace(line.front())) line.remove_prefix(1);
  while (!line.empty() && IsSpace(line.back())) line.remove_suffix(1);
  return line;
}

double ParseDouble(std::string_view token, const std::string& what, const std::string& where) {
  return ParseNumber<double>(token, "a number", what, where);
}

std::int64_t ParseInt(std::string_view token, const std::string& what, const std::string& where) {
  return ParseNumber<std::int64_t>(token, "an integer", what, where);
}

std::uint64_t ParseUint(std::string_view token, const std::string& what, const std::string& where) {
  return ParseNumber<std::uint64_t>(token, "a non-negative integer", what, where);
}

std::uint64_t ParseUintAtMost(std::string_view token,
                              std::uint64_t max_value,
                              const std::string& what,
                              const std::string& where) {
  const std::uint64_t value = ParseUint(token, what, where);
  if (value > max_value) {
    throw std::runtime_error(where + ": " + what + " " + std::string(token) +
                             " is out of range (at most " + std::to_string(max_value) + ")");
  }
  return value;
}

}  // namespace internal
}  // namespace colmap
}  // namespace trigrav
