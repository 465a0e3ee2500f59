#include "triplet_tracks.h"

namespace trigrav::kitti {

std::vector<Track> ChainTracks(const std::vector<int>& b_of_a, const std::vector<int>& c_of_b) {
  std::vector<Track> tracks;
  for (int a = 0; a < static_cast<int>(b_of_a.size()); ++a) {
    const int b = b_of_a[a];
    if (b < 0 || b >= static_cast<int>(c_of_b.size())) continue;
    const int c = c_of_b[b];
    if (c >= 0) tracks.push_back({a, b, c});
  }
  return tracks;
}

ThreeViewObservations TrackObservations(const std::array<const FrameFeatures*, 3>& frames,
                                        const std::vector<Track>& tracks,
                                        const PinholeCamera& camera,
                                        const std::array<Eigen::Vector3d, 3>& gravity_in_cam) {
  ThreeViewObservations observations;
  observations.cameras = {camera, camera, camera};
  observations.gravity_in_cam = gravity_in_cam;
  for (int k = 0; k < 3; ++k) {
    observations.pixels[k].reserve(tracks.size());
    for (const Track& track : tracks) {
      observations.pixels[k].push_back(frames[k]->pixels[track[k]].cast<double>());
    }
  }
  return observations;
}

}  // namespace trigrav::kitti
