#include "model_folder.h"

#include <filesystem>
#include <system_error>
#include <vector>

namespace trigrav::colmap_tools {

void WriteModelFolder(const colmap::Reconstruction& model,
                      const std::string& folder,
                      colmap::ModelFormat format) {
  namespace fs = std::filesystem;
  // The missing folders above `folder`, deepest first.
  std::vector<fs::path> missing;
  for (fs::path above = fs::path(folder).lexically_normal().parent_path();
       !above.empty() && !fs::exists(above) && above != above.parent_path();
       above = above.parent_path()) {
    missing.push_back(above);
  }
  std::vector<fs::path> created;
  try {
    for (auto above = missing.rbegin(); above != missing.rend(); ++above) {
      fs::create_directory(*above);
      created.push_back(*above);
    }
    colmap::WriteModel(model, folder, format);
  } catch (...) {
    std::error_code ignored;
    for (auto above = created.rbegin(); above != created.rend(); ++above) {
      fs::remove(*above, ignored);  // only an empty folder is removed
    }
    throw;
  }
}

}  // namespace trigrav::colmap_tools
