#include "trigrav/initializers/trifocal_4pt.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "solver_test_utils.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/gravity.h"

namespace trigrav {
namespace {

// Solves a scene through the gravity overload with the measured gravity of each view.
int SolveScene(const SyntheticScene& scene,
               const Trifocal4ptOptions& options,
               std::vector<ThreeViewPose>* solutions) {
  return SolveTrifocal4pt(scene.rays[0], scene.rays[1], scene.rays[2],
                          scene.gravity_in_cam_measured[0], scene.gravity_in_cam_measured[1],
                          scene.gravity_in_cam_measured[2], options, solutions);
}

TEST(Trifocal4pt, RecoversTruePoseNoiseFreeOnThousandScenes) {
  std::mt19937_64 rng(1);
  SyntheticSceneOptions scene_options;
  int failures = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 1000; ++trial) {
    const SyntheticScene scene = GenerateSyntheticScene(scene_options, &rng);
    std::vector<ThreeViewPose> solutions;
    ASSERT_EQ(SolveScene(scene, Trifocal4ptOptions(), &solutions), 1);
    ASSERT_EQ(solutions.size(), 1u);
    EXPECT_NEAR(solutions[0].cam2_from_cam1.Center().norm(), 1.0, 1e-12);
    const ThreeViewPoseErrors e = ComputeThreeViewPoseErrors(scene.ground_truth, solutions[0]);
    const double error = e.MaxAngleDeg();
    worst = std::max(worst, error);
    if (!(error < 1e-8 && e.relative_scale < 1e-9)) {
      ++failures;
      ADD_FAILURE() << "trial " << trial << " error " << error << " deg, scale "
                    << e.relative_scale;
    }
  }
  EXPECT_EQ(failures, 0) << "worst error " << worst << " deg";
}

// Scenes unlike the default: other focal lengths, yaw well beyond 10 deg, tilts of several degrees,
// more triplets than the minimum.
TEST(Trifocal4pt, GeneralisesToUnseenScenes) {
  std::mt19937_64 rng(2);
  const std::vector<SyntheticSceneOptions> unseen = testing_utils::UnseenSceneOptions();
  const int num_points[] = {4, 4, 7, 20};  // minimal and least-squares paths
  for (std::size_t c = 0; c < unseen.size(); ++c) {
    SyntheticSceneOptions scene_options = unseen[c];
    scene_options.num_points = num_points[c];
    for (int trial = 0; trial < 200; ++trial) {
      const SyntheticScene scene = GenerateSyntheticScene(scene_options, &rng);
      std::vector<ThreeViewPose> solutions;
      ASSERT_EQ(SolveScene(scene, Trifocal4ptOptions(), &solutions), 1);
      ASSERT_LT(ComputeThreeViewPoseErrors(scene.ground_truth, solutions[0]).MaxAngleDeg(), 1e-8)
          << "f " << scene_options.focal_px << " yaw " << scene_options.max_yaw_deg << " trial "
          << trial;
    }
  }
}

// Every recovery variant is exact without noise; the paper's closed form may return 0 on the rare
// scene where its denominators vanish, never a wrong pose.
TEST(Trifocal4pt, PaperVariantsExactNoiseFree) {
  std::mt19937_64 rng(3);
  for (const Trifocal4ptRecovery recovery :
       {Trifocal4ptRecovery::kEnforced, Trifocal4ptRecovery::kLeastSquares,
        Trifocal4ptRecovery::kPaperClosedForm}) {
    for (const bool resolve : {false, true}) {
      for (const Trifocal4ptEpipoles epipoles : {Trifocal4ptEpipoles::kLeastSquaresReadIfMinimal,
                                                 Trifocal4ptEpipoles::kTensorNullVectors}) {
        if (recovery != Trifocal4ptRecovery::kEnforced &&
            epipoles != Trifocal4ptEpipoles::kLeastSquaresReadIfMinimal) {
          continue;  // the epipoles are an option of the enforcement only
        }
        Trifocal4ptOptions options;
        options.recovery = recovery;
        options.epipoles = epipoles;
        options.resolve_translations = resolve;
        options.polish_iterations =
            0;  // each variant alone, as the paper and derivations.md section 4 define it
        for (int trial = 0; trial < 200; ++trial) {
          const SyntheticScene scene = GenerateSyntheticScene(SyntheticSceneOptions(), &rng);
          std::vector<ThreeViewPose> solutions;
          const int count = SolveScene(scene, options, &solutions);
          ASSERT_EQ(count, 1);
          EXPECT_LT(ComputeThreeViewPoseErrors(scene.ground_truth, solutions[0]).MaxAngleDeg(),
                    1e-7)
              << static_cast<int>(recovery) << " " << static_cast<int>(epipoles);
        }
      }
    }
  }
}

double MedianRotationErrorDeg(const Trifocal4ptOptions& options, int num_points, double noise_px) {
  SyntheticSceneOptions scene_options;
  scene_options.pixel_noise_px = noise_px;
  scene_options.num_points = num_points;
  return testing_utils::MedianFirstSolutionRotationErrorDeg(
      scene_options, 5, 300,
      [&options](const SyntheticScene& scene, std::vector<ThreeViewPose>* out) {
        return SolveScene(scene, options, out);
      });
}

// With noise the error grows smoothly with the noise level and stays in the range measured for this
// scene (f = 500 px; 1 px: 0.74 deg for the default pipeline, 1.0 deg for the enforcement with
// one polish step, 3.4 deg without the polish).
TEST(Trifocal4pt, DegradesSmoothlyWithNoise) {
  std::vector<double> medians;
  for (const double noise_px : {0.1, 0.5, 1.0, 2.0}) {
    medians.push_back(MedianRotationErrorDeg(Trifocal4ptOptions(), 4, noise_px));
  }
  EXPECT_LT(medians[0], 0.2);
  EXPECT_GT(medians[2], 0.5);
  EXPECT_LT(medians[2], 1.5);
  for (std::size_t i = 1; i < medians.size(); ++i) EXPECT_GT(medians[i], 1.5 * medians[i - 1]);
}

// Each stage earns its place (derivations.md sections 4.2-4.5 and 4.7): the least-squares read
// alone (1 px: 12.6 deg); the enforcement with the re-solve, the paper's step (3.4 deg); one polish
// step after it (1.0 deg); the default, the least-squares read polished until converged (0.74
// deg); then more triplets (10: 0.19 deg).
TEST(Trifocal4pt, EachStageReducesTheError) {
  Trifocal4ptOptions least_squares;
  least_squares.recovery = Trifocal4ptRecovery::kLeastSquares;
  least_squares.resolve_translations = false;
  least_squares.polish_iterations = 0;
  Trifocal4ptOptions enforced;
  enforced.recovery = Trifocal4ptRecovery::kEnforced;
  enforced.polish_iterations = 0;
  Trifocal4ptOptions enforced_polished = enforced;
  enforced_polished.polish_iterations = 1;
  const double least_squares_error = MedianRotationErrorDeg(least_squares, 4, 1.0);
  const double enforced_error = MedianRotationErrorDeg(enforced, 4, 1.0);
  const double enforced_polished_error = MedianRotationErrorDeg(enforced_polished, 4, 1.0);
  const double default_error = MedianRotationErrorDeg(Trifocal4ptOptions(), 4, 1.0);
  EXPECT_LT(enforced_error, 0.6 * least_squares_error);
  EXPECT_LT(enforced_polished_error, 0.5 * enforced_error);
  EXPECT_LT(default_error, 0.9 * enforced_polished_error);
  EXPECT_LT(MedianRotationErrorDeg(Trifocal4ptOptions(), 10, 1.0), 0.5 * default_error);
}

// Aligning by hand with the same alignment rotations gives bit-for-bit the overload's poses.
// Another valid alignment (pitch/roll: differs by a yaw) gives the same poses noise-free; with
// noise the normalisation |q| = 1 is not yaw-invariant, so results then differ at the noise level
// only.
TEST(Trifocal4pt, GravityOverloadMatchesAligningByHand) {
  std::mt19937_64 rng(6);
  for (const double noise_px : {0.0, 0.5}) {
    SyntheticSceneOptions scene_options;
    scene_options.pixel_noise_px = noise_px;
    scene_options.num_points = 6;
    for (int trial = 0; trial < 50; ++trial) {
      const SyntheticScene scene = GenerateSyntheticScene(scene_options, &rng);
      std::vector<ThreeViewPose> from_gravity, by_hand;
      ASSERT_EQ(SolveTrifocal4pt(scene.rays[0], scene.rays[1], scene.rays[2],
                                 scene.gravity_in_cam_measured[0], scene.gravity_in_cam_measured[1],
                                 scene.gravity_in_cam_measured[2], &from_gravity),
                1);
      const std::array<Eigen::Matrix3d, 3> from_gravity_alignment = {
          GravityAlignmentFromGravity(scene.gravity_in_cam_measured[0]),
          GravityAlignmentFromGravity(scene.gravity_in_cam_measured[1]),
          GravityAlignmentFromGravity(scene.gravity_in_cam_measured[2])};
      for (const auto& align : {from_gravity_alignment, scene.gravity_alignment_measured}) {
        const bool same_alignment = &align == &from_gravity_alignment;
        if (!same_alignment && noise_px > 0.0) continue;
        ASSERT_EQ(
            SolveTrifocal4pt(AlignRays(align[0], scene.rays[0]), AlignRays(align[1], scene.rays[1]),
                             AlignRays(align[2], scene.rays[2]), &by_hand),
            1);
        const ThreeViewPose unaligned =
            UnalignThreeViewPose(by_hand[0], align[0], align[1], align[2]);
        const ThreeViewPoseErrors e = ComputeThreeViewPoseErrors(unaligned, from_gravity[0]);
        const double tolerance = same_alignment ? 0.0 : 1e-8;
        EXPECT_LE(e.MaxRotationDeg(), tolerance);
        EXPECT_LE(e.MaxTranslationDeg(), tolerance);
        EXPECT_LE(e.relative_scale, tolerance);
      }
    }
  }
}

TEST(Trifocal4pt, YawNear180Degrees) {
  std::mt19937_64 rng(7);
  SyntheticSceneOptions scene_options;
  scene_options.max_yaw_deg = 0.0;
  const SyntheticScene base = GenerateSyntheticScene(scene_options, &rng);
  // Rays seen by cameras turned by 180 deg about gravity: cameras 2 and 3 look back at the points
  // through their mirror image. Instead rotate the aligned frames of 2 and 3 and map rays
  // accordingly.
  for (const double yaw : {M_PI, M_PI - 1e-9, -M_PI + 1e-6}) {
    const Eigen::Matrix3d turn = RotationAboutY(yaw);
    std::vector<Eigen::Vector3d> x1 = AlignRays(base.gravity_alignment_true[0], base.rays[0]);
    std::vector<Eigen::Vector3d> x2 =
        AlignRays(turn * base.gravity_alignment_true[1], base.rays[1]);
    std::vector<Eigen::Vector3d> x3 = AlignRays(base.gravity_alignment_true[2], base.rays[2]);
    std::vector<ThreeViewPose> solutions;
    ASSERT_EQ(SolveTrifocal4pt(x1, x2, x3, &solutions), 1);
    const ThreeViewPose truth_aligned = {
        UnalignPose(base.ground_truth.cam2_from_cam1, base.gravity_alignment_true[0].transpose(),
                    (turn * base.gravity_alignment_true[1]).transpose()),
        UnalignPose(base.ground_truth.cam3_from_cam1, base.gravity_alignment_true[0].transpose(),
                    base.gravity_alignment_true[2].transpose())};
    const ThreeViewPoseErrors e = ComputeThreeViewPoseErrors(truth_aligned, solutions[0]);
    EXPECT_LT(e.MaxRotationDeg(), 1e-8) << yaw;
    EXPECT_LT(e.MaxTranslationDeg(), 1e-8) << yaw;
  }
}

// Camera 2 moved straight along gravity: its horizontal epipole vanishes, so the least-squares
// read of q is undefined (derivations.md section 4.2). The default recovery then takes the
// enforcement, and the enforcement's default epipoles the tensor's own (sections 4.3 and 4.7): the
// pose is still exact. The read alone (kLeastSquares) gives no solution.
TEST(Trifocal4pt, VerticalMotionFallsBackToTheTensorsEpipoles) {
  const std::vector<Eigen::Vector3d> points = {
      {0.3, -0.2, 4.0}, {-0.5, 0.4, 6.0}, {0.8, 0.6, 5.0}, {-0.2, -0.7, 7.5}};
  const Eigen::Matrix3d R2 = RotationAboutY(0.2), R3 = RotationAboutY(-0.3);
  const Eigen::Vector3d center2(0.0, -0.8, 0.0), center3(0.7, 0.1, 0.4);
  std::vector<Eigen::Vector3d> x1, x2, x3;
  for (const Eigen::Vector3d& X : points) {
    x1.push_back(X);
    x2.push_back(R2 * (X - center2));
    x3.push_back(R3 * (X - center3));
  }
  // Aligned truth, scaled to |c2| = 1 as the solver returns it.
  const double scale = center2.norm();
  const ThreeViewPose truth = {CameraPose{R2, -R2 * center2 / scale},
                               CameraPose{R3, -R3 * center3 / scale}};
  for (const Trifocal4ptRecovery recovery :
       {Trifocal4ptRecovery::kLeastSquaresIfMinimal, Trifocal4ptRecovery::kEnforced}) {
    for (const Trifocal4ptEpipoles epipoles : {Trifocal4ptEpipoles::kLeastSquaresReadIfMinimal,
                                               Trifocal4ptEpipoles::kTensorNullVectors}) {
      Trifocal4ptOptions options;
      options.recovery = recovery;
      options.epipoles = epipoles;
      std::vector<ThreeViewPose> solutions;
      ASSERT_EQ(SolveTrifocal4pt(x1, x2, x3, options, &solutions), 1);
      const ThreeViewPoseErrors e = ComputeThreeViewPoseErrors(truth, solutions[0]);
      EXPECT_LT(e.MaxAngleDeg(), 1e-8) << static_cast<int>(recovery) << static_cast<int>(epipoles);
      EXPECT_LT(e.relative_scale, 1e-9) << static_cast<int>(recovery) << static_cast<int>(epipoles);
    }
  }
  Trifocal4ptOptions read_alone;
  read_alone.recovery = Trifocal4ptRecovery::kLeastSquares;
  std::vector<ThreeViewPose> solutions;
  EXPECT_EQ(SolveTrifocal4pt(x1, x2, x3, read_alone, &solutions), 0);
  // The fallback is the enforcement with the re-solve, bit for bit.
  Trifocal4ptOptions enforced;
  enforced.recovery = Trifocal4ptRecovery::kEnforced;
  std::vector<ThreeViewPose> by_default, by_enforcement;
  ASSERT_EQ(SolveTrifocal4pt(x1, x2, x3, &by_default), 1);
  ASSERT_EQ(SolveTrifocal4pt(x1, x2, x3, enforced, &by_enforcement), 1);
  for (const auto pose : {&ThreeViewPose::cam2_from_cam1, &ThreeViewPose::cam3_from_cam1}) {
    EXPECT_EQ((by_default[0].*pose).R, (by_enforcement[0].*pose).R);
    EXPECT_EQ((by_default[0].*pose).t, (by_enforcement[0].*pose).t);
  }
}

// The default recovery is the least-squares read with no re-solve for 4 triplets, the enforcement
// with the re-solve and at most one polish step for more (derivations.md section 4.7): with noise,
// bit-for-bit the same poses as those pipelines spelled out.
TEST(Trifocal4pt, DefaultPipelineDependsOnTheNumberOfTriplets) {
  std::mt19937_64 rng(12);
  for (const int polish_iterations : {0, 1, 8}) {
    Trifocal4ptOptions by_default;
    by_default.polish_iterations = polish_iterations;
    Trifocal4ptOptions read = by_default;
    read.recovery = Trifocal4ptRecovery::kLeastSquares;
    read.resolve_translations = false;
    Trifocal4ptOptions enforced = by_default;
    enforced.recovery = Trifocal4ptRecovery::kEnforced;
    enforced.polish_iterations = std::min(polish_iterations, 1);
    for (const int num_points : {4, 6, 20}) {
      SyntheticSceneOptions scene_options;
      scene_options.pixel_noise_px = 1.0;
      scene_options.num_points = num_points;
      for (int trial = 0; trial < 20; ++trial) {
        const SyntheticScene scene = GenerateSyntheticScene(scene_options, &rng);
        std::vector<ThreeViewPose> solved, spelled_out;
        ASSERT_EQ(SolveScene(scene, by_default, &solved), 1);
        ASSERT_EQ(SolveScene(scene, num_points == 4 ? read : enforced, &spelled_out), 1);
        for (const auto pose : {&ThreeViewPose::cam2_from_cam1, &ThreeViewPose::cam3_from_cam1}) {
          EXPECT_EQ((solved[0].*pose).R, (spelled_out[0].*pose).R)
              << polish_iterations << " " << num_points << " " << trial;
          EXPECT_EQ((solved[0].*pose).t, (spelled_out[0].*pose).t)
              << polish_iterations << " " << num_points << " " << trial;
        }
      }
    }
  }
}

TEST(Trifocal4pt, MisuseThrows) {
  std::mt19937_64 rng(8);
  const SyntheticScene scene = GenerateSyntheticScene(SyntheticSceneOptions(), &rng);
  const auto& x = scene.rays;
  const Eigen::Vector3d g = Eigen::Vector3d::UnitY();
  std::vector<ThreeViewPose> solutions;
  auto bad = [&](std::vector<Eigen::Vector3d> a, std::vector<Eigen::Vector3d> b,
                 std::vector<Eigen::Vector3d> c) {
    EXPECT_THROW(SolveTrifocal4pt(a, b, c, &solutions), std::invalid_argument);
    EXPECT_THROW(SolveTrifocal4pt(a, b, c, g, g, g, &solutions), std::invalid_argument);
  };
  bad({x[0].begin(), x[0].begin() + 3}, {x[1].begin(), x[1].begin() + 3},
      {x[2].begin(), x[2].begin() + 3});              // too few
  bad(x[0], {x[1].begin(), x[1].begin() + 3}, x[2]);  // sizes differ
  bad({}, {}, {});                                    // empty
  auto with = [&](int view, const Eigen::Vector3d& value) {
    std::array<std::vector<Eigen::Vector3d>, 3> rays = x;
    rays[view][2] = value;
    return rays;
  };
  for (const Eigen::Vector3d& value : {Eigen::Vector3d(NAN, 0, 1), Eigen::Vector3d(0, INFINITY, 1),
                                       Eigen::Vector3d::Zero().eval()}) {
    for (int view = 0; view < 3; ++view) {
      const auto rays = with(view, value);
      bad(rays[0], rays[1], rays[2]);
    }
  }
  for (const Eigen::Vector3d& gravity :
       {Eigen::Vector3d::Zero().eval(), Eigen::Vector3d(0, NAN, 0)}) {
    EXPECT_THROW(SolveTrifocal4pt(x[0], x[1], x[2], g, gravity, g, &solutions),
                 std::invalid_argument);
  }
  EXPECT_THROW(SolveTrifocal4pt(x[0], x[1], x[2], nullptr), std::invalid_argument);
  try {
    SolveTrifocal4pt(x[0], {x[1].begin(), x[1].begin() + 3}, x[2], &solutions);
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("differ in size"), std::string::npos) << error.what();
  }
}

// Degenerate input has no single answer: the incidence system's null space is more than
// one-dimensional, and the solver says so with 0 solutions (minimal and least-squares paths).
TEST(Trifocal4pt, DegenerateInputGivesNoSolution) {
  std::mt19937_64 rng(9);
  for (const int num_points : {4, 20}) {
    SyntheticSceneOptions options;
    options.num_points = num_points;
    for (int trial = 0; trial < 50; ++trial) {
      const SyntheticScene scene = GenerateSyntheticScene(options, &rng);
      std::vector<ThreeViewPose> solutions(1);
      // Identical views (zero baseline): no translation is observable.
      EXPECT_EQ(SolveTrifocal4pt(scene.rays[0], scene.rays[0], scene.rays[0], &solutions), 0);
      EXPECT_TRUE(solutions.empty());
      // Every triplet the same point.
      const std::vector<Eigen::Vector3d> same1(num_points, scene.rays[0][0]),
          same2(num_points, scene.rays[1][0]), same3(num_points, scene.rays[2][0]);
      EXPECT_EQ(SolveTrifocal4pt(same1, same2, same3, &solutions), 0);
    }
  }
}

}  // namespace
}  // namespace trigrav
