#ifndef TRIGRAV_EXAMPLES_COLMAP_MODEL_FOLDER_H_
#define TRIGRAV_EXAMPLES_COLMAP_MODEL_FOLDER_H_

// A tool's model output: trigrav::colmap::WriteModel (one set: the old model or the new one,
// never a mix) into a folder whose missing parent folders are created first and removed again
// when the write fails, so that a failed run leaves no empty folder.

#include <string>

#include "trigrav/colmap/model_io.h"

namespace trigrav::colmap_tools {

// Throws what WriteModel throws, or std::filesystem::filesystem_error when a parent folder
// cannot be created.
void WriteModelFolder(const colmap::Reconstruction& model,
                      const std::string& folder,
                      colmap::ModelFormat format);

}  // namespace trigrav::colmap_tools

#endif  // TRIGRAV_EXAMPLES_COLMAP_MODEL_FOLDER_H_
