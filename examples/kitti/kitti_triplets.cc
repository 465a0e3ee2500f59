// The paper's KITTI evaluation (Section IV-B): SIFT point triplets on consecutive frames of a KITTI
// odometry sequence, every method in RANSAC with the same threshold, raw and refined (three-view
// bundle adjustment, yaw-only and gravity-prior), errors of views 2 and 3 against ground truth,
// chained trajectories and their ATE. Gravity of each frame from the ground-truth pitch and roll,
// optionally with IMU noise.
//
//   kitti_triplets --kitti_dir=../shared/data/kitti --sequence=00 --output_dir=kitti_00
//
// Writes to --output_dir: poses.csv (one row per triplet, method and stage), summary.csv (medians,
// failures, time, ATE per method and stage), trajectories.csv (chained, aligned camera centres;
// plot with plot_kitti_trajectories.py), frames.csv (per frame: SIFT time, tracks and matching
// time of the triplet it starts). Features are cached per frame in --cache_dir.

#include <gflags/gflags.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "../require_flag.h"
#include "kitti_flags.h"
#include "kitti_methods.h"
#ifdef TRIGRAV_KITTI_WITH_PEERS
#include "peer_methods.h"
#endif
#include "kitti_report.h"
#include "sequence_evaluation.h"

// The dataset, frame range, RANSAC, refinement, SIFT and matching flags are in kitti_flags.cc.
DEFINE_string(output_dir, "", "Folder for the CSVs (created; required).");
DEFINE_uint64(seed, 1, "Seed of the IMU noise and of RANSAC (triplet f uses seed + f).");
DEFINE_int32(threads, 2, "Worker threads.");
DEFINE_bool(peers,
            false,
            "Also run the OpenCV / OpenGV five-point peers (examples/peers/), if built with them.");

namespace {

namespace fs = std::filesystem;
using trigrav::examples::RequireFlag;
namespace kitti = trigrav::kitti;

// Per frame f: SIFT time if detected in this run (empty if from the cache); tracks and loading /
// matching time of the triplet (f, f+1, f+2) (empty for the last two frames).
bool WriteFramesCsv(const std::string& path,
                    const kitti::KittiSequence& sequence,
                    const kitti::SequenceEvaluation& evaluation) {
  std::ofstream frames(path);
  frames << "frame,sift_ms,triplet_tracks,triplet_features_ms,triplet_matching_ms\n";
  for (int i = 0; i < sequence.num_frames(); ++i) {
    frames << sequence.first_frame + i << ",";
    if (evaluation.detect_ms[i] >= 0.0) frames << evaluation.detect_ms[i];
    if (i < static_cast<int>(evaluation.triplets.size())) {
      const kitti::TripletData& s = evaluation.triplets[i];
      frames << "," << s.tracks.size() << "," << 1e3 * s.features_s << "," << 1e3 * s.matching_s
             << "\n";
    } else {
      frames << ",,,\n";
    }
  }
  return static_cast<bool>(frames);
}

}  // namespace

int main(int argc, char** argv) {
  gflags::SetUsageMessage(
      "KITTI three-view evaluation: kitti_triplets --kitti_dir=DIR --sequence=00 "
      "--output_dir=OUT");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  kitti::ValidateKittiFlags(FLAGS_output_dir);
  RequireFlag(!FLAGS_output_dir.empty(), "--output_dir is required (folder for the CSVs)");
  RequireFlag(FLAGS_threads >= 1 && FLAGS_threads <= 256, "--threads must be in 1..256");

  const kitti::KittiSequence sequence = kitti::LoadSequenceFromFlags();
  std::vector<kitti::Method> methods = kitti::TrigravMethodsFromFlags();
#ifdef TRIGRAV_KITTI_WITH_PEERS
  if (FLAGS_peers) kitti::AppendPeerMethods(kitti::ThresholdPxFlag(), &methods);
#else
  RequireFlag(!FLAGS_peers, "--peers: built without OpenCV's calib3d and OpenGV (no peers)");
#endif
  const std::string cache_dir =
      kitti::CacheDirFromFlags((fs::path(FLAGS_output_dir) / "feature_cache").string());
  std::error_code ec;
  fs::create_directories(FLAGS_output_dir, ec);
  RequireFlag(!ec, "--output_dir: cannot create " + FLAGS_output_dir + ": " + ec.message());
  fs::create_directories(cache_dir, ec);
  RequireFlag(!ec, "--cache_dir: cannot create " + cache_dir + ": " + ec.message());
  // Parallelism is ours (one frame or triplet per thread); OpenCV's own threads would
  // oversubscribe.
  cv::setNumThreads(1);

  kitti::SequenceEvaluation evaluation;
  std::string error;
  const bool evaluated = kitti::EvaluateSequence(
      sequence, methods, kitti::EvaluationOptionsFromFlags(cache_dir, FLAGS_seed, FLAGS_threads),
      &evaluation, &error);
  RequireFlag(evaluated, error);

  const fs::path out(FLAGS_output_dir);
  for (const auto& [file, written] :
       {std::pair{"poses.csv", kitti::WritePoseRecordsCsv((out / "poses.csv").string(),
                                                          evaluation.records)},
        std::pair{"summary.csv",
                  kitti::WriteSummaryCsv((out / "summary.csv").string(), evaluation.summaries)},
        std::pair{"trajectories.csv",
                  kitti::WriteTrajectoriesCsv((out / "trajectories.csv").string(), sequence,
                                              evaluation.summaries)},
        std::pair{"frames.csv",
                  WriteFramesCsv((out / "frames.csv").string(), sequence, evaluation)}}) {
    RequireFlag(written, std::string("cannot write ") + (out / file).string());
  }

  std::vector<double> tracks, matching_ms, detected_ms;
  for (const kitti::TripletData& s : evaluation.triplets) {
    tracks.push_back(static_cast<double>(s.tracks.size()));
    matching_ms.push_back(1e3 * s.matching_s);
  }
  for (const double ms : evaluation.detect_ms) {
    if (ms >= 0.0) detected_ms.push_back(ms);
  }
  kitti::PrintEvaluationHeader(sequence);
  std::printf("tracks per triplet: median %.0f, min %.0f\n", trigrav::Median(tracks),
              *std::min_element(tracks.begin(), tracks.end()));
  std::printf(
      "errors: median over triplets of views 2 and 3 pooled (deg); ATE: RMSE (m) of the chained "
      "trajectory after rigid alignment\n");
  kitti::PrintSummaryTable(evaluation.summaries, std::cout);
  std::printf(
      "time: features %.1f s wall (%zu frames detected, median %.0f ms per frame on one thread; "
      "%d from the cache), triplets %.1f s wall (matching median %.1f ms per triplet), %d "
      "threads\n",
      evaluation.features_wall_s, detected_ms.size(),
      detected_ms.empty() ? 0.0 : trigrav::Median(detected_ms),
      sequence.num_frames() - static_cast<int>(detected_ms.size()), evaluation.triplets_wall_s,
      trigrav::Median(matching_ms), FLAGS_threads);
  return 0;
}
