#ifndef TRIGRAV_COLMAP_MATCH_GRAPH_H_
#define TRIGRAV_COLMAP_MATCH_GRAPH_H_

// The verified pairwise matches of a COLMAP database (two_view_geometries,
// Database::ReadTwoViewGeometries) as a graph over the images, the three-view tracks chained from
// them, and the choice of triplets: the input side of a triplet initialisation (what the tool
// examples/colmap/triplet_initializer runs). Images are database image ids, keypoints indices into
// Database::ReadKeypoints of their image. Pure functions of their arguments: nothing is read,
// written or printed; nothing throws but std::invalid_argument where stated (and std::bad_alloc).

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "trigrav/colmap/database.h"

namespace trigrav {
namespace colmap {

// The one-to-one matches of one image pair: a keypoint in more than one match of the pair, on
// either side (an ambiguous match, which COLMAP's verification can leave), is dropped with all its
// matches.
struct PairMatches {
  // (keypoint of the pair's first image, keypoint of its second), sorted by the first; and the
  // same matches sorted by the second.
  std::vector<std::array<std::uint32_t, 2>> by_first;
  std::vector<std::array<std::uint32_t, 2>> by_second;
};

class MatchGraph {
 public:
  explicit MatchGraph(const std::vector<TwoViewGeometry>& geometries);

  // One-to-one matches of the pair (0 when the pair has none).
  int NumMatches(ImageId a, ImageId b) const;
  // The keypoint of image b matched to keypoint `keypoint_a` of image a; false if there is none.
  bool Match(ImageId a, std::uint32_t keypoint_a, ImageId b, std::uint32_t* keypoint_b) const;
  // The matches of the pair as (keypoint of a, keypoint of b), sorted by a's keypoint.
  std::vector<std::array<std::uint32_t, 2>> Matches(ImageId a, ImageId b) const;
  // Images with at least one match to `image`, in increasing id order.
  const std::vector<ImageId>& Neighbors(ImageId image) const;

 private:
  const PairMatches* Find(ImageId a, ImageId b) const;

  std::map<std::pair<ImageId, ImageId>, PairMatches> pairs_;  // keyed (smaller id, larger id)
  std::map<ImageId, std::vector<ImageId>> neighbors_;
};

// Keypoint indices of one three-view track in the triplet's images 1, 2, 3 (the order of the
// triplet's image ids).
using ThreeViewTrack = std::array<std::uint32_t, 3>;

// Three-view tracks of the images (in that order): a keypoint of the hub image h matched to
// keypoint x of one other image and to keypoint y of the third, the hub being the image matched to
// both others (the one whose smaller pair has the most matches when several are). If the two others
// are matched to each other too, a chain is kept only when that pair does not contradict it (x
// matched to a keypoint other than y, or y to one other than x). Sorted; empty when no image is
// matched to both others.
std::vector<ThreeViewTrack> ThreeViewTracks(const MatchGraph& graph,
                                            const std::array<ImageId, 3>& images);

// Triplets of consecutive images of `images_by_name` (sorted by name, as the frames of a
// sequence): (i, i+1, i+2) for every i.
std::vector<std::array<ImageId, 3>> ConsecutiveTriplets(const std::vector<ImageId>& images_by_name);

// The best-connected triplets, greedily: candidate triplets are those with an image matched to
// both others; in decreasing order of their three-view track count (ThreeViewTracks), a triplet is
// taken when it contains an image no taken triplet contains, until every image of a candidate is
// in one or `max_triplets` (> 0) are taken; equal counts go to the smaller image ids. Each triplet
// lists its images in the order of `images_by_name`; images not in `images_by_name` are left out.
// Throws std::invalid_argument if max_triplets < 1.
std::vector<std::array<ImageId, 3>> ConnectedTriplets(const MatchGraph& graph,
                                                      const std::vector<ImageId>& images_by_name,
                                                      int max_triplets);

}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_MATCH_GRAPH_H_
