// Input checks of the solvers' entry points (input_checks.h).
#include "input_checks.h"

#include <sstream>
#include <stdexcept>
#include <string>

namespace trigrav {
namespace internal {

std::string DirectionProblem(const Eigen::Vector3d& v, const std::string& zero) {
  if (!v.allFinite()) return "not finite";
  if (v.isZero(0.0)) return zero;
  const bool too_long = v.squaredNorm() > 0.0;  // else it underflowed to 0
  // stableNorm: the length itself, where norm() gives Inf or 0.
  std::ostringstream message;
  message << "too " << (too_long ? "long" : "short") << " to normalise (length " << v.stableNorm()
          << ": its squared length " << (too_long ? "overflows" : "underflows to 0")
          << "); scale it to about unit length";
  return message.str();
}

namespace {

void CheckRays(const char* solver, const char* name, const std::vector<Eigen::Vector3d>& rays) {
  for (std::size_t n = 0; n < rays.size(); ++n) {
    // One comparison per ray on the hot path (every solver call); the message only on failure.
    if (!IsUsableDirection(rays[n])) {
      throw std::invalid_argument(std::string("trigrav: ") + solver + ": " + name + "[" +
                                  std::to_string(n) + "] is " +
                                  DirectionProblem(rays[n], "a zero-length ray"));
    }
  }
}

}  // namespace

void CheckTriplets(const char* solver,
                   std::size_t min_triplets,
                   std::size_t max_triplets,
                   const std::vector<Eigen::Vector3d>& x1,
                   const std::vector<Eigen::Vector3d>& x2,
                   const std::vector<Eigen::Vector3d>& x3,
                   const void* solutions) {
  // The message is built only on failure: this runs on every solver call (the RANSAC hot path).
  auto fail = [solver](const std::string& what) {
    throw std::invalid_argument(std::string("trigrav: ") + solver + ": " + what);
  };
  if (solutions == nullptr) fail("solutions is null");
  if (x1.size() != x2.size() || x1.size() != x3.size()) {
    fail("x1, x2, x3 differ in size (" + std::to_string(x1.size()) + ", " +
         std::to_string(x2.size()) + ", " + std::to_string(x3.size()) + ")");
  }
  if (x1.size() < min_triplets || x1.size() > max_triplets) {
    fail(std::string("needs ") + (min_triplets == max_triplets ? "exactly " : "at least ") +
         std::to_string(min_triplets) + " triplets, got " + std::to_string(x1.size()));
  }
  CheckRays(solver, "x1", x1);
  CheckRays(solver, "x2", x2);
  CheckRays(solver, "x3", x3);
}

void CheckPairs(const char* solver,
                std::size_t min_pairs,
                std::size_t max_pairs,
                const std::vector<Eigen::Vector3d>& x1,
                const std::vector<Eigen::Vector3d>& x2,
                const void* solutions) {
  // As CheckTriplets: the message is built only on failure.
  auto fail = [solver](const std::string& what) {
    throw std::invalid_argument(std::string("trigrav: ") + solver + ": " + what);
  };
  if (solutions == nullptr) fail("solutions is null");
  if (x1.size() != x2.size()) {
    fail("x1, x2 differ in size (" + std::to_string(x1.size()) + ", " + std::to_string(x2.size()) +
         ")");
  }
  if (x1.size() < min_pairs || x1.size() > max_pairs) {
    fail(std::string("needs ") + (min_pairs == max_pairs ? "exactly " : "at least ") +
         std::to_string(min_pairs) + " correspondences, got " + std::to_string(x1.size()));
  }
  CheckRays(solver, "x1", x1);
  CheckRays(solver, "x2", x2);
}

void CheckGravity(const char* solver, const char* name, const Eigen::Vector3d& gravity) {
  if (!IsUsableDirection(gravity)) {
    throw std::invalid_argument(std::string("trigrav: ") + solver + ": " + name + " is " +
                                DirectionProblem(gravity, "zero"));
  }
}

void CheckPoses(const char* solver, const char* name, const std::vector<CameraPose>& poses) {
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (!poses[i].IsFinite()) {
      throw std::invalid_argument(std::string("trigrav: ") + solver + ": " + name + "[" +
                                  std::to_string(i) + "] is not finite");
    }
  }
}

}  // namespace internal
}  // namespace trigrav
