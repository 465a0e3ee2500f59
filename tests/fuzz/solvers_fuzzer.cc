// Fuzz harness over every minimal and non-minimal solver overload (trifocal_3pt.h, trifocal_4pt.h,
// trifocal_linear.h, essential_5pt.h, essential_8pt.h, two_view_to_three_view.h).
//
// Input: a mode byte, then either a synthetic scene with edits (fuzz_scene.h) or raw rays and
// gravity (0-12 rays per view, sizes may differ), then the 4-point solver's options. Each solver
// runs on all the rays and on the first `minimal sample` rays of each view. Checked for every call:
//   - the only exception is std::invalid_argument, and clearly valid input (equal sizes in the
//     solver's range, finite rays and gravity with norms in [1e-150, 1e150]) does not throw;
//   - the returned count equals solutions->size() (the vector is cleared) and is within the
//     solver's maximum; every pose is finite;
//   - a null output pointer throws std::invalid_argument.
// Built as a libFuzzer target with Clang, and into a replay driver (replay_main.cc) for ctest.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include "fuzz_check.h"
#include "fuzz_input.h"
#include "fuzz_scene.h"
#include "trigrav/initializers/essential_5pt.h"
#include "trigrav/initializers/essential_8pt.h"
#include "trigrav/initializers/trifocal_3pt.h"
#include "trigrav/initializers/trifocal_4pt.h"
#include "trigrav/initializers/trifocal_linear.h"
#include "trigrav/initializers/two_view_to_three_view.h"

namespace trigrav {
namespace fuzz {
namespace {

using Rays = std::vector<Eigen::Vector3d>;
constexpr std::size_t kUnbounded = std::numeric_limits<std::size_t>::max();

struct RayProblem {
  std::array<Rays, 3> rays;
  std::array<Eigen::Vector3d, 3> gravity_in_cam;
};

RayProblem DecodeRayProblem(FuzzInput* input) {
  RayProblem problem;
  if (input->Byte() % 2 == 0) {
    if (auto scene = DecodeSyntheticScene(input, 3, 12)) {
      problem.rays = scene->rays;
      problem.gravity_in_cam = scene->gravity_in_cam_measured;
    }
  } else {
    const bool same_size = input->Byte() % 2 == 0;
    const int common_size = input->Index(13);
    for (Rays& view : problem.rays) {
      view.resize(same_size ? common_size : input->Index(13));
      for (Eigen::Vector3d& ray : view) ray = input->Vector3();
    }
    for (Eigen::Vector3d& gravity : problem.gravity_in_cam) gravity = input->Vector3();
  }
  ApplyEdits<3>(input, &problem.rays, &problem.gravity_in_cam);
  return problem;
}

Trifocal4ptOptions DecodeTrifocal4ptOptions(FuzzInput* input) {
  Trifocal4ptOptions options;
  options.recovery = static_cast<Trifocal4ptRecovery>(input->Index(4));
  options.epipoles = static_cast<Trifocal4ptEpipoles>(input->Index(2));
  options.resolve_translations = input->Byte() % 2 == 0;
  options.epipole_iterations = input->Index(4);
  options.polish_iterations = input->Index(9);
  return options;
}

// Finite with a norm that neither overflows nor underflows: no reading of the documented misuse
// ("non-finite", "zero-length") covers it.
bool ClearlyValid(const Eigen::Vector3d& v) {
  const double norm = v.norm();
  return v.allFinite() && norm >= 1e-150 && norm <= 1e150;
}

bool ClearlyValidRays(const std::vector<const Rays*>& views,
                      std::size_t min_size,
                      std::size_t max_size) {
  const std::size_t size = views.front()->size();
  if (size < min_size || size > max_size) return false;
  for (const Rays* view : views) {
    if (view->size() != size) return false;
    for (const Eigen::Vector3d& ray : *view) {
      if (!ClearlyValid(ray)) return false;
    }
  }
  return true;
}

// Runs one solver call and checks the contract above. solve(nullptr) must throw.
template <typename Pose, typename Solve>
void CheckCall(bool valid_input, std::size_t max_solutions, Solve solve) {
  try {
    solve(nullptr);
    TRIGRAV_FUZZ_CHECK(false, "a null output did not throw");
  } catch (const std::invalid_argument&) {
  }
  std::vector<Pose> solutions(2);  // stale entries: the solver must clear them
  int count = -1;
  try {
    count = solve(&solutions);
  } catch (const std::invalid_argument& error) {
    if (valid_input) std::fprintf(stderr, "thrown: %s\n", error.what());
    TRIGRAV_FUZZ_CHECK(!valid_input, "std::invalid_argument on valid input");
    return;
  }
  TRIGRAV_FUZZ_CHECK(count >= 0 && static_cast<std::size_t>(count) == solutions.size(),
                     "count differs from solutions->size()");
  TRIGRAV_FUZZ_CHECK(solutions.size() <= max_solutions, "more solutions than the solver's maximum");
  for (const Pose& pose : solutions) TRIGRAV_FUZZ_CHECK(pose.IsFinite(), "non-finite pose");
}

Rays Head(const Rays& rays, std::size_t count) {
  return Rays(rays.begin(), rays.begin() + std::min(count, rays.size()));
}

// Every three-view solver (both overloads of the gravity-aware ones) on x1, x2, x3.
void CheckThreeViewSolvers(const Rays& x1,
                           const Rays& x2,
                           const Rays& x3,
                           const std::array<Eigen::Vector3d, 3>& g,
                           const Trifocal4ptOptions& options_4pt) {
  const bool valid_gravity = ClearlyValid(g[0]) && ClearlyValid(g[1]) && ClearlyValid(g[2]);
  auto valid = [&](std::size_t min_size, std::size_t max_size) {
    return ClearlyValidRays({&x1, &x2, &x3}, min_size, max_size);
  };
  const bool valid_3pt = valid(3, 3), valid_4pt = valid(4, kUnbounded);
  CheckCall<ThreeViewPose>(valid_3pt, 16, [&](std::vector<ThreeViewPose>* out) {
    return SolveTrifocal3pt(x1, x2, x3, out);
  });
  CheckCall<ThreeViewPose>(valid_3pt && valid_gravity, 16, [&](std::vector<ThreeViewPose>* out) {
    return SolveTrifocal3pt(x1, x2, x3, g[0], g[1], g[2], out);
  });
  CheckCall<ThreeViewPose>(valid_3pt, 6, [&](std::vector<ThreeViewPose>* out) {
    return SolveTrifocal3ptSextic(x1, x2, x3, out);
  });
  CheckCall<ThreeViewPose>(valid_3pt && valid_gravity, 6, [&](std::vector<ThreeViewPose>* out) {
    return SolveTrifocal3ptSextic(x1, x2, x3, g[0], g[1], g[2], out);
  });
  CheckCall<ThreeViewPose>(valid_4pt, 1, [&](std::vector<ThreeViewPose>* out) {
    return SolveTrifocal4pt(x1, x2, x3, out);
  });
  CheckCall<ThreeViewPose>(valid_4pt && valid_gravity, 1, [&](std::vector<ThreeViewPose>* out) {
    return SolveTrifocal4pt(x1, x2, x3, g[0], g[1], g[2], out);
  });
  CheckCall<ThreeViewPose>(valid_4pt, 1, [&](std::vector<ThreeViewPose>* out) {
    return SolveTrifocal4pt(x1, x2, x3, options_4pt, out);
  });
  CheckCall<ThreeViewPose>(valid_4pt && valid_gravity, 1, [&](std::vector<ThreeViewPose>* out) {
    return SolveTrifocal4pt(x1, x2, x3, g[0], g[1], g[2], options_4pt, out);
  });
  CheckCall<ThreeViewPose>(valid(7, kUnbounded), 1, [&](std::vector<ThreeViewPose>* out) {
    return SolveTrifocalLinear(x1, x2, x3, out);
  });
}

// The two-view solvers on pairs (1,2) and (1,3), and the three-view poses combined from the
// five-point solutions.
void CheckTwoViewSolvers(const Rays& x1, const Rays& x2, const Rays& x3) {
  for (const Rays* xk : {&x2, &x3}) {
    CheckCall<CameraPose>(ClearlyValidRays({&x1, xk}, 5, 5), 10, [&](std::vector<CameraPose>* out) {
      return SolveEssential5pt(x1, *xk, out);
    });
    CheckCall<CameraPose>(
        ClearlyValidRays({&x1, xk}, 8, kUnbounded), 1,
        [&](std::vector<CameraPose>* out) { return SolveEssential8pt(x1, *xk, out); });
  }
  std::vector<CameraPose> pair12, pair13;
  try {
    SolveEssential5pt(x1, x2, &pair12);
    SolveEssential5pt(x1, x3, &pair13);
  } catch (const std::invalid_argument&) {
    return;
  }
  std::vector<ThreeViewPose> combined;
  std::vector<double> residuals;
  CombineTwoViewPairs(x1, x2, x3, pair12, pair13, &combined, &residuals);
  TRIGRAV_FUZZ_CHECK(combined.size() == residuals.size(), "one residual per combined pose");
  for (const ThreeViewPose& pose : combined) {
    TRIGRAV_FUZZ_CHECK(pose.IsFinite(), "CombineTwoViewPairs: non-finite pose");
  }
  for (const double residual : residuals) {
    TRIGRAV_FUZZ_CHECK(!std::isnan(residual), "CombineTwoViewPairs: NaN residual");
  }
}

}  // namespace
}  // namespace fuzz
}  // namespace trigrav

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace trigrav::fuzz;  // NOLINT: the harness entry point must stay outside namespaces
  FuzzInput input(data, size);
  const RayProblem problem = DecodeRayProblem(&input);
  const trigrav::Trifocal4ptOptions options_4pt = DecodeTrifocal4ptOptions(&input);
  const Rays& x1 = problem.rays[0];
  const Rays& x2 = problem.rays[1];
  const Rays& x3 = problem.rays[2];
  // All rays, then the minimal samples 3 (3-point), 4, 5 (5-point), 7 and 8 (linear, 8-point).
  CheckThreeViewSolvers(x1, x2, x3, problem.gravity_in_cam, options_4pt);
  CheckTwoViewSolvers(x1, x2, x3);
  for (const std::size_t minimal : {3, 4, 5, 7, 8}) {
    const Rays h1 = Head(x1, minimal), h2 = Head(x2, minimal), h3 = Head(x3, minimal);
    if (minimal == 5 || minimal == 8) {
      CheckTwoViewSolvers(h1, h2, h3);
    } else {
      CheckThreeViewSolvers(h1, h2, h3, problem.gravity_in_cam, options_4pt);
    }
  }
  return 0;
}
