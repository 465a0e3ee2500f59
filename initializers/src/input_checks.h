// Internal input checks of the solvers' public entry points: rays, gravity directions, poses and
// the output pointer, with std::invalid_argument naming the solver and the offending argument. Not
// installed; not part of the public API.
#ifndef TRIGRAV_INITIALIZERS_SRC_INPUT_CHECKS_H_
#define TRIGRAV_INITIALIZERS_SRC_INPUT_CHECKS_H_

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {
namespace internal {

// True if v is finite with a non-zero length whose square neither underflows to 0 nor overflows
// (a length within about [2e-162, 1e154]), which the input checks demand of rays and gravity. One
// comparison: NaN fails it, and an infinite entry or an overflowing length gives an infinite
// squared length.
inline bool IsUsableDirection(const Eigen::Vector3d& v) {
  const double squared = v.squaredNorm();
  return squared > 0.0 && squared <= std::numeric_limits<double>::max();
}

// What is wrong with a v that fails IsUsableDirection, to follow "<name> is ": "not finite", `zero`
// (the caller's wording) for a zero vector, else too short or too long to normalise, with the
// length.
std::string DirectionProblem(const Eigen::Vector3d& v, const std::string& zero);

// Throws std::invalid_argument unless x1, x2, x3 have the same size within
// [min_triplets, max_triplets], every ray passes IsUsableDirection, and solutions is not null.
void CheckTriplets(const char* solver,
                   std::size_t min_triplets,
                   std::size_t max_triplets,
                   const std::vector<Eigen::Vector3d>& x1,
                   const std::vector<Eigen::Vector3d>& x2,
                   const std::vector<Eigen::Vector3d>& x3,
                   const void* solutions);

// The two-view counterpart of CheckTriplets: throws std::invalid_argument unless x1, x2 have the
// same size within [min_pairs, max_pairs], every ray passes IsUsableDirection, and solutions is
// not null.
void CheckPairs(const char* solver,
                std::size_t min_pairs,
                std::size_t max_pairs,
                const std::vector<Eigen::Vector3d>& x1,
                const std::vector<Eigen::Vector3d>& x2,
                const void* solutions);

// Throws std::invalid_argument if a gravity direction fails IsUsableDirection (DirectionProblem).
void CheckGravity(const char* solver, const char* name, const Eigen::Vector3d& gravity);

// Throws std::invalid_argument naming the first pose with a non-finite entry, as "name[i]".
void CheckPoses(const char* solver, const char* name, const std::vector<CameraPose>& poses);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_INPUT_CHECKS_H_
