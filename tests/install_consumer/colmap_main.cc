// An outside project against the installed trigrav::colmap (SQLite through find_dependency): an
// empty file is an SQLite database without COLMAP's tables, a gravity CSV round trip, three-view
// tracks of hand-made matches and a model converted to the N-view bundle adjustment's input (the
// COLMAP side of trigrav::ba, in trigrav::colmap).
#include <trigrav/colmap/database.h>
#include <trigrav/colmap/gravity_csv.h>
#include <trigrav/colmap/match_graph.h>
#include <trigrav/colmap/nview_conversion.h>

#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const std::string folder = argv[1];
  std::ofstream(folder + "/empty.db").close();
  std::string message;
  try {
    trigrav::colmap::Database database(folder + "/empty.db");
  } catch (const std::runtime_error& error) {
    message = error.what();
  }
  const trigrav::colmap::GravityByImageName gravity = {{"a.png", Eigen::Vector3d(0, 1, 0.5)}};
  trigrav::colmap::WriteGravityCsv(gravity, folder + "/gravity.csv");
  const bool same = trigrav::colmap::ReadGravityCsv(folder + "/gravity.csv") == gravity;
  // Keypoint 0 of image 1 matched to keypoint 1 of image 2 and keypoint 2 of image 3.
  const trigrav::colmap::MatchGraph graph({{1, 2, 2, {{0, 1}}}, {1, 3, 2, {{0, 2}}}});
  const std::vector<trigrav::colmap::ThreeViewTrack> tracks =
      trigrav::colmap::ThreeViewTracks(graph, {1, 2, 3});
  const bool tracked = tracks.size() == 1 && tracks[0] == trigrav::colmap::ThreeViewTrack{0, 1, 2};
  trigrav::colmap::Reconstruction model;
  model.cameras[1] = {1, trigrav::Camera::FromColmap("PINHOLE", {500, 500, 320, 240}), 640, 480};
  model.images[1].image_id = 1;
  model.images[1].name = "a.png";
  model.images[1].camera_id = 1;
  const trigrav::colmap::NViewInput input = trigrav::colmap::ToNView(model, gravity);
  const bool converted = input.reconstruction.images.size() == 1 && input.image_ids[0] == 1;
  std::cout << "trigrav::colmap: " << message << "; gravity CSV round trip "
            << (same ? "equal" : "DIFFERENT") << "; three-view tracks "
            << (tracked ? "found" : "WRONG") << "; N-view input "
            << (converted ? "converted" : "WRONG") << "\n";
  return same && tracked && converted && message.find("not a COLMAP database") != std::string::npos
             ? 0
             : 1;
}
