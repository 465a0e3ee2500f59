// NViewBundleAdjuster's per-image covariances (derivations.md section 14.3): ceres::Covariance on
// the camera blocks, mapped from each block's tangent space to [yaw or omega, C_world].

#include <ceres/covariance.h>
#include <ceres/manifold.h>

#include <Eigen/Geometry>
#include <chrono>
#include <utility>
#include <vector>

#include "trigrav/ba/nview_bundle_adjustment.h"

namespace trigrav {

bool NViewBundleAdjuster::ComputeCovariances(NViewBundleAdjustmentSummary* summary) {
  const auto start = std::chrono::steady_clock::now();
  const bool yaw_only =
      options_.rotation_model == NViewBundleAdjustmentOptions::RotationModel::kYawOnly;
  const int num_images = static_cast<int>(input_.images.size());
  const int rotation_size = yaw_only ? 1 : 3;
  const int size = rotation_size + 3;

  // Per image, the blocks that vary and the map M from each block's tangent space to the output
  // coordinates: yaw -> yaw (1); QuaternionManifold's delta -> omega = 2 delta (its Plus rotates by
  // 2 |delta|, on the left); the reference's tilt-only delta (a, b) -> omega = R (a e_x + b e_z);
  // centre in W -> C_world = A_w^T C_W (the scale image's fixed coordinate left out).
  struct Block {
    double* data;
    int offset;                 // first row in the image's output
    Eigen::MatrixXd to_output;  // rows: output coordinates of the block; cols: its tangent size
  };
  std::vector<std::vector<Block>> image_blocks(num_images);
  for (int k = 0; k < num_images; ++k) {
    double* rotation = RotationBlock(k);
    if (problem_->HasParameterBlock(rotation) && !problem_->IsParameterBlockConstant(rotation)) {
      Eigen::MatrixXd m;
      if (yaw_only) {
        m = Eigen::MatrixXd::Identity(1, 1);
      } else if (k == config_.reference_image) {
        const Eigen::Matrix3d r = Eigen::Quaterniond(quaternions_[k][0], quaternions_[k][1],
                                                     quaternions_[k][2], quaternions_[k][3])
                                      .normalized()
                                      .toRotationMatrix();
        m.resize(3, 2);
        m << r.col(0), r.col(2);
      } else {
        m = 2.0 * Eigen::MatrixXd::Identity(3, 3);
      }
      image_blocks[k].push_back({rotation, 0, m});
    }
    double* center = centers_[k].data();
    if (problem_->HasParameterBlock(center) && !problem_->IsParameterBlockConstant(center)) {
      Eigen::MatrixXd m = world_aligned_from_world_.transpose();
      if (k == scale_image_) {
        // SubsetManifold: its Plus Jacobian selects the two free coordinates.
        Eigen::Matrix<double, 3, 2, Eigen::RowMajor> plus_jacobian;
        problem_->GetManifold(center)->PlusJacobian(center, plus_jacobian.data());
        m = world_aligned_from_world_.transpose() * plus_jacobian;
      }
      image_blocks[k].push_back({center, rotation_size, m});
    }
  }

  std::vector<std::pair<const double*, const double*>> pairs;
  for (const std::vector<Block>& blocks : image_blocks) {
    for (std::size_t a = 0; a < blocks.size(); ++a) {
      for (std::size_t b = a; b < blocks.size(); ++b) {
        pairs.emplace_back(blocks[a].data, blocks[b].data);
      }
    }
  }
  ceres::Covariance::Options covariance_options;
  covariance_options.num_threads = options_.num_threads;
  ceres::Covariance covariance(covariance_options);
  summary->covariances.clear();
  if (!covariance.Compute(pairs, problem_.get())) {
    summary->message = "ceres::Covariance failed (rank-deficient Jacobian): no covariances";
    summary->covariance_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return false;
  }
  const double variance_px2 = options_.pixel_sigma_px * options_.pixel_sigma_px;
  summary->covariances.assign(num_images, Eigen::MatrixXd::Zero(size, size));
  for (int k = 0; k < num_images; ++k) {
    const std::vector<Block>& blocks = image_blocks[k];
    Eigen::MatrixXd& out = summary->covariances[k];
    for (std::size_t a = 0; a < blocks.size(); ++a) {
      for (std::size_t b = a; b < blocks.size(); ++b) {
        const Block& block_a = blocks[a];
        const Block& block_b = blocks[b];
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> tangent(
            block_a.to_output.cols(), block_b.to_output.cols());
        covariance.GetCovarianceBlockInTangentSpace(block_a.data, block_b.data, tangent.data());
        const Eigen::MatrixXd mapped =
            variance_px2 * block_a.to_output * tangent * block_b.to_output.transpose();
        out.block(block_a.offset, block_b.offset, mapped.rows(), mapped.cols()) = mapped;
        if (a != b) {
          out.block(block_b.offset, block_a.offset, mapped.cols(), mapped.rows()) =
              mapped.transpose();
        }
      }
    }
  }
  summary->covariance_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

}  // namespace trigrav
