#include "trigrav/colmap/match_graph.h"

#include <algorithm>
#include <queue>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>

namespace trigrav {
namespace colmap {
namespace {

using KeypointMatch = std::array<std::uint32_t, 2>;

PairMatches OneToOne(std::vector<KeypointMatch> matches) {
  const auto by = [](int side) {
    return [side](const KeypointMatch& a, const KeypointMatch& b) {
      return std::tie(a[side], a[1 - side]) < std::tie(b[side], b[1 - side]);
    };
  };
  std::sort(matches.begin(), matches.end(), by(0));
  matches.erase(std::unique(matches.begin(), matches.end()), matches.end());
  // Keypoints in more than one match, on either side, counted over all matches of the pair.
  std::array<std::map<std::uint32_t, int>, 2> count;
  for (const KeypointMatch& match : matches) {
    ++count[0][match[0]];
    ++count[1][match[1]];
  }
  matches.erase(std::remove_if(matches.begin(), matches.end(),
                               [&count](const KeypointMatch& match) {
                                 return count[0][match[0]] > 1 || count[1][match[1]] > 1;
                               }),
                matches.end());
  PairMatches pair;
  pair.by_first = matches;
  std::sort(matches.begin(), matches.end(), by(1));
  pair.by_second = std::move(matches);
  return pair;
}

// The match of `keypoint` on side `side` in `matches` (sorted by that side); false if none.
bool Lookup(const std::vector<KeypointMatch>& matches,
            int side,
            std::uint32_t keypoint,
            std::uint32_t* other) {
  const auto it = std::lower_bound(
      matches.begin(), matches.end(), keypoint,
      [side](const KeypointMatch& match, std::uint32_t value) { return match[side] < value; });
  if (it == matches.end() || (*it)[side] != keypoint) return false;
  *other = (*it)[1 - side];
  return true;
}

// The hub of a triplet (index 0-2) and the smaller match count of its two pairs; -1 if no image is
// matched to both others.
std::pair<int, int> Hub(const MatchGraph& graph, const std::array<ImageId, 3>& images) {
  int hub = -1, best = 0;
  for (int h = 0; h < 3; ++h) {
    const int smaller = std::min(graph.NumMatches(images[h], images[(h + 1) % 3]),
                                 graph.NumMatches(images[h], images[(h + 2) % 3]));
    if (smaller > best) {
      hub = h;
      best = smaller;
    }
  }
  return {hub, best};
}

}  // namespace

MatchGraph::MatchGraph(const std::vector<TwoViewGeometry>& geometries) {
  for (const TwoViewGeometry& geometry : geometries) {
    if (geometry.image_id1 == geometry.image_id2) continue;
    const bool swap = geometry.image_id1 > geometry.image_id2;
    std::vector<KeypointMatch> matches = geometry.matches;
    if (swap) {
      for (KeypointMatch& match : matches) std::swap(match[0], match[1]);
    }
    PairMatches pair = OneToOne(std::move(matches));
    if (pair.by_first.empty()) continue;
    const ImageId a = std::min(geometry.image_id1, geometry.image_id2);
    const ImageId b = std::max(geometry.image_id1, geometry.image_id2);
    pairs_[{a, b}] = std::move(pair);
    neighbors_[a].push_back(b);
    neighbors_[b].push_back(a);
  }
  for (auto& [image, neighbors] : neighbors_) {
    std::sort(neighbors.begin(), neighbors.end());
    neighbors.erase(std::unique(neighbors.begin(), neighbors.end()), neighbors.end());
  }
}

const PairMatches* MatchGraph::Find(ImageId a, ImageId b) const {
  const auto it = pairs_.find({std::min(a, b), std::max(a, b)});
  return it == pairs_.end() ? nullptr : &it->second;
}

int MatchGraph::NumMatches(ImageId a, ImageId b) const {
  const PairMatches* pair = Find(a, b);
  return pair == nullptr ? 0 : static_cast<int>(pair->by_first.size());
}

bool MatchGraph::Match(ImageId a,
                       std::uint32_t keypoint_a,
                       ImageId b,
                       std::uint32_t* keypoint_b) const {
  const PairMatches* pair = Find(a, b);
  if (pair == nullptr) return false;
  return a < b ? Lookup(pair->by_first, 0, keypoint_a, keypoint_b)
               : Lookup(pair->by_second, 1, keypoint_a, keypoint_b);
}

const std::vector<ImageId>& MatchGraph::Neighbors(ImageId image) const {
  static const std::vector<ImageId> kNone;
  const auto it = neighbors_.find(image);
  return it == neighbors_.end() ? kNone : it->second;
}

std::vector<std::array<std::uint32_t, 2>> MatchGraph::Matches(ImageId a, ImageId b) const {
  const PairMatches* pair = Find(a, b);
  if (pair == nullptr) return {};
  if (a < b) return pair->by_first;
  std::vector<std::array<std::uint32_t, 2>> matches = pair->by_second;
  for (std::array<std::uint32_t, 2>& match : matches) std::swap(match[0], match[1]);
  return matches;
}

std::vector<ThreeViewTrack> ThreeViewTracks(const MatchGraph& graph,
                                            const std::array<ImageId, 3>& images) {
  const int h = Hub(graph, images).first;
  if (h < 0) return {};
  const int x = (h + 1) % 3, y = (h + 2) % 3;
  std::vector<ThreeViewTrack> tracks;
  for (const std::array<std::uint32_t, 2>& hx : graph.Matches(images[h], images[x])) {
    ThreeViewTrack track;
    track[h] = hx[0];
    track[x] = hx[1];
    if (!graph.Match(images[h], track[h], images[y], &track[y])) continue;
    // The pair (x, y) must not contradict the chain.
    std::uint32_t y_of_x, x_of_y;
    if (graph.Match(images[x], track[x], images[y], &y_of_x) && y_of_x != track[y]) continue;
    if (graph.Match(images[y], track[y], images[x], &x_of_y) && x_of_y != track[x]) continue;
    tracks.push_back(track);
  }
  std::sort(tracks.begin(), tracks.end());
  return tracks;
}

std::vector<std::array<ImageId, 3>> ConsecutiveTriplets(
    const std::vector<ImageId>& images_by_name) {
  std::vector<std::array<ImageId, 3>> triplets;
  for (std::size_t i = 0; i + 2 < images_by_name.size(); ++i) {
    triplets.push_back({images_by_name[i], images_by_name[i + 1], images_by_name[i + 2]});
  }
  return triplets;
}

std::vector<std::array<ImageId, 3>> ConnectedTriplets(const MatchGraph& graph,
                                                      const std::vector<ImageId>& images_by_name,
                                                      int max_triplets) {
  if (max_triplets < 1) {
    throw std::invalid_argument("ConnectedTriplets: max_triplets must be >= 1, not " +
                                std::to_string(max_triplets));
  }
  std::map<ImageId, int> rank;
  for (std::size_t i = 0; i < images_by_name.size(); ++i) rank[images_by_name[i]] = int(i);
  const auto by_name = [&rank](ImageId a, ImageId b) { return rank.at(a) < rank.at(b); };
  // Every triplet with a hub, in name order.
  std::set<std::array<ImageId, 3>> candidates;
  for (const ImageId hub : images_by_name) {
    std::vector<ImageId> neighbors;
    for (const ImageId neighbor : graph.Neighbors(hub)) {
      if (rank.count(neighbor) > 0) neighbors.push_back(neighbor);
    }
    for (std::size_t i = 0; i < neighbors.size(); ++i) {
      for (std::size_t j = i + 1; j < neighbors.size(); ++j) {
        std::array<ImageId, 3> triplet = {hub, neighbors[i], neighbors[j]};
        std::sort(triplet.begin(), triplet.end(), by_name);
        candidates.insert(triplet);
      }
    }
  }
  // Lazy greedy: a candidate enters the queue with an upper bound of its track count (the smaller
  // pair of its hub) and is re-queued with its exact count when it first reaches the top; an exact
  // count on top is the best remaining candidate.
  struct Entry {
    int count;
    bool exact;
    std::array<ImageId, 3> triplet;
    bool operator<(const Entry& other) const {
      // Larger counts first; at equal counts exact ones first, then the earlier triplet.
      return std::tie(count, exact, other.triplet) < std::tie(other.count, other.exact, triplet);
    }
  };
  std::priority_queue<Entry> queue;
  for (const std::array<ImageId, 3>& triplet : candidates) {
    queue.push({Hub(graph, triplet).second, false, triplet});
  }
  std::set<ImageId> uncovered;
  for (const std::array<ImageId, 3>& triplet : candidates) {
    uncovered.insert(triplet.begin(), triplet.end());
  }
  std::vector<std::array<ImageId, 3>> taken;
  while (!queue.empty() && !uncovered.empty() && static_cast<int>(taken.size()) < max_triplets) {
    Entry entry = queue.top();
    queue.pop();
    if (!entry.exact) {
      entry.count = static_cast<int>(ThreeViewTracks(graph, entry.triplet).size());
      entry.exact = true;
      queue.push(entry);
      continue;
    }
    if (entry.count == 0) break;  // no remaining candidate has a track
    bool covers_new = false;
    for (const ImageId image : entry.triplet) covers_new |= uncovered.erase(image) > 0;
    if (covers_new) taken.push_back(entry.triplet);
  }
  return taken;
}

}  // namespace colmap
}  // namespace trigrav
