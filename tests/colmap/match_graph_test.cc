// The three-view tracks and triplets of examples/colmap/match_graph.h on hand-made matches.

#include "trigrav/colmap/match_graph.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace trigrav {
namespace colmap {
namespace {

TwoViewGeometry Pair(ImageId a,
                     ImageId b,
                     const std::vector<std::array<std::uint32_t, 2>>& matches) {
  TwoViewGeometry geometry;
  geometry.image_id1 = a;
  geometry.image_id2 = b;
  geometry.config = 2;
  geometry.matches = matches;
  return geometry;
}

TEST(MatchGraphTest, DropsAmbiguousMatchesAndAnswersBothWays) {
  // Keypoint 3 of image 1 matched twice (to 10 and 11), keypoint 10 of image 2 twice (to 0 and 3),
  // keypoint 13 of image 2 twice: all their matches dropped; an exact repeat is no ambiguity.
  const MatchGraph graph(
      {Pair(1, 2, {{0, 10}, {3, 10}, {3, 11}, {4, 13}, {5, 13}, {6, 16}, {6, 16}})});
  EXPECT_EQ(graph.NumMatches(1, 2), 1);
  EXPECT_EQ(graph.NumMatches(2, 1), 1);
  EXPECT_EQ(graph.NumMatches(1, 3), 0);
  std::uint32_t keypoint = 0;
  ASSERT_TRUE(graph.Match(1, 6, 2, &keypoint));
  EXPECT_EQ(keypoint, 16u);
  ASSERT_TRUE(graph.Match(2, 16, 1, &keypoint));
  EXPECT_EQ(keypoint, 6u);
  EXPECT_FALSE(graph.Match(1, 0, 2, &keypoint));
  EXPECT_FALSE(graph.Match(1, 3, 2, &keypoint));
  EXPECT_FALSE(graph.Match(2, 13, 1, &keypoint));
  EXPECT_EQ(graph.Neighbors(2), std::vector<ImageId>({1}));
}

TEST(MatchGraphTest, PairsStoredWithTheLargerIdFirstAreSwapped) {
  const MatchGraph graph({Pair(5, 2, {{7, 1}})});
  std::uint32_t keypoint = 0;
  ASSERT_TRUE(graph.Match(2, 1, 5, &keypoint));
  EXPECT_EQ(keypoint, 7u);
  EXPECT_EQ(graph.Matches(5, 2), (std::vector<std::array<std::uint32_t, 2>>{{7, 1}}));
}

TEST(ThreeViewTracksTest, ChainsThroughTheHubAndDropsContradictedChains) {
  // Hub 2: 1-2 and 2-3 chain keypoints 0, 1, 2 of image 1; the pair 1-3 confirms 0 -> 20,
  // contradicts 1 -> 21 (matched to 29 instead) and says nothing about 2.
  const MatchGraph graph({Pair(1, 2, {{0, 10}, {1, 11}, {2, 12}, {5, 15}}),
                          Pair(2, 3, {{10, 20}, {11, 21}, {12, 22}}),
                          Pair(1, 3, {{0, 20}, {1, 29}})});
  EXPECT_EQ(ThreeViewTracks(graph, {1, 2, 3}),
            (std::vector<ThreeViewTrack>{{0, 10, 20}, {2, 12, 22}}));
  // The same tracks in the order of the images given.
  EXPECT_EQ(ThreeViewTracks(graph, {3, 1, 2}),
            (std::vector<ThreeViewTrack>{{20, 0, 10}, {22, 2, 12}}));
  // No image matched to both others: no track.
  EXPECT_TRUE(ThreeViewTracks(graph, {1, 2, 4}).empty());
}

TEST(ThreeViewTracksTest, AChainThroughTheTargetPairContradictingTheOtherWayIsDropped) {
  // Image 3's keypoint 20 is matched to image 1's keypoint 7, not 0: the chain 0-10-20 is dropped.
  const MatchGraph graph({Pair(1, 2, {{0, 10}}), Pair(2, 3, {{10, 20}}), Pair(1, 3, {{7, 20}})});
  EXPECT_TRUE(ThreeViewTracks(graph, {1, 2, 3}).empty());
}

TEST(TripletsTest, ConsecutiveTripletsOfASequence) {
  EXPECT_EQ(ConsecutiveTriplets({4, 2, 9, 7}),
            (std::vector<std::array<ImageId, 3>>{{4, 2, 9}, {2, 9, 7}}));
  EXPECT_TRUE(ConsecutiveTriplets({1, 2}).empty());
}

// n one-to-one matches 0..n-1 -> 0..n-1.
std::vector<std::array<std::uint32_t, 2>> Identity(std::uint32_t n) {
  std::vector<std::array<std::uint32_t, 2>> matches;
  for (std::uint32_t i = 0; i < n; ++i) matches.push_back({i, i});
  return matches;
}

TEST(TripletsTest, ConnectedTripletsGreedilyByTrackCountUntilEveryImageIsCovered) {
  // Tracks: (1,2,3) 30, (2,3,4) 20 (hub 3: min(2-3, 3-4)), (3,4,5) 10, (1,2,4) 20 (hub 2).
  const MatchGraph graph({Pair(1, 2, Identity(30)), Pair(2, 3, Identity(30)),
                          Pair(1, 3, Identity(30)), Pair(3, 4, Identity(20)),
                          Pair(2, 4, Identity(20)), Pair(4, 5, Identity(10))});
  EXPECT_EQ(ThreeViewTracks(graph, {1, 2, 3}).size(), 30u);
  EXPECT_EQ(ThreeViewTracks(graph, {3, 4, 5}).size(), 10u);
  // Name order 5, 4, 3, 2, 1 (the ids sorted by name): each triplet lists its images that way.
  // (1,2,3) first; then the best triplet with image 4, (1,2,4) or (2,3,4) or (1,3,4) with 20
  // tracks (ties go to the smaller ids); then one of (3,4,5) and (2,4,5), 10 tracks each, the
  // only ones with image 5.
  const std::vector<std::array<ImageId, 3>> triplets =
      ConnectedTriplets(graph, {5, 4, 3, 2, 1}, 10);
  ASSERT_EQ(triplets.size(), 3u);
  EXPECT_EQ(triplets[0], (std::array<ImageId, 3>{3, 2, 1}));
  EXPECT_EQ(triplets[2][0], 5u);
  EXPECT_EQ(ThreeViewTracks(graph, triplets[2]).size(), 10u);
  EXPECT_EQ(triplets[1][0], 4u);
  EXPECT_EQ(ThreeViewTracks(graph, triplets[1]).size(), 20u);
  // --max_triplets.
  EXPECT_EQ(ConnectedTriplets(graph, {5, 4, 3, 2, 1}, 1).size(), 1u);
}

}  // namespace
}  // namespace colmap
}  // namespace trigrav
