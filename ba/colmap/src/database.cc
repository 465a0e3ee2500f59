// Read-only queries on COLMAP 3.8's database schema (https://colmap.github.io/database.html):
//   cameras(camera_id, model, width, height, params BLOB of doubles, prior_focal_length)
//   images(image_id, name, camera_id, prior_q*, prior_t*)
//   keypoints(image_id, rows, cols, data BLOB of float32, rows x cols, row-major)
//   two_view_geometries(pair_id, rows, cols, data BLOB of uint32, rows x 2, config, F, E, H, ...)
// with pair_id = 2147483647 image_id1 + image_id2, image_id1 < image_id2 (COLMAP's
// Database::ImagePairToPairId).
#include "trigrav/colmap/database.h"

#include <sqlite3.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>

#include "colmap_camera_models.h"
#include "file_io.h"

namespace trigrav {
namespace colmap {
namespace {

// COLMAP's kMaxNumImages: the factor of image_id1 in a pair id.
constexpr std::uint64_t kMaxNumImages = 2147483647;

// One prepared statement, finalised on destruction.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql, const std::string& path) : db_(db), path_(path) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &statement_, nullptr) != SQLITE_OK) {
      throw std::runtime_error(path + ": not a COLMAP database (" + sqlite3_errmsg(db) + ")");
    }
  }
  ~Statement() { sqlite3_finalize(statement_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  void Bind(int index, std::int64_t value) { sqlite3_bind_int64(statement_, index, value); }
  // The next row, or false when there is none.
  bool Step() {
    const int result = sqlite3_step(statement_);
    if (result == SQLITE_ROW) return true;
    if (result == SQLITE_DONE) return false;
    throw std::runtime_error(path_ + ": " + sqlite3_errmsg(db_));
  }
  std::int64_t Int(int column) const { return sqlite3_column_int64(statement_, column); }
  bool IsNull(int column) const { return sqlite3_column_type(statement_, column) == SQLITE_NULL; }
  std::string Text(int column) const {
    const unsigned char* text = sqlite3_column_text(statement_, column);
    return text == nullptr ? std::string()
                           : std::string(reinterpret_cast<const char*>(text),
                                         sqlite3_column_bytes(statement_, column));
  }
  // The blob as values of T (native byte order, as COLMAP writes them); throws unless it holds
  // exactly `count` values.
  template <typename T>
  std::vector<T> Blob(int column, std::int64_t count, const std::string& where) const {
    const void* data = sqlite3_column_blob(statement_, column);
    const std::int64_t bytes = sqlite3_column_bytes(statement_, column);
    const auto value_bytes = static_cast<std::int64_t>(sizeof(T));
    if (count < 0 || bytes % value_bytes != 0 || bytes / value_bytes != count) {
      throw std::runtime_error(where + ": blob of " + std::to_string(bytes) + " bytes, expected " +
                               std::to_string(count) + " values of " + std::to_string(sizeof(T)) +
                               " bytes");
    }
    std::vector<T> values(static_cast<std::size_t>(count));
    if (count > 0) std::memcpy(values.data(), data, static_cast<std::size_t>(bytes));
    return values;
  }

 private:
  sqlite3* db_;
  const std::string& path_;
  sqlite3_stmt* statement_ = nullptr;
};

std::uint32_t CheckedId(std::int64_t id, const std::string& what) {
  if (id < 0 || id > std::numeric_limits<std::uint32_t>::max()) {
    throw std::runtime_error(what + " " + std::to_string(id) + " is out of range");
  }
  return static_cast<std::uint32_t>(id);
}

// Throws unless the tables of a COLMAP database are there; an error of the first query means the
// file is not an SQLite database.
void CheckTables(sqlite3* db, const std::string& path) {
  sqlite3_stmt* tables = nullptr;
  if (sqlite3_prepare_v2(db, "SELECT name FROM sqlite_master WHERE type = 'table'", -1, &tables,
                         nullptr) != SQLITE_OK) {
    const std::string reason = sqlite3_errmsg(db);
    sqlite3_finalize(tables);
    throw std::runtime_error(path + ": not an SQLite database (" + reason + ")");
  }
  std::vector<std::string> missing = {"cameras", "images", "keypoints", "two_view_geometries"};
  int result;
  while ((result = sqlite3_step(tables)) == SQLITE_ROW) {
    const unsigned char* name = sqlite3_column_text(tables, 0);
    for (auto table = missing.begin(); name != nullptr && table != missing.end(); ++table) {
      if (*table == reinterpret_cast<const char*>(name)) {
        missing.erase(table);
        break;
      }
    }
  }
  sqlite3_finalize(tables);
  if (result != SQLITE_DONE) {
    throw std::runtime_error(path + ": not an SQLite database (" + sqlite3_errmsg(db) + ")");
  }
  if (!missing.empty()) {
    std::string list;
    for (const std::string& table : missing) list += (list.empty() ? "" : ", ") + table;
    throw std::runtime_error(path + ": not a COLMAP database (no table " + list + ")");
  }
}

// A row count of a blob, at most 2^31 - 1 (no overflow in rows x cols).
std::int64_t CheckedRows(std::int64_t rows, const std::string& where) {
  if (rows < 0 || rows > std::numeric_limits<std::int32_t>::max()) {
    throw std::runtime_error(where + ": rows " + std::to_string(rows) + " out of range");
  }
  return rows;
}

}  // namespace

struct Database::Impl {
  std::string path;
  sqlite3* db = nullptr;
};

Database::Database(const std::string& path) : impl_(new Impl) {
  impl_->path = path;
  if (!internal::FileExists(path)) throw std::runtime_error(path + ": no such file");
  if (sqlite3_open_v2(path.c_str(), &impl_->db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    const std::string reason = impl_->db ? sqlite3_errmsg(impl_->db) : "out of memory";
    sqlite3_close(impl_->db);
    throw std::runtime_error(path + ": cannot be opened (" + reason + ")");
  }
  try {
    CheckTables(impl_->db, path);
  } catch (...) {
    sqlite3_close(impl_->db);
    throw;
  }
}

Database::~Database() { sqlite3_close(impl_->db); }

std::vector<ColmapCamera> Database::ReadCameras() const {
  Statement statement(impl_->db,
                      "SELECT camera_id, model, width, height, params FROM cameras "
                      "ORDER BY camera_id",
                      impl_->path);
  std::vector<ColmapCamera> cameras;
  while (statement.Step()) {
    ColmapCamera camera;
    camera.camera_id = CheckedId(statement.Int(0), impl_->path + ": camera_id");
    const std::string where = impl_->path + ": camera " + std::to_string(camera.camera_id);
    const CameraModel model = internal::ModelOfColmapId(statement.Int(1), where);
    const std::int64_t width = statement.Int(2), height = statement.Int(3);
    if (width <= 0 || height <= 0 || width > std::numeric_limits<int>::max() ||
        height > std::numeric_limits<int>::max()) {
      throw std::runtime_error(where + ": width " + std::to_string(width) + " or height " +
                               std::to_string(height) + " out of range");
    }
    camera.width = static_cast<int>(width);
    camera.height = static_cast<int>(height);
    camera.camera = internal::CameraFromColmap(
        CameraModelName(model),
        statement.Blob<double>(4, NumCameraParams(model), where + " params"), where);
    cameras.push_back(camera);
  }
  return cameras;
}

std::vector<DatabaseImage> Database::ReadImages() const {
  // The last column is NULL when no camera row has the image's camera_id.
  Statement statement(impl_->db,
                      "SELECT images.image_id, images.name, images.camera_id, cameras.camera_id "
                      "FROM images LEFT JOIN cameras ON images.camera_id = cameras.camera_id "
                      "ORDER BY images.image_id",
                      impl_->path);
  std::vector<DatabaseImage> images;
  while (statement.Step()) {
    DatabaseImage image;
    image.image_id = CheckedId(statement.Int(0), impl_->path + ": image_id");
    const std::string where = impl_->path + ": image " + std::to_string(image.image_id);
    image.name = statement.Text(1);
    image.camera_id = CheckedId(statement.Int(2), where + " camera_id");
    if (statement.IsNull(3)) {
      throw std::runtime_error(where + " (" + image.name + "): camera_id " +
                               std::to_string(image.camera_id) + " has no camera row");
    }
    images.push_back(image);
  }
  return images;
}

std::vector<Eigen::Vector2d> Database::ReadKeypoints(ImageId image_id) const {
  const std::string where = impl_->path + ": keypoints of image " + std::to_string(image_id);
  Statement image(impl_->db, "SELECT 1 FROM images WHERE image_id = ?", impl_->path);
  image.Bind(1, image_id);
  if (!image.Step())
    throw std::runtime_error(impl_->path + ": no image " + std::to_string(image_id));
  Statement statement(impl_->db, "SELECT rows, cols, data FROM keypoints WHERE image_id = ?",
                      impl_->path);
  statement.Bind(1, image_id);
  std::vector<Eigen::Vector2d> keypoints;
  if (!statement.Step()) return keypoints;
  const std::int64_t rows = CheckedRows(statement.Int(0), where), cols = statement.Int(1);
  if ((cols != 2 && cols != 4 && cols != 6)) {
    throw std::runtime_error(where + ": " + std::to_string(rows) + " x " + std::to_string(cols) +
                             " (COLMAP stores 2, 4 or 6 columns)");
  }
  const std::vector<float> data = statement.Blob<float>(2, rows * cols, where);
  keypoints.reserve(static_cast<std::size_t>(rows));
  for (std::int64_t row = 0; row < rows; ++row) {
    const float x = data[row * cols], y = data[row * cols + 1];
    if (!std::isfinite(x) || !std::isfinite(y)) {
      throw std::runtime_error(where + ": row " + std::to_string(row) + " (" + std::to_string(x) +
                               ", " + std::to_string(y) + ") is not finite");
    }
    keypoints.emplace_back(x, y);
  }
  return keypoints;
}

std::vector<TwoViewGeometry> Database::ReadTwoViewGeometries() const {
  std::map<ImageId, std::int64_t> num_keypoints;
  {
    Statement images(impl_->db, "SELECT image_id FROM images", impl_->path);
    while (images.Step()) num_keypoints[CheckedId(images.Int(0), impl_->path + ": image_id")] = 0;
    Statement keypoints(impl_->db, "SELECT image_id, rows FROM keypoints", impl_->path);
    while (keypoints.Step()) {
      const auto image = num_keypoints.find(CheckedId(keypoints.Int(0), "keypoints image_id"));
      if (image != num_keypoints.end()) image->second = keypoints.Int(1);
    }
  }
  Statement statement(impl_->db,
                      "SELECT pair_id, rows, cols, data, config FROM two_view_geometries "
                      "WHERE rows > 0 ORDER BY pair_id",
                      impl_->path);
  std::vector<TwoViewGeometry> geometries;
  while (statement.Step()) {
    const std::int64_t pair_id = statement.Int(0);
    TwoViewGeometry geometry;
    std::string where = impl_->path + ": two_view_geometry of pair_id " + std::to_string(pair_id);
    if (pair_id < 0) throw std::runtime_error(where + ": negative pair_id");
    ImagesOfPairId(static_cast<std::uint64_t>(pair_id), &geometry.image_id1, &geometry.image_id2);
    where = impl_->path + ": two_view_geometry of images " + std::to_string(geometry.image_id1) +
            " and " + std::to_string(geometry.image_id2);
    const auto image1 = num_keypoints.find(geometry.image_id1);
    const auto image2 = num_keypoints.find(geometry.image_id2);
    if (geometry.image_id1 >= geometry.image_id2 ||
        PairId(geometry.image_id1, geometry.image_id2) != static_cast<std::uint64_t>(pair_id) ||
        image1 == num_keypoints.end() || image2 == num_keypoints.end()) {
      throw std::runtime_error(where + ": not a pair of distinct images of the database");
    }
    if (statement.Int(2) != 2) {
      throw std::runtime_error(where + ": " + std::to_string(statement.Int(2)) +
                               " columns (2 expected)");
    }
    const std::int64_t rows = CheckedRows(statement.Int(1), where);
    const std::vector<std::uint32_t> data = statement.Blob<std::uint32_t>(3, rows * 2, where);
    geometry.config = static_cast<int>(statement.Int(4));
    geometry.matches.resize(static_cast<std::size_t>(rows));
    for (std::int64_t row = 0; row < rows; ++row) {
      const std::uint32_t index1 = data[2 * row], index2 = data[2 * row + 1];
      if (index1 >= image1->second || index2 >= image2->second) {
        throw std::runtime_error(where + ": match " + std::to_string(row) + " (" +
                                 std::to_string(index1) + ", " + std::to_string(index2) +
                                 ") beyond the keypoints (" + std::to_string(image1->second) +
                                 ", " + std::to_string(image2->second) + ")");
      }
      geometry.matches[static_cast<std::size_t>(row)] = {index1, index2};
    }
    geometries.push_back(std::move(geometry));
  }
  return geometries;
}

std::uint64_t PairId(ImageId image_id1, ImageId image_id2) {
  if (image_id1 > image_id2) std::swap(image_id1, image_id2);
  return kMaxNumImages * image_id1 + image_id2;
}

void ImagesOfPairId(std::uint64_t pair_id, ImageId* image_id1, ImageId* image_id2) {
  *image_id2 = static_cast<ImageId>(pair_id % kMaxNumImages);
  *image_id1 = static_cast<ImageId>(pair_id / kMaxNumImages);
}

}  // namespace colmap
}  // namespace trigrav
