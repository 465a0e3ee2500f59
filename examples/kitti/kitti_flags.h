#ifndef TRIGRAV_EXAMPLES_KITTI_KITTI_FLAGS_H_
#define TRIGRAV_EXAMPLES_KITTI_KITTI_FLAGS_H_

// The command-line flags of the KITTI evaluation (dataset, frame range, feature cache, RANSAC,
// refinement, SIFT and matching), shared by kitti_triplets and peer_comparison's KITTI section so
// that both run with the same settings and defaults: the ones chosen on 00 and 02 (README, "KITTI:
// settings"). Each tool adds its own flags (output, threads, seed).

#include <string>
#include <vector>

#include "kitti_methods.h"
#include "kitti_sequence.h"
#include "sequence_evaluation.h"

namespace trigrav::kitti {

// The dataset folder given with --kitti_dir ("" when the flag is not set).
const std::string& KittiDirFlag();

// Checks the shared flags; a bad value prints "error: <message>" and exits with status 2
// (require_flag.h). --kitti_dir must name a folder; output_dir (if not empty) and the feature
// cache must not be inside it.
void ValidateKittiFlags(const std::string& output_dir);

// The sequence and frame range of --kitti_dir, --sequence, --first_frame, --last_frame (exits
// with status 2 and the loader's message if they cannot be read).
KittiSequence LoadSequenceFromFlags();

// --cache_dir, or default_cache_dir when it is empty.
std::string CacheDirFromFlags(const std::string& default_cache_dir);

// trigrav's methods of --methods, those of --refine also refined, with the RANSAC and bundle
// adjustment settings of the flags (exits with status 2 on an unknown method).
std::vector<Method> TrigravMethodsFromFlags();

// The evaluation's options from the flags (cache, SIFT, matching, IMU noise) and the given seed
// and thread count.
SequenceEvaluationOptions EvaluationOptionsFromFlags(const std::string& cache_dir,
                                                     std::uint64_t seed,
                                                     int threads);

// --threshold_px: the one inlier threshold of every method, peers included (px).
double ThresholdPxFlag();

// "KITTI <sequence> frames <first>-<last> (<n> triplets), threshold, IMU noise, gravity sigma" on
// stdout.
void PrintEvaluationHeader(const KittiSequence& sequence);

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_KITTI_FLAGS_H_
