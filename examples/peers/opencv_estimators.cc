// OpenCV peers: cv::findEssentialMat (RANSAC, USAC_MAGSAC, USAC_DEFAULT) + cv::recoverPose on the
// pairs (1,2) and (1,3).

#include <cstdio>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "pairwise_estimator.h"
#include "peer_backends.h"

namespace trigrav::peers {
namespace {

// Normalised image coordinates (K^-1 [u v 1]^T without the 1) of one view's pixels.
std::vector<cv::Point2d> Normalized(const ThreeViewObservations& observations, int view) {
  std::vector<cv::Point2d> points;
  points.reserve(observations.size());
  for (std::size_t n = 0; n < observations.size(); ++n) {
    const Eigen::Vector3d ray = observations.Ray(view, n);
    points.emplace_back(ray.x(), ray.y());
  }
  return points;
}

// findEssentialMat + recoverPose on views 0 and `view`. The points go in normalised with an
// identity camera matrix and the threshold divided by the mean focal length of the two views: what
// findEssentialMat does itself with one camera matrix, and valid when the views' intrinsics differ.
PairEstimator OpenCvPair(int method) {
  return [method](const ThreeViewObservations& observations, int view, double threshold_px) {
    const Camera& camera1 = observations.cameras[0];
    const Camera& camera2 = observations.cameras[view];
    const std::vector<cv::Point2d> points1 = Normalized(observations, 0);
    const std::vector<cv::Point2d> points2 = Normalized(observations, view);
    const double focal_px =
        (camera1.FocalX() + camera1.FocalY() + camera2.FocalX() + camera2.FocalY()) / 4.0;
    PairEstimate pair;
    cv::Mat mask;
    const cv::Mat E =
        cv::findEssentialMat(points1, points2, cv::Mat::eye(3, 3, CV_64F), method, kPeerConfidence,
                             threshold_px / focal_px, kPeerMaxIterations, mask);
    if (E.rows < 3 || E.cols != 3 || mask.empty()) {
      pair.message = "findEssentialMat found no essential matrix";
      return pair;
    }
    // recoverPose narrows a copy of the mask to the points in front of both cameras; the pair's
    // inliers stay those of findEssentialMat.
    cv::Mat cheiral_mask = mask.clone();
    cv::Matx33d R;
    cv::Vec3d t;
    if (cv::recoverPose(E.rowRange(0, 3), points1, points2, cv::Mat::eye(3, 3, CV_64F), R, t,
                        cheiral_mask) == 0) {
      pair.message = "recoverPose: no inlier in front of both cameras";
      return pair;
    }
    pair.success = true;
    for (int r = 0; r < 3; ++r) {
      pair.cam_from_cam1.t(r) = t(r);
      for (int c = 0; c < 3; ++c) pair.cam_from_cam1.R(r, c) = R(r, c);
    }
    pair.inliers.assign(mask.ptr<unsigned char>(), mask.ptr<unsigned char>() + mask.total());
    return pair;
  };
}

// What every OpenCV entry shares.
std::string CommonNote() {
  char iterations[96];
  std::snprintf(iterations, sizeof(iterations), "confidence %g", kPeerConfidence);
  return std::string(iterations) +
         "; points normalised with an identity camera matrix and the threshold divided by the "
         "mean focal length (what findEssentialMat does with one camera matrix); cv::recoverPose "
         "(cheirality, distanceThresh 50) picks R, t; the pairs are combined with "
         "trigrav::CombineTwoViewPairs on their common inliers";
}

}  // namespace

void SetOpenCvThreads(int threads) { cv::setNumThreads(threads); }

std::vector<NamedEstimator> OpenCvEstimators() {
  const std::string usac_note =
      "inlier iff the symmetric epipolar distance (squared distances to the epipolar lines in both "
      "images, summed) <= threshold^2; the USAC path ignores maxIters (checked on OpenCV 4.6; its "
      "source caps USAC at 1000 iterations); ";
  return {
      {"opencv-ransac", "raw",
       "cv::findEssentialMat(cv::RANSAC) on pairs (1,2), (1,3): Nister 5-point, inlier iff the "
       "Sampson distance <= threshold, maxIters " +
           std::to_string(kPeerMaxIterations) + ", no refinement; " + CommonNote(),
       PairwiseEstimator(OpenCvPair(cv::RANSAC))},
      {"opencv-usac-magsac", "raw",
       "cv::findEssentialMat(cv::USAC_MAGSAC) on pairs (1,2), (1,3): Stewenius 5-point, MAGSAC++ "
       "score, sigma-consensus LO, final least-squares polish; " +
           usac_note + CommonNote(),
       PairwiseEstimator(OpenCvPair(cv::USAC_MAGSAC))},
      {"opencv-usac-default", "raw",
       "cv::findEssentialMat(cv::USAC_DEFAULT) on pairs (1,2), (1,3): Stewenius 5-point, MSAC "
       "score, SPRT, inner + iterative LO, final least-squares polish; " +
           usac_note + CommonNote(),
       PairwiseEstimator(OpenCvPair(cv::USAC_DEFAULT))},
  };
}

}  // namespace trigrav::peers
