#ifndef TRIGRAV_INITIALIZERS_SRC_ROBUST_METHODS_H_
#define TRIGRAV_INITIALIZERS_SRC_ROBUST_METHODS_H_

// The method policies of the robust estimator: for each InitialSolver, its minimal sample, the
// rays it works on (gravity-aligned or raw), its minimal solver and its local-optimisation solver.

#include <vector>

#include "robust_triplet_data.h"
#include "trigrav/initializers/essential_5pt.h"
#include "trigrav/initializers/essential_8pt.h"
#include "trigrav/initializers/trifocal_3pt.h"
#include "trigrav/initializers/trifocal_4pt.h"
#include "trigrav/initializers/trifocal_linear.h"
#include "trigrav/initializers/two_view_to_three_view.h"

namespace trigrav {
namespace internal {

// Three-view models of a two-view method (derivations.md section 6.3): CombineTwoViewPairs
// (two_view_to_three_view.h) rescales camera 3 by the view-1 depth ratio kappa of the two pairs.

// Method policies. Minimal() and Refine() append three-view poses in the original frames from the
// selected triplets' rays (aligned ones if kAligned); Refine() gets all inliers of a model.
template <int (*kSolveAligned)(const Rays&, const Rays&, const Rays&, std::vector<ThreeViewPose>*)>
void SolveGravityAware(const TripletData& data,
                       const ViewRays& aligned,
                       Workspace* work,
                       std::vector<ThreeViewPose>* poses) {
  kSolveAligned(aligned[0], aligned[1], aligned[2], &work->three_view);
  for (const ThreeViewPose& pose : work->three_view) {
    poses->push_back(
        UnalignThreeViewPose(pose, data.alignment[0], data.alignment[1], data.alignment[2]));
  }
}

template <int (*kSolvePair)(const Rays&, const Rays&, std::vector<CameraPose>*)>
void SolveTwoViewPairs(const TripletData&,
                       const ViewRays& raw,
                       Workspace* work,
                       std::vector<ThreeViewPose>* poses) {
  kSolvePair(raw[0], raw[1], &work->pair12);
  kSolvePair(raw[0], raw[2], &work->pair13);
  CombineTwoViewPairs(raw[0], raw[1], raw[2], work->pair12, work->pair13, poses);
}

inline void SolveLinear(const TripletData&,
                        const ViewRays& raw,
                        Workspace* work,
                        std::vector<ThreeViewPose>* poses) {
  SolveTrifocalLinear(raw[0], raw[1], raw[2], &work->three_view);
  poses->insert(poses->end(), work->three_view.begin(), work->three_view.end());
}

// The aligned-frame overloads, as plain function pointers.
inline int Trifocal3pt(const Rays& x1,
                       const Rays& x2,
                       const Rays& x3,
                       std::vector<ThreeViewPose>* out) {
  return SolveTrifocal3pt(x1, x2, x3, out);
}
inline int Trifocal3ptSextic(const Rays& x1,
                             const Rays& x2,
                             const Rays& x3,
                             std::vector<ThreeViewPose>* out) {
  return SolveTrifocal3ptSextic(x1, x2, x3, out);
}
inline int Trifocal4pt(const Rays& x1,
                       const Rays& x2,
                       const Rays& x3,
                       std::vector<ThreeViewPose>* out) {
  return SolveTrifocal4pt(x1, x2, x3, out);
}

template <int kSize,
          bool kAlignedRays,
          SolveFunction kMinimal,
          int kMinRefine,
          SolveFunction kRefine>
struct Method {
  static constexpr int kSampleSize = kSize;
  static constexpr bool kAligned = kAlignedRays;
  static constexpr int kMinTripletsToRefine = kMinRefine;
  static void Minimal(const TripletData& d,
                      const ViewRays& r,
                      Workspace* w,
                      std::vector<ThreeViewPose>* p) {
    kMinimal(d, r, w, p);
  }
  static void Refine(const TripletData& d,
                     const ViewRays& r,
                     Workspace* w,
                     std::vector<ThreeViewPose>* p) {
    kRefine(d, r, w, p);
  }
};

using Method3pt =
    Method<3, true, SolveGravityAware<Trifocal3pt>, 4, SolveGravityAware<Trifocal4pt>>;
using Method3ptSextic =
    Method<3, true, SolveGravityAware<Trifocal3ptSextic>, 4, SolveGravityAware<Trifocal4pt>>;
using Method4pt =
    Method<4, true, SolveGravityAware<Trifocal4pt>, 4, SolveGravityAware<Trifocal4pt>>;
using Method7ptLinear = Method<7, false, SolveLinear, 7, SolveLinear>;
using Method5pt =
    Method<5, false, SolveTwoViewPairs<SolveEssential5pt>, 8, SolveTwoViewPairs<SolveEssential8pt>>;
using Method8pt =
    Method<8, false, SolveTwoViewPairs<SolveEssential8pt>, 8, SolveTwoViewPairs<SolveEssential8pt>>;

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_ROBUST_METHODS_H_
