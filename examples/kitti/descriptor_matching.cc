#include "descriptor_matching.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "cache_file.h"

namespace trigrav::kitti {
namespace {

constexpr int kDescriptorSize = 128;
constexpr float kCellPx = 32.0f;

constexpr char kMagic[8] = {'T', 'G', 'M', 'A', 'T', 'C', 'H', '2'};

struct MatchCacheHeader {
  char magic[8];
  std::int64_t a_count;
  std::int64_t b_count;
  std::uint64_t pixels_hash;
};

// FNV-1a over the bytes of both frames' pixels.
std::uint64_t PixelsHash(const FrameFeatures& a, const FrameFeatures& b) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const FrameFeatures* frame : {&a, &b}) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(frame->pixels.data());
    const std::size_t size = frame->pixels.size() * sizeof(Eigen::Vector2f);
    for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
  }
  return hash;
}

MatchCacheHeader HeaderOf(const FrameFeatures& a, const FrameFeatures& b) {
  MatchCacheHeader header;
  std::memcpy(header.magic, kMagic, sizeof(kMagic));
  header.a_count = a.size();
  header.b_count = b.size();
  header.pixels_hash = PixelsHash(a, b);
  return header;
}

// Squared Euclidean distance of two 128-byte SIFT descriptors (vectorised by the compiler).
inline int SquaredDistance(const std::uint8_t* a, const std::uint8_t* b) {
  int sum = 0;
  for (int i = 0; i < kDescriptorSize; ++i) {
    const int d = static_cast<int>(a[i]) - static_cast<int>(b[i]);
    sum += d * d;
  }
  return sum;
}

// The two smallest distances seen so far and the index of the smallest.
struct BestTwo {
  int best = std::numeric_limits<int>::max();
  int second = std::numeric_limits<int>::max();
  int index = -1;

  void Offer(int distance, int i) {
    if (distance < best) {
      second = best;
      best = distance;
      index = i;
    } else if (distance < second) {
      second = distance;
    }
  }
  // best < ratio * second on distances, i.e. best^2 < ratio^2 second^2 on squared ones.
  bool PassesRatio(double squared_ratio) const {
    return index >= 0 && (second == std::numeric_limits<int>::max() ||
                          static_cast<double>(best) < squared_ratio * second);
  }
};

// Features of a frame bucketed into square cells, for window queries.
class CellGrid {
 public:
  explicit CellGrid(const FrameFeatures& features) {
    for (const Eigen::Vector2f& p : features.pixels) {
      columns_ = std::max(columns_, Cell(p.x()) + 1);
      rows_ = std::max(rows_, Cell(p.y()) + 1);
    }
    start_.assign(static_cast<std::size_t>(rows_) * columns_ + 1, 0);
    for (const Eigen::Vector2f& p : features.pixels) ++start_[Index(p) + 1];
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    members_.resize(features.pixels.size());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (int i = 0; i < features.size(); ++i) members_[fill[Index(features.pixels[i])]++] = i;
  }

  // Calls visit(j) for every feature j in the cells overlapping [x0, x1] x [y0, y1].
  template <typename Visit>
  void ForEachInBox(float x0, float x1, float y0, float y1, Visit visit) const {
    const int c0 = std::max(0, Cell(x0)), c1 = std::min(columns_ - 1, Cell(x1));
    const int r0 = std::max(0, Cell(y0)), r1 = std::min(rows_ - 1, Cell(y1));
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) {
        const std::size_t cell = static_cast<std::size_t>(r) * columns_ + c;
        for (int k = start_[cell]; k < start_[cell + 1]; ++k) visit(members_[k]);
      }
    }
  }

 private:
  static int Cell(float coordinate) {
    return static_cast<int>(std::floor(std::max(coordinate, 0.0f) / kCellPx));
  }
  std::size_t Index(const Eigen::Vector2f& p) const {
    return static_cast<std::size_t>(Cell(p.y())) * columns_ + Cell(p.x());
  }

  int columns_ = 0, rows_ = 0;
  std::vector<int> start_;    // members_ of cell c: [start_[c], start_[c + 1])
  std::vector<int> members_;  // feature indices sorted by cell
};

}  // namespace

std::string MatchOptions::CacheTag() const {
  std::ostringstream tag;
  tag << "r" << ratio << "_x" << window_x_px << "_y" << window_y_px << "_m" << mutual;
  return tag.str();
}

std::vector<int> MatchFeatures(const FrameFeatures& a,
                               const FrameFeatures& b,
                               const MatchOptions& options) {
  std::vector<BestTwo> best_in_b(a.size()), best_in_a(b.size());
  const CellGrid grid(b);
  const float wx = static_cast<float>(options.window_x_px);
  const float wy = static_cast<float>(options.window_y_px);
  for (int i = 0; i < a.size(); ++i) {
    const Eigen::Vector2f& p = a.pixels[i];
    const std::uint8_t* descriptor = a.descriptors.ptr<std::uint8_t>(i);
    grid.ForEachInBox(p.x() - wx, p.x() + wx, p.y() - wy, p.y() + wy, [&](int j) {
      const Eigen::Vector2f d = b.pixels[j] - p;
      if (std::abs(d.x()) > wx || std::abs(d.y()) > wy) return;
      const int distance = SquaredDistance(descriptor, b.descriptors.ptr<std::uint8_t>(j));
      best_in_b[i].Offer(distance, j);
      best_in_a[j].Offer(distance, i);
    });
  }
  const double squared_ratio = options.ratio * options.ratio;
  std::vector<int> b_index_of_a(a.size(), -1);
  for (int i = 0; i < a.size(); ++i) {
    const BestTwo& forward = best_in_b[i];
    if (!forward.PassesRatio(squared_ratio)) continue;
    if (options.mutual && best_in_a[forward.index].index != i) continue;
    b_index_of_a[i] = forward.index;
  }
  return b_index_of_a;
}

bool ReadMatchCache(const std::string& path,
                    const FrameFeatures& a,
                    const FrameFeatures& b,
                    std::vector<int>* b_index_of_a) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return false;
  MatchCacheHeader header;
  const MatchCacheHeader expected = HeaderOf(a, b);
  if (!file.read(reinterpret_cast<char*>(&header), sizeof(header)) ||
      std::memcmp(&header, &expected, sizeof(header)) != 0) {
    return false;
  }
  std::vector<std::int32_t> stored(static_cast<std::size_t>(a.size()));
  if (!file.read(reinterpret_cast<char*>(stored.data()),
                 static_cast<std::streamsize>(stored.size() * sizeof(std::int32_t))) ||
      file.peek() != std::ifstream::traits_type::eof()) {
    return false;
  }
  if (std::any_of(stored.begin(), stored.end(),
                  [&](std::int32_t j) { return j < -1 || j >= b.size(); })) {
    return false;
  }
  b_index_of_a->assign(stored.begin(), stored.end());
  return true;
}

bool WriteMatchCache(const std::string& path,
                     const FrameFeatures& a,
                     const FrameFeatures& b,
                     const std::vector<int>& b_index_of_a) {
  const MatchCacheHeader header = HeaderOf(a, b);
  const std::vector<std::int32_t> stored(b_index_of_a.begin(), b_index_of_a.end());
  return WriteCacheFile(path, [&](std::ostream& file) {
    file.write(reinterpret_cast<const char*>(&header), sizeof(header));
    file.write(reinterpret_cast<const char*>(stored.data()),
               static_cast<std::streamsize>(stored.size() * sizeof(std::int32_t)));
  });
}

bool LoadOrMatchFeatures(const FrameFeatures& a,
                         const FrameFeatures& b,
                         const MatchOptions& options,
                         const std::string& cache_path,
                         std::vector<int>* b_index_of_a,
                         std::string* error) {
  if (!cache_path.empty() && ReadMatchCache(cache_path, a, b, b_index_of_a)) {
    return true;
  }
  *b_index_of_a = MatchFeatures(a, b, options);
  if (!cache_path.empty() && !WriteMatchCache(cache_path, a, b, *b_index_of_a)) {
    *error = "cannot write the match cache " + cache_path;
    return false;
  }
  return true;
}

}  // namespace trigrav::kitti
