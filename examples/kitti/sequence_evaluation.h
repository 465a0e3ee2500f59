#ifndef TRIGRAV_EXAMPLES_KITTI_SEQUENCE_EVALUATION_H_
#define TRIGRAV_EXAMPLES_KITTI_SEQUENCE_EVALUATION_H_

// The paper's KITTI evaluation (Section IV-B) of a list of methods on every triplet (f, f+1, f+2)
// of a frame range: features of every frame (cached), tracks, each method's poses against the
// ground truth, per-method summaries with chained trajectories.

#include <cstdint>
#include <string>
#include <vector>

#include "descriptor_matching.h"
#include "kitti_methods.h"
#include "kitti_report.h"
#include "kitti_sequence.h"
#include "sift_features.h"
#include "track_mistakes.h"
#include "triplet_source.h"

namespace trigrav::kitti {

struct SequenceEvaluationOptions {
  // Feature and match cache folder (created); empty: no cache, features are detected and pairs
  // matched while walking the triplets (each once per worker chunk it falls in).
  std::string cache_dir;
  SiftOptions sift;
  MatchOptions match;
  double imu_noise_deg = 0.0;  // sigma of each frame's pitch and roll error (ImuGravityInCameras)
  std::uint64_t seed = 1;      // IMU noise; triplet f's RANSAC seed is seed + f
  TrackMistake mistake = TrackMistake::kNone;  // applied to every triplet's observations
  int threads = 2;
  bool show_progress = true;  // "\r<stage> done/total" on stderr
};

struct SequenceEvaluation {
  std::vector<PoseRecord> records;       // per triplet in frame order, methods and stages in order
  std::vector<MethodSummary> summaries;  // Summarize(records)
  std::vector<double> detect_ms;         // per frame: SIFT time on one thread, -1 if cached
  // Per triplet: tracks and loading / matching times (observations cleared).
  std::vector<TripletData> triplets;
  double features_wall_s = 0.0, triplets_wall_s = 0.0;
};

// Runs every method on every triplet of the sequence's range on options.threads threads (one
// chunk of consecutive triplets per worker, so that frames are loaded and pairs matched once).
// Returns false with the first error (an unreadable image, an unwritable cache).
bool EvaluateSequence(const KittiSequence& sequence,
                      const std::vector<Method>& methods,
                      const SequenceEvaluationOptions& options,
                      SequenceEvaluation* evaluation,
                      std::string* error);

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_SEQUENCE_EVALUATION_H_
