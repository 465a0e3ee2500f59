// The seed model (examples/colmap/triplet_model.h) and the triplet CSV (triplet_csv.h) of a
// hand-made estimate.

#include "trigrav/colmap/triplet_model.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <sstream>
#include <stdexcept>
#include <string>

#include "trigrav/colmap/triplet_csv.h"

namespace trigrav {
namespace colmap {
namespace {

// Two cameras, images 7, 3, 5 (camera 2, 1, 2) with 4, 3, 5 keypoints, tracks of keypoints
// (0,0,0), (1,2,4), (3,1,2), of which the refinement kept the first and the third.
struct Fixture {
  std::vector<ColmapCamera> cameras;
  std::array<DatabaseImage, 3> images;
  std::array<std::vector<Eigen::Vector2d>, 3> keypoints;
  std::vector<ThreeViewTrack> tracks = {{0, 0, 0}, {1, 2, 4}, {3, 1, 2}};
  ThreeViewEstimate estimate;

  Fixture() {
    for (CameraId id : {1u, 2u}) {
      ColmapCamera& camera = cameras.emplace_back();
      camera.camera_id = id;
      camera.camera = Camera::FromColmap("PINHOLE", {500.0, 500.0, 320.0, 240.0});
      camera.width = 640;
      camera.height = 480;
    }
    images = {DatabaseImage{7, "a.png", 2}, DatabaseImage{3, "b.png", 1},
              DatabaseImage{5, "c.png", 2}};
    const int sizes[3] = {4, 3, 5};
    for (int k = 0; k < 3; ++k) {
      for (int i = 0; i < sizes[k]; ++i) keypoints[k].emplace_back(10.0 * i + k, 20.0);
    }
    estimate.success = true;
    estimate.num_inliers = 2;
    ThreeViewRefinement& refinement = estimate.refinement;
    refinement.summary.success = true;
    refinement.pose.cam2_from_cam1.R =
        Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()).toRotationMatrix();
    refinement.pose.cam2_from_cam1.t = Eigen::Vector3d(0.0, 0.0, -1.0);
    refinement.pose.cam3_from_cam1.t = Eigen::Vector3d(0.0, 0.0, -2.0);
    refinement.triplets = {0, 2};
    refinement.points_in_cam1 = {Eigen::Vector3d(1.0, 2.0, 10.0), Eigen::Vector3d(-1.0, 0.0, 8.0)};
    refinement.residual_norms = {Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(0.3, 0.3, 0.3)};
    refinement.covariance = Eigen::MatrixXd::Identity(11, 11) * 1e-6;
    estimate.refined = refinement.pose;
  }
};

TEST(TripletModelTest, EveryKeypointEveryCameraAndTheInlierPoints) {
  const Fixture f;
  const Reconstruction model = TripletModel(f.cameras, f.images, f.keypoints, f.tracks, f.estimate);
  EXPECT_NO_THROW(model.Check());
  EXPECT_EQ(model.cameras.size(), 2u);
  ASSERT_EQ(model.images.size(), 3u);
  const ColmapImage& first = model.images.at(7);
  EXPECT_EQ(first.name, "a.png");
  EXPECT_EQ(first.camera_id, 2u);
  EXPECT_TRUE(first.cam_from_world.R.isIdentity());
  EXPECT_TRUE(first.cam_from_world.t.isZero());
  EXPECT_TRUE(
      model.images.at(3).cam_from_world.R.isApprox(f.estimate.refinement.pose.cam2_from_cam1.R));
  EXPECT_TRUE(model.images.at(5).cam_from_world.t.isApprox(Eigen::Vector3d(0.0, 0.0, -2.0)));
  // All keypoints, in the database's order; a point id only on the kept tracks' keypoints.
  for (int k = 0; k < 3; ++k) {
    const ColmapImage& image = model.images.at(f.images[k].image_id);
    EXPECT_EQ(image.points2D, f.keypoints[k]);
    int with_point = 0;
    for (const Point3DId id : image.point3D_ids) with_point += id != kInvalidPoint3DId;
    EXPECT_EQ(with_point, 2);
  }
  EXPECT_EQ(model.images.at(5).point3D_ids[4], kInvalidPoint3DId);  // track 1, dropped
  ASSERT_EQ(model.points3D.size(), 2u);
  const ColmapPoint3D& second = model.points3D.at(2);
  EXPECT_TRUE(second.xyz.isApprox(Eigen::Vector3d(-1.0, 0.0, 8.0)));
  EXPECT_DOUBLE_EQ(second.error, 0.3);
  ASSERT_EQ(second.track.size(), 3u);
  EXPECT_EQ(second.track[1].image_id, 3u);
  EXPECT_EQ(second.track[1].point2D_idx, 1u);
  EXPECT_EQ(model.images.at(3).point3D_ids[1], 2u);
}

TEST(TripletModelTest, RejectsAFailedRefinementAndUnknownKeypoints) {
  Fixture f;
  std::vector<ThreeViewTrack> bad_tracks = f.tracks;
  bad_tracks[2][1] = 3;  // image 3 has 3 keypoints
  EXPECT_THROW(TripletModel(f.cameras, f.images, f.keypoints, bad_tracks, f.estimate),
               std::invalid_argument);
  f.images[1].camera_id = 9;
  EXPECT_THROW(TripletModel(f.cameras, f.images, f.keypoints, f.tracks, f.estimate),
               std::invalid_argument);
  f.images[1].camera_id = 1;
  f.estimate.refinement.summary.success = false;
  EXPECT_THROW(TripletModel(f.cameras, f.images, f.keypoints, f.tracks, f.estimate),
               std::invalid_argument);
}

TEST(TripletCsvTest, VerdictsAndOneFieldPerColumn) {
  Fixture f;
  TripletResult trusted{f.images, 3, true, f.estimate};
  EXPECT_EQ(TripletVerdict(trusted), "trusted");
  TripletResult no_covariance = trusted;
  no_covariance.estimate.refinement.covariance.resize(0, 0);
  no_covariance.estimate.message = "a note, with a comma and a \"quote\"";
  EXPECT_EQ(TripletVerdict(no_covariance), "no_covariance");
  TripletResult unrefined = trusted;
  unrefined.estimate.refinement.summary.success = false;
  EXPECT_EQ(TripletVerdict(unrefined), "unrefined");
  TripletResult failed = trusted;
  failed.estimate.success = false;
  EXPECT_EQ(TripletVerdict(failed), "failed");
  TripletResult few{f.images, 2, false, ThreeViewEstimate()};
  EXPECT_EQ(TripletVerdict(few), "too_few_tracks");

  std::istringstream in(
      FormatTripletCsv({trusted, no_covariance, few},
                       ThreeViewBundleAdjustmentOptions::RotationModel::kGravityPrior));
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != '#') rows.push_back(line);
  }
  ASSERT_EQ(rows.size(), 4u);
  // Fields outside quotes.
  const auto fields = [](const std::string& row) {
    int count = 1;
    bool quoted = false;
    for (const char c : row) {
      if (c == '"') quoted = !quoted;
      if (c == ',' && !quoted) ++count;
    }
    return count;
  };
  for (const std::string& row : rows) EXPECT_EQ(fields(row), fields(rows[0])) << row;
  EXPECT_EQ(rows[0].rfind("image_name1,image_name2,image_name3,", 0), 0u);
  EXPECT_NE(rows[1].find("a.png,b.png,c.png,7,3,5,3,trusted,1,2,"), std::string::npos);
  EXPECT_NE(rows[2].find(",\"a note, with a comma and a \"\"quote\"\"\""), std::string::npos);
  // The 11 x 11 covariance: 121 space-separated numbers in the trusted row.
  std::istringstream covariance(rows[1].substr(rows[1].rfind(',', rows[1].size() - 2) + 1));
  int numbers = 0;
  for (double value; covariance >> value;) ++numbers;
  EXPECT_EQ(numbers, 121);
}

}  // namespace
}  // namespace colmap
}  // namespace trigrav
