#include "trigrav/colmap/gravity_csv.h"

#include <sstream>
#include <stdexcept>
#include <string_view>

#include "file_io.h"
#include "text_io.h"

namespace trigrav {
namespace colmap {
namespace {

constexpr std::string_view kHeader = "image_name,gravity_x,gravity_y,gravity_z";

// A usable gravity: finite and of positive length.
bool IsUsableGravity(const Eigen::Vector3d& gravity) {
  return gravity.allFinite() && gravity.norm() > 0.0;
}

std::vector<std::string_view> SplitCommas(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = line.find(',', begin);
    fields.push_back(internal::Trim(line.substr(begin, comma - begin)));
    if (comma == std::string_view::npos) return fields;
    begin = comma + 1;
  }
}

}  // namespace

GravityByImageName ReadGravityCsv(const std::string& path) {
  const std::string contents = internal::ReadFileContents(path);
  GravityByImageName gravity;
  bool has_header = false;
  int line_number = 0;
  std::size_t position = 0;
  while (position < contents.size()) {
    std::size_t end = contents.find('\n', position);
    if (end == std::string::npos) end = contents.size();
    const std::string_view line =
        internal::Trim(std::string_view(contents).substr(position, end - position));
    position = end + 1;
    ++line_number;
    if (line.empty() || line.front() == '#') continue;
    const std::string where = path + ":" + std::to_string(line_number);
    if (!has_header) {
      if (line != kHeader) {
        throw std::runtime_error(where + ": expected the header \"" + std::string(kHeader) + "\"");
      }
      has_header = true;
      continue;
    }
    const std::vector<std::string_view> fields = SplitCommas(line);
    if (fields.size() != 4 || fields[0].empty()) {
      throw std::runtime_error(where + ": expected image_name,gravity_x,gravity_y,gravity_z");
    }
    const Eigen::Vector3d vector(internal::ParseDouble(fields[1], "gravity_x", where),
                                 internal::ParseDouble(fields[2], "gravity_y", where),
                                 internal::ParseDouble(fields[3], "gravity_z", where));
    if (!IsUsableGravity(vector)) {
      throw std::runtime_error(where + ": the gravity of " + std::string(fields[0]) +
                               " is zero or not finite");
    }
    if (!gravity.emplace(std::string(fields[0]), vector).second) {
      throw std::runtime_error(where + ": " + std::string(fields[0]) + " appears twice");
    }
  }
  if (!has_header) {
    throw std::runtime_error(path + ": empty (expected the header \"" + std::string(kHeader) +
                             "\")");
  }
  return gravity;
}

void WriteGravityCsv(const GravityByImageName& gravity, const std::string& path) {
  std::string contents = std::string(kHeader) + "\n";
  for (const auto& [name, vector] : gravity) {
    if (name.empty() || name.front() == '#' || name != internal::Trim(name) ||
        name.find_first_of(",\n\r") != std::string::npos) {
      throw std::runtime_error(path + ": image name \"" + name +
                               "\" cannot be written (empty, a leading '#', surrounding "
                               "whitespace, a comma or a line break)");
    }
    if (!IsUsableGravity(vector)) {
      throw std::runtime_error(path + ": the gravity of " + name + " is zero or not finite");
    }
    contents += name;
    for (int i = 0; i < 3; ++i) contents += "," + internal::FormatDouble(vector[i]);
    contents += "\n";
  }
  internal::WriteFileAtomically(path, contents);
}

std::vector<Eigen::Vector3d> GravityOfImages(const GravityByImageName& gravity,
                                             const std::vector<std::string>& image_names) {
  std::vector<Eigen::Vector3d> result;
  result.reserve(image_names.size());
  std::vector<std::string> missing;
  for (const std::string& name : image_names) {
    const auto entry = gravity.find(name);
    if (entry == gravity.end()) {
      missing.push_back(name);
    } else {
      result.push_back(entry->second);
    }
  }
  if (!missing.empty()) {
    constexpr std::size_t kMaxListed = 5;
    std::string list;
    for (std::size_t i = 0; i < missing.size() && i < kMaxListed; ++i) {
      list += (i > 0 ? ", " : "") + missing[i];
    }
    if (missing.size() > kMaxListed) list += ", ...";
    throw std::runtime_error("no gravity for " + std::to_string(missing.size()) + " of " +
                             std::to_string(image_names.size()) + " images: " + list);
  }
  return result;
}

}  // namespace colmap
}  // namespace trigrav
