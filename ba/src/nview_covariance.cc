// NViewBundleAdjuster's per-image covariances (ba/derivations.md section 14.3): the Gauss-Newton
// covariance of the camera parameters, (J^T J)^-1 restricted to the cameras, as the inverse of the
// reduced camera matrix S = U - sum_p W_p V_p^+ W_p^T (the points eliminated block by block), then
// mapped from each block's tangent space to [yaw or omega, C_world].

#include <ceres/manifold.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <unordered_map>
#include <vector>

#include "pseudo_inverse.h"
#include "trigrav/ba/nview_bundle_adjustment.h"

namespace trigrav {
namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// A camera parameter block that varies: where its tangent sits in S, and the map from its tangent
// to the image's output coordinates.
struct CameraBlock {
  int image = -1;
  int offset = 0;         // first column in S
  int output_offset = 0;  // first row in the image's covariance
  Eigen::MatrixXd to_output;
  int size() const { return static_cast<int>(to_output.cols()); }
};

}  // namespace

bool NViewBundleAdjuster::ComputeCovariances(NViewBundleAdjustmentSummary* summary) {
  const auto start = std::chrono::steady_clock::now();
  auto finish = [&](bool ok, const char* why) {
    summary->covariance_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!ok) summary->message = why;
    return ok;
  };
  const bool yaw_only =
      options_.rotation_model == NViewBundleAdjustmentOptions::RotationModel::kYawOnly;
  const int num_images = static_cast<int>(input_.images.size());
  const int rotation_size = yaw_only ? 1 : 3;
  const int size = rotation_size + 3;

  // The varying camera blocks. Tangent -> output through the manifold's Plus Jacobian: yaw -> yaw;
  // quaternion (QuaternionManifold, or the reference's tilt chart) -> omega; centre in W ->
  // C_world = W^T C_W (the scale image's fixed coordinate left out by its SubsetManifold).
  std::vector<CameraBlock> blocks;
  std::unordered_map<const double*, int> block_index;
  int num_camera_parameters = 0;
  for (int k = 0; k < num_images; ++k) {
    double* rotation = RotationBlock(k);
    double* center = centers_[k].data();
    for (double* data : {rotation, center}) {
      if (!problem_->HasParameterBlock(data) || problem_->IsParameterBlockConstant(data)) continue;
      CameraBlock block;
      block.image = k;
      block.offset = num_camera_parameters;
      if (data == center) {
        block.output_offset = rotation_size;
        Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor> plus_jacobian(
            3, problem_->ParameterBlockTangentSize(center));
        if (const ceres::Manifold* manifold = problem_->GetManifold(center)) {
          manifold->PlusJacobian(center, plus_jacobian.data());
        } else {
          plus_jacobian.setIdentity();
        }
        block.to_output = world_aligned_from_world_.transpose() * plus_jacobian;
      } else if (yaw_only) {
        block.to_output = Eigen::MatrixXd::Identity(1, 1);
      } else {
        // Quaternion q (cam_from_W): a change dq of q turns R by omega = 2 vec(dq q^*).
        const int tangent_size = problem_->ParameterBlockTangentSize(rotation);
        Eigen::Matrix<double, 4, Eigen::Dynamic, Eigen::RowMajor> plus_jacobian(4, tangent_size);
        problem_->GetManifold(rotation)->PlusJacobian(rotation, plus_jacobian.data());
        const Eigen::Quaterniond q_conjugate =
            Eigen::Quaterniond(rotation[0], rotation[1], rotation[2], rotation[3]).conjugate();
        block.to_output.resize(3, tangent_size);
        for (int j = 0; j < tangent_size; ++j) {
          const Eigen::Quaterniond dq(plus_jacobian(0, j), plus_jacobian(1, j), plus_jacobian(2, j),
                                      plus_jacobian(3, j));
          block.to_output.col(j) = 2.0 * (dq * q_conjugate).vec();
        }
      }
      block_index[data] = static_cast<int>(blocks.size());
      num_camera_parameters += block.size();
      blocks.push_back(block);
    }
  }

  // S = U - sum_p W_p V_p^+ W_p^T over the used observations (grouped by point) and the priors.
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(num_camera_parameters, num_camera_parameters);
  std::vector<int> order(used_observations_.size());
  for (std::size_t j = 0; j < order.size(); ++j) order[j] = static_cast<int>(j);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return input_.observations[used_observations_[a]].point_index <
           input_.observations[used_observations_[b]].point_index;
  });
  RowMajorMatrix jacobians[3] = {RowMajorMatrix(2, 3), RowMajorMatrix(2, 3), RowMajorMatrix(2, 3)};
  Eigen::Matrix3d v = Eigen::Matrix3d::Zero();
  std::vector<std::pair<int, Eigen::MatrixXd>> w;  // (camera block, J_block^T J_point) of a point
  auto eliminate_point = [&]() {
    // A point's depth along a zero baseline is left out: W_p has no component along it.
    const Eigen::Matrix3d v_inverse = internal::PseudoInverse(v, 1e-12);
    for (const auto& [a, w_a] : w) {
      for (const auto& [b, w_b] : w) {
        s.block(blocks[a].offset, blocks[b].offset, blocks[a].size(), blocks[b].size()) -=
            w_a * v_inverse * w_b.transpose();
      }
    }
    v.setZero();
    w.clear();
  };
  for (std::size_t j = 0; j < order.size(); ++j) {
    const int i = used_observations_[order[j]];
    const NViewObservation& o = input_.observations[i];
    if (j > 0 &&
        input_.observations[used_observations_[order[j - 1]]].point_index != o.point_index) {
      eliminate_point();
    }
    double* parameters[3] = {RotationBlock(o.image_index), centers_[o.image_index].data(),
                             points_[o.point_index].data()};
    double* jacobian_pointers[3];
    for (int b = 0; b < 3; ++b) {
      const bool varies = b == 2 ? !problem_->IsParameterBlockConstant(parameters[2])
                                 : block_index.count(parameters[b]) > 0;
      jacobians[b].resize(2, problem_->ParameterBlockTangentSize(parameters[b]));
      jacobian_pointers[b] = varies ? jacobians[b].data() : nullptr;
    }
    double residuals[2];
    if (!problem_->EvaluateResidualBlock(observation_residuals_[order[j]], true, nullptr, residuals,
                                         jacobian_pointers)) {
      return finish(false, "a residual could not be evaluated: no covariances");
    }
    const bool point_varies = jacobian_pointers[2] != nullptr;
    if (point_varies) v += jacobians[2].transpose() * jacobians[2];
    for (int a = 0; a < 2; ++a) {
      if (jacobian_pointers[a] == nullptr) continue;
      const CameraBlock& block_a = blocks[block_index[parameters[a]]];
      for (int b = 0; b < 2; ++b) {
        if (jacobian_pointers[b] == nullptr) continue;
        const CameraBlock& block_b = blocks[block_index[parameters[b]]];
        s.block(block_a.offset, block_b.offset, block_a.size(), block_b.size()) +=
            jacobians[a].transpose() * jacobians[b];
      }
      if (point_varies) {
        const Eigen::MatrixXd w_a = jacobians[a].transpose() * jacobians[2];
        const int index = block_index[parameters[a]];
        auto found =
            std::find_if(w.begin(), w.end(), [&](const auto& e) { return e.first == index; });
        if (found == w.end()) {
          w.emplace_back(index, w_a);
        } else {
          found->second += w_a;
        }
      }
    }
  }
  eliminate_point();
  for (const ceres::ResidualBlockId id : prior_residuals_) {
    std::vector<double*> parameters;
    problem_->GetParameterBlocksForResidualBlock(id, &parameters);
    const auto found = block_index.find(parameters[0]);
    if (found == block_index.end()) continue;
    const CameraBlock& block = blocks[found->second];
    RowMajorMatrix jacobian(2, block.size());
    double* jacobian_pointer = jacobian.data();
    double residuals[2];
    if (!problem_->EvaluateResidualBlock(id, true, nullptr, residuals, &jacobian_pointer)) {
      return finish(false, "a gravity prior could not be evaluated: no covariances");
    }
    s.block(block.offset, block.offset, block.size(), block.size()) +=
        jacobian.transpose() * jacobian;
  }

  // S^-1 = L^-T L^-1 (S = L L^T); the diagonal blocks from the columns of L^-1.
  const Eigen::LLT<Eigen::MatrixXd> llt(s);
  if (llt.info() != Eigen::Success) {
    return finish(false, "the reduced camera matrix is not positive definite: no covariances");
  }
  const Eigen::MatrixXd l_inverse =
      llt.matrixL().solve(Eigen::MatrixXd::Identity(num_camera_parameters, num_camera_parameters));
  if (!l_inverse.allFinite()) {
    return finish(false, "the reduced camera matrix is singular: no covariances");
  }
  const double variance_px2 = options_.pixel_sigma_px * options_.pixel_sigma_px;
  summary->covariances.assign(num_images, Eigen::MatrixXd::Zero(size, size));
  for (const CameraBlock& a : blocks) {
    for (const CameraBlock& b : blocks) {
      if (a.image != b.image) continue;
      const Eigen::MatrixXd tangent = l_inverse.middleCols(a.offset, a.size()).transpose() *
                                      l_inverse.middleCols(b.offset, b.size());
      summary->covariances[a.image].block(a.output_offset, b.output_offset, a.to_output.rows(),
                                          b.to_output.rows()) =
          variance_px2 * a.to_output * tangent * b.to_output.transpose();
    }
  }
  return finish(true, "");
}

}  // namespace trigrav
