// trigrav::colmap::Database on databases made here with the sqlite3 C API: COLMAP 3.8's schema
// with known rows, read back field by field; then corrupt rows, a foreign SQLite database, a file
// that is not SQLite, a damaged SQLite file and a missing file, each with a clear error.
#include "trigrav/colmap/database.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <functional>

#include "colmap_schema.h"
#include "colmap_test_utils.h"

namespace trigrav {
namespace colmap {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;
using testing_utils::ReadBytes;
using testing_utils::ScratchFolder;
using testing_utils::WriteText;

// A writable SQLite database for building test fixtures; statements that fail abort the test.
class TestDatabase {
 public:
  explicit TestDatabase(const std::string& path) {
    EXPECT_EQ(sqlite3_open(path.c_str(), &db_), SQLITE_OK);
    Execute("PRAGMA synchronous = OFF");  // no fsync per insert: a scratch file
  }
  ~TestDatabase() { sqlite3_close(db_); }

  void Execute(const std::string& sql) {
    char* error = nullptr;
    EXPECT_EQ(sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK)
        << (error ? error : "") << " in " << sql;
    sqlite3_free(error);
  }
  // INSERT with the integer values and then one blob (a vector of T) as the last column.
  template <typename T>
  void InsertWithBlob(const std::string& sql,
                      const std::vector<std::int64_t>& integers,
                      const std::vector<T>& blob) {
    sqlite3_stmt* statement = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db_, sql.c_str(), -1, &statement, nullptr), SQLITE_OK) << sql;
    int index = 1;
    for (const std::int64_t value : integers) sqlite3_bind_int64(statement, index++, value);
    sqlite3_bind_blob(statement, index, blob.data(), static_cast<int>(blob.size() * sizeof(T)),
                      SQLITE_TRANSIENT);
    EXPECT_EQ(sqlite3_step(statement), SQLITE_DONE) << sqlite3_errmsg(db_);
    sqlite3_finalize(statement);
  }
  void AddCamera(std::int64_t camera_id, int model, const std::vector<double>& params) {
    InsertWithBlob(
        "INSERT INTO cameras (camera_id, model, width, height, prior_focal_length, "
        "params) VALUES (?, ?, 1241, 376, 1, ?)",
        {camera_id, model}, params);
  }
  void AddImage(std::int64_t image_id, const std::string& name, std::int64_t camera_id) {
    Execute("INSERT INTO images (image_id, name, camera_id) VALUES (" + std::to_string(image_id) +
            ", '" + name + "', " + std::to_string(camera_id) + ")");
  }
  void AddKeypoints(std::int64_t image_id, std::int64_t rows, std::int64_t cols) {
    std::vector<float> data(static_cast<std::size_t>(rows * cols));
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = 0.5f * static_cast<float>(i);
    InsertWithBlob("INSERT INTO keypoints (image_id, rows, cols, data) VALUES (?, ?, ?, ?)",
                   {image_id, rows, cols}, data);
  }
  void AddTwoViewGeometry(std::uint64_t pair_id,
                          const std::vector<std::uint32_t>& matches,
                          std::int64_t config) {
    InsertWithBlob(
        "INSERT INTO two_view_geometries (pair_id, rows, cols, config, data) "
        "VALUES (?, ?, 2, ?, ?)",
        {static_cast<std::int64_t>(pair_id), static_cast<std::int64_t>(matches.size() / 2), config},
        matches);
  }

 private:
  sqlite3* db_ = nullptr;
};

const std::vector<double> kKittiParams = {718.856, 718.856, 607.1928, 185.2157};

// Camera 1 (PINHOLE), images 1-3; keypoints 6 x 5 (image 1, COLMAP's affine rows), 4 x 2
// (image 2), none for image 3; verified pairs (1, 2) with two matches and (1, 3) with none.
std::string MakeDatabase(const std::string& folder) {
  const std::string path = folder + "/database.db";
  TestDatabase db(path);
  db.Execute(kColmapSchema);
  db.AddCamera(1, 1, kKittiParams);
  db.AddImage(1, "000000.png", 1);
  db.AddImage(2, "000001.png", 1);
  db.AddImage(3, "sub/000002.png", 1);
  db.AddKeypoints(1, 5, 6);
  db.AddKeypoints(2, 4, 2);
  db.AddTwoViewGeometry(PairId(1, 2), {0, 3, 4, 1}, 2);
  db.AddTwoViewGeometry(PairId(1, 3), {}, 1);
  return path;
}

TEST(Database, PairIdsAreColmaps) {
  EXPECT_EQ(PairId(1, 2), 2147483647ull + 2);
  EXPECT_EQ(PairId(2, 1), PairId(1, 2));
  EXPECT_EQ(PairId(7, 2147483646), 7ull * 2147483647ull + 2147483646ull);
  ImageId image_id1 = 0, image_id2 = 0;
  ImagesOfPairId(PairId(7, 2147483646), &image_id1, &image_id2);
  EXPECT_EQ(image_id1, 7u);
  EXPECT_EQ(image_id2, 2147483646u);
}

TEST(Database, ReadsEveryTable) {
  const Database db(MakeDatabase(ScratchFolder()));
  const std::vector<ColmapCamera> cameras = db.ReadCameras();
  ASSERT_EQ(cameras.size(), 1u);
  EXPECT_EQ(cameras[0].camera_id, 1u);
  EXPECT_EQ(cameras[0].camera.model, CameraModel::kPinhole);
  EXPECT_EQ(
      std::vector<double>(cameras[0].camera.params.begin(), cameras[0].camera.params.begin() + 4),
      kKittiParams);
  EXPECT_EQ(cameras[0].width, 1241);
  EXPECT_EQ(cameras[0].height, 376);

  const std::vector<DatabaseImage> images = db.ReadImages();
  ASSERT_EQ(images.size(), 3u);
  EXPECT_EQ(images[2].image_id, 3u);
  EXPECT_EQ(images[2].name, "sub/000002.png");
  EXPECT_EQ(images[2].camera_id, 1u);

  // Rows of 6 floats 0, 0.5, 1, ...: the positions are the first two of each row.
  const std::vector<Eigen::Vector2d> keypoints1 = db.ReadKeypoints(1);
  ASSERT_EQ(keypoints1.size(), 5u);
  EXPECT_EQ(keypoints1[2], Eigen::Vector2d(6.0, 6.5));
  const std::vector<Eigen::Vector2d> keypoints2 = db.ReadKeypoints(2);
  ASSERT_EQ(keypoints2.size(), 4u);
  EXPECT_EQ(keypoints2[3], Eigen::Vector2d(3.0, 3.5));
  EXPECT_TRUE(db.ReadKeypoints(3).empty());
  EXPECT_THAT([&] { db.ReadKeypoints(4); },
              ThrowsMessage<std::runtime_error>(HasSubstr("database.db: no image 4")));

  const std::vector<TwoViewGeometry> geometries = db.ReadTwoViewGeometries();
  ASSERT_EQ(geometries.size(), 1u);  // the pair without inliers is left out
  EXPECT_EQ(geometries[0].image_id1, 1u);
  EXPECT_EQ(geometries[0].image_id2, 2u);
  EXPECT_EQ(geometries[0].config, 2);
  ASSERT_EQ(geometries[0].matches.size(), 2u);
  EXPECT_EQ(geometries[0].matches[0], (std::array<std::uint32_t, 2>{0, 3}));
  EXPECT_EQ(geometries[0].matches[1], (std::array<std::uint32_t, 2>{4, 1}));
}

TEST(Database, BadRowsAreNamed) {
  struct Case {
    std::function<void(TestDatabase*)> spoil;
    std::function<void(const Database&)> read;
    std::string message;
  };
  const auto cameras = [](const Database& db) { db.ReadCameras(); };
  const auto geometries = [](const Database& db) { db.ReadTwoViewGeometries(); };
  const std::vector<Case> cases = {
      {[](TestDatabase* db) { db->AddCamera(2, 6, std::vector<double>(12, 1.0)); }, cameras,
       "camera 2: COLMAP camera model FULL_OPENCV (id 6) is not supported"},
      {[](TestDatabase* db) {
         db->AddCamera(2, 7, {1, 1, 1, 1, 1});
       },
       cameras, "FOV (id 7)"},
      {[](TestDatabase* db) {
         db->AddCamera(2, 1, {700, 700, 600});
       },
       cameras, "camera 2 params: blob of 24 bytes, expected 4 values of 8 bytes"},
      {[](TestDatabase* db) {
         db->AddCamera(2, 0, {NAN, 600, 180});
       },
       cameras, "camera 2: trigrav: Camera: SIMPLE_PINHOLE parameter 0 is not finite"},
      {[](TestDatabase* db) { db->Execute("UPDATE cameras SET width = 0"); }, cameras,
       "camera 1: width 0 or height 376 out of range"},
      {[](TestDatabase* db) {
         db->AddTwoViewGeometry(PairId(2, 3), {0, 0}, 2);
       },
       geometries,
       "two_view_geometry of images 2 and 3: match 0 (0, 0) beyond the keypoints (4, 0)"},
      {[](TestDatabase* db) {
         db->Execute("DELETE FROM two_view_geometries");
         db->AddTwoViewGeometry(PairId(1, 2), {0, 3, 0, 4}, 2);
       },
       geometries, "images 1 and 2: match 1 (0, 4) beyond the keypoints (5, 4)"},
      {[](TestDatabase* db) {
         db->AddTwoViewGeometry(PairId(1, 9), {0, 0}, 2);
       },
       geometries, "images 1 and 9: not a pair of distinct images of the database"},
      {[](TestDatabase* db) {
         db->AddTwoViewGeometry(PairId(2, 2), {0, 0}, 2);
       },
       geometries, "not a pair of distinct images"},
      {[](TestDatabase* db) { db->Execute("UPDATE two_view_geometries SET rows = 3"); }, geometries,
       "blob of 16 bytes, expected 6 values of 4 bytes"},
      {[](TestDatabase* db) { db->Execute("UPDATE two_view_geometries SET cols = 3"); }, geometries,
       "3 columns (2 expected)"},
      {[](TestDatabase* db) { db->Execute("UPDATE keypoints SET cols = 3"); },
       [](const Database& db) { db.ReadKeypoints(1); }, "(COLMAP stores 2, 4 or 6 columns)"},
      {[](TestDatabase* db) { db->Execute("UPDATE keypoints SET rows = 6 WHERE image_id = 1"); },
       [](const Database& db) { db.ReadKeypoints(1); },
       "keypoints of image 1: blob of 120 bytes, expected 36 values"},
      {[](TestDatabase* db) { db->Execute("UPDATE keypoints SET rows = -1 WHERE image_id = 1"); },
       [](const Database& db) { db.ReadKeypoints(1); }, "rows -1 out of range"},
      {[](TestDatabase* db) {
         std::vector<float> rows = {1, 2, 3, 4, 5, NAN};  // row 2's y
         db->InsertWithBlob<float>(
             "INSERT INTO keypoints (image_id, rows, cols, data) VALUES (?, 3, 2, ?)", {3}, rows);
       },
       [](const Database& db) { db.ReadKeypoints(3); },
       "keypoints of image 3: row 2 (5.000000, nan) is not finite"},
      {[](TestDatabase* db) { db->AddImage(4, "000003.png", 2); },
       [](const Database& db) { db.ReadImages(); },
       "image 4 (000003.png): camera_id 2 has no camera row"},
  };
  for (const Case& bad : cases) {
    const std::string path = MakeDatabase(ScratchFolder());
    {
      TestDatabase db(path);
      bad.spoil(&db);
    }
    const Database db(path);
    EXPECT_THAT([&] { bad.read(db); }, ThrowsMessage<std::runtime_error>(HasSubstr(bad.message)));
  }
}

TEST(Database, ForeignAndCorruptFilesAreRejected) {
  const std::string folder = ScratchFolder();
  EXPECT_THAT([&] { Database db(folder + "/missing.db"); },
              ThrowsMessage<std::runtime_error>(HasSubstr("missing.db: no such file")));

  const std::string foreign = folder + "/foreign.db";
  {
    TestDatabase db(foreign);
    db.Execute("CREATE TABLE images (id INTEGER, path TEXT); CREATE TABLE cameras (id INTEGER);");
  }
  EXPECT_THAT([&] { Database db(foreign); },
              ThrowsMessage<std::runtime_error>(HasSubstr(
                  "foreign.db: not a COLMAP database (no table keypoints, two_view_geometries)")));
  // The tables are there, their columns are not COLMAP's.
  {
    TestDatabase db(foreign);
    db.Execute("CREATE TABLE keypoints (id INTEGER); CREATE TABLE two_view_geometries (id);");
  }
  const Database wrong_columns(foreign);
  EXPECT_THAT(
      [&] { wrong_columns.ReadCameras(); },
      ThrowsMessage<std::runtime_error>(HasSubstr("not a COLMAP database (no such column")));

  const std::string text = folder + "/text.db";
  WriteText(text, std::string(5000, 'x'));
  EXPECT_THAT([&] { Database db(text); },
              ThrowsMessage<std::runtime_error>(HasSubstr("text.db: not an SQLite database")));

  // A real database cut after its first page (the schema): the tables' pages are gone.
  const std::string database = MakeDatabase(folder);
  const std::string bytes = ReadBytes(database);
  ASSERT_GT(bytes.size(), 8192u);
  const std::string cut = folder + "/cut.db";
  WriteText(cut, bytes.substr(0, 4096));
  EXPECT_THROW(
      {
        Database db(cut);
        db.ReadCameras();
        db.ReadImages();
        db.ReadKeypoints(1);
        db.ReadTwoViewGeometries();
      },
      std::runtime_error);
  // Garbage over everything after the header.
  std::string damaged = bytes;
  for (std::size_t i = 100; i < damaged.size(); ++i) damaged[i] = static_cast<char>(i * 7919);
  WriteText(cut, damaged);
  EXPECT_THROW(
      {
        Database db(cut);
        db.ReadCameras();
        db.ReadImages();
        db.ReadKeypoints(1);
        db.ReadTwoViewGeometries();
      },
      std::runtime_error);
}

}  // namespace
}  // namespace colmap
}  // namespace trigrav
