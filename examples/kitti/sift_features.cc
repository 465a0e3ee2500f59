#include "sift_features.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "cache_file.h"

namespace trigrav::kitti {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'T', 'G', 'S', 'I', 'F', 'T', '0', '1'};
constexpr int kDescriptorSize = 128;

struct CacheHeader {
  char magic[8];
  std::uint64_t image_bytes;
  std::uint64_t count;
};

}  // namespace

std::string SiftOptions::CacheTag() const {
  std::ostringstream tag;
  tag << "n" << max_features << "_l" << octave_layers << "_c" << contrast_threshold << "_e"
      << edge_threshold << "_s" << sigma;
  return tag.str();
}

FrameFeatures DetectSift(const cv::Mat& gray_image, const SiftOptions& options) {
  cv::Ptr<cv::SIFT> sift =
      cv::SIFT::create(options.max_features, options.octave_layers, options.contrast_threshold,
                       options.edge_threshold, options.sigma, CV_8U);
  std::vector<cv::KeyPoint> keypoints;
  FrameFeatures features;
  sift->detectAndCompute(gray_image, cv::noArray(), keypoints, features.descriptors);
  features.pixels.reserve(keypoints.size());
  for (const cv::KeyPoint& keypoint : keypoints) {
    features.pixels.emplace_back(keypoint.pt.x, keypoint.pt.y);
  }
  return features;
}

bool ReadFeatureCache(const std::string& path,
                      std::uintmax_t image_bytes,
                      FrameFeatures* features) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return false;
  CacheHeader header;
  if (!file.read(reinterpret_cast<char*>(&header), sizeof(header)) ||
      std::memcmp(header.magic, kMagic, sizeof(kMagic)) != 0 || header.image_bytes != image_bytes ||
      header.count > (1u << 24)) {
    return false;
  }
  const int n = static_cast<int>(header.count);
  features->pixels.resize(n);
  features->descriptors.create(n, kDescriptorSize, CV_8U);
  return static_cast<bool>(file.read(reinterpret_cast<char*>(features->pixels.data()),
                                     static_cast<std::streamsize>(n * sizeof(Eigen::Vector2f)))) &&
         static_cast<bool>(file.read(reinterpret_cast<char*>(features->descriptors.data),
                                     static_cast<std::streamsize>(n) * kDescriptorSize)) &&
         file.peek() == std::ifstream::traits_type::eof();
}

bool WriteFeatureCache(const std::string& path,
                       std::uintmax_t image_bytes,
                       const FrameFeatures& features) {
  CacheHeader header;
  std::memcpy(header.magic, kMagic, sizeof(kMagic));
  header.image_bytes = image_bytes;
  header.count = static_cast<std::uint64_t>(features.size());
  return WriteCacheFile(path, [&](std::ostream& file) {
    const cv::Mat descriptors =
        features.descriptors.isContinuous() ? features.descriptors : features.descriptors.clone();
    file.write(reinterpret_cast<const char*>(&header), sizeof(header));
    file.write(reinterpret_cast<const char*>(features.pixels.data()),
               static_cast<std::streamsize>(features.pixels.size() * sizeof(Eigen::Vector2f)));
    file.write(reinterpret_cast<const char*>(descriptors.data),
               static_cast<std::streamsize>(features.size()) * kDescriptorSize);
  });
}

bool LoadOrDetectFeatures(const std::string& image_path,
                          const std::string& cache_path,
                          const SiftOptions& options,
                          FrameFeatures* features,
                          bool* detected,
                          std::string* error) {
  std::error_code ec;
  const std::uintmax_t image_bytes = fs::file_size(image_path, ec);
  if (ec) {
    *error = "cannot read " + image_path;
    return false;
  }
  *detected = false;
  if (!cache_path.empty() && ReadFeatureCache(cache_path, image_bytes, features)) return true;
  const cv::Mat image = cv::imread(image_path, cv::IMREAD_GRAYSCALE);
  if (image.empty()) {
    *error = "cannot decode " + image_path;
    return false;
  }
  *features = DetectSift(image, options);
  *detected = true;
  if (!cache_path.empty() && !WriteFeatureCache(cache_path, image_bytes, *features)) {
    *error = "cannot write the feature cache " + cache_path;
    return false;
  }
  return true;
}

}  // namespace trigrav::kitti
