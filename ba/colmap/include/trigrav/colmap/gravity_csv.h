#ifndef TRIGRAV_COLMAP_GRAVITY_CSV_H_
#define TRIGRAV_COLMAP_GRAVITY_CSV_H_

// Gravity per image, as an IMU gives it, in a CSV file:
//   image_name,gravity_x,gravity_y,gravity_z
//   000000.png,0.0123,0.9998,-0.0141
// one line per image after that header; image_name as in the COLMAP database / model (path
// relative to the image folder); the vector is the direction of gravity (pointing down, towards
// the ground) in that image's camera frame (x right, y down, z forward, COLMAP's camera frame), any
// positive length. Lines starting with '#' and blank lines are skipped.

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace trigrav {
namespace colmap {

using GravityByImageName = std::map<std::string, Eigen::Vector3d>;

// Throws std::runtime_error naming the file and line for a missing file or header, a malformed
// line, a duplicate image name, or a zero-length or non-finite vector.
GravityByImageName ReadGravityCsv(const std::string& path);
// Writes every entry (sorted by name) with 17 significant digits; throws std::runtime_error on an
// I/O error or a zero-length or non-finite vector (nothing is written then).
void WriteGravityCsv(const GravityByImageName& gravity, const std::string& path);
// The gravity of each name; throws std::runtime_error listing (the first few) names without one.
std::vector<Eigen::Vector3d> GravityOfImages(const GravityByImageName& gravity,
                                             const std::vector<std::string>& image_names);

}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_GRAVITY_CSV_H_
