#ifndef TRIGRAV_EXAMPLES_KITTI_CACHE_FILE_H_
#define TRIGRAV_EXAMPLES_KITTI_CACHE_FILE_H_

// Writing a cache file so that a reader never sees half of it, even with several threads or
// processes writing the same file: the bytes go to a temporary file of this thread, then a rename
// replaces the file at once.

#include <functional>
#include <ostream>
#include <string>

namespace trigrav::kitti {

// Calls write(stream) on a temporary file beside `path`, then renames it to `path`. False if the
// file cannot be written (the stream fails) or renamed.
bool WriteCacheFile(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_CACHE_FILE_H_
