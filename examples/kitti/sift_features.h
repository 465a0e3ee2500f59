#ifndef TRIGRAV_EXAMPLES_KITTI_SIFT_FEATURES_H_
#define TRIGRAV_EXAMPLES_KITTI_SIFT_FEATURES_H_

// SIFT keypoints and descriptors of a frame (OpenCV's cv::SIFT, Lowe, IJCV 2004), with a per-frame
// cache file so that reruns skip detection.

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace trigrav::kitti {

// cv::SIFT::create parameters.
struct SiftOptions {
  int max_features = 0;  // keep the strongest n; 0 keeps all
  int octave_layers = 3;
  double contrast_threshold = 0.04;
  double edge_threshold = 10.0;
  double sigma = 1.6;

  // Part of the cache file name, so that other settings never read stale features, e.g.
  // "n0_l3_c0.04_e10_s1.6".
  std::string CacheTag() const;
};

struct FrameFeatures {
  std::vector<Eigen::Vector2f> pixels;  // sub-pixel keypoint positions (x right, y down)
  cv::Mat descriptors;                  // pixels.size() x 128, CV_8U (SIFT's values are 0..255)

  int size() const { return static_cast<int>(pixels.size()); }
};

FrameFeatures DetectSift(const cv::Mat& gray_image, const SiftOptions& options);

// Binary cache: a header (magic, version, image byte size, count) then the pixels and descriptors.
// Read returns false for a missing, truncated or foreign file or another image size; Write goes
// through a temporary file and a rename, so a reader never sees half a file.
bool ReadFeatureCache(const std::string& path, std::uintmax_t image_bytes, FrameFeatures* features);
bool WriteFeatureCache(const std::string& path,
                       std::uintmax_t image_bytes,
                       const FrameFeatures& features);

// Features of an image file: from cache_path when it holds a valid cache of this image, otherwise
// detected (and written to cache_path; an empty cache_path disables the cache). *detected tells
// which. Returns false with a message if the image cannot be read or the cache not written.
bool LoadOrDetectFeatures(const std::string& image_path,
                          const std::string& cache_path,
                          const SiftOptions& options,
                          FrameFeatures* features,
                          bool* detected,
                          std::string* error);

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_SIFT_FEATURES_H_
