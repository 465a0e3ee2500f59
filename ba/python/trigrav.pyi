"""Type stub of the trigrav module (ba/python/README.md). Arrays are float64 numpy arrays; inputs
accept any array-like of real numbers of the shape given in the comments.

Checked against the built module by tests/python/test_stub.py: every name, member, parameter (name,
order, keyword-only) and default. Defaults are the module's own, written as expressions of the
module (RansacOptions(), InitialSolver.TRIFOCAL_3PT); every enum value and constant ends with
`# value = <repr() of the module's value>`, e.g. `NONE: ClassVar[FailureCause]  # value =
<FailureCause.NONE: 0>`, so that names and integer values are both compared."""

from typing import ClassVar, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
Array = npt.NDArray[np.float64]
Mask = npt.NDArray[np.bool_]

CAMERA_MODELS: Tuple[str, ...]  # value = ('SIMPLE_PINHOLE', 'PINHOLE', 'SIMPLE_RADIAL', 'RADIAL', 'OPENCV', 'OPENCV_FISHEYE')

class CameraPose:
    """x_cam = R @ x_ref + t; center = -R.T @ t."""
    R: Array  # 3 x 3
    t: Array  # (3,)
    def __init__(self, R: Optional[ArrayLike] = None, t: Optional[ArrayLike] = None) -> None: ...
    @property
    def center(self) -> Array: ...
    def inverse(self) -> CameraPose: ...
    def apply(self, points_in_ref: ArrayLike) -> Array: ...  # N x 3 -> N x 3
    def is_finite(self) -> bool: ...
    def __mul__(self, b_from_a: CameraPose) -> CameraPose: ...

class ThreeViewPose:
    cam2_from_cam1: CameraPose
    cam3_from_cam1: CameraPose
    def __init__(
        self, cam2_from_cam1: CameraPose = CameraPose(), cam3_from_cam1: CameraPose = CameraPose()
    ) -> None: ...
    def cam3_from_cam2(self) -> CameraPose: ...
    def is_finite(self) -> bool: ...

class Camera:
    """COLMAP model name and parameter list, e.g. Camera('PINHOLE', [fx, fy, cx, cy])."""
    def __init__(self, model: str, params: Sequence[float]) -> None: ...
    @staticmethod
    def pinhole(fx: float, fy: float, cx: float, cy: float) -> Camera: ...
    @property
    def model(self) -> str: ...
    @property
    def params(self) -> List[float]: ...
    @property
    def focal_x(self) -> float: ...
    @property
    def focal_y(self) -> float: ...
    @property
    def is_pinhole(self) -> bool: ...
    def project(self, points_in_cam: ArrayLike) -> Array: ...  # N x 3 -> N x 2
    def unproject(self, pixels: ArrayLike) -> Array: ...  # N x 2 -> N x 3 rays (u, v, 1)

class ThreeViewObservations:
    pixels: List[Array]  # three N x 2 (copies)
    bearings: List[Array]  # three N x 3 (copies)
    cameras: List[Camera]  # set with one Camera or three
    gravity_in_cam: Array  # 3 x 3, row k: gravity (down) in camera k + 1
    def __init__(
        self,
        *,
        pixels: Optional[Sequence[ArrayLike]] = None,
        cameras: Union[Camera, Sequence[Camera], None] = None,
        gravity_in_cam: Optional[ArrayLike] = None,
        bearings: Optional[Sequence[ArrayLike]] = None,
    ) -> None: ...
    def has_bearings(self) -> bool: ...
    def check(self) -> None: ...
    def __len__(self) -> int: ...

def rotation_about_y(theta_rad: float) -> Array: ...
def gravity_alignment_from_gravity(gravity_in_cam: ArrayLike) -> Array: ...
def gravity_alignment_from_pitch_roll(pitch_rad: float, roll_rad: float) -> Array: ...
def gravity_in_camera(gravity_alignment: ArrayLike) -> Array: ...
def align_rays(gravity_alignment: ArrayLike, rays_in_cam: ArrayLike) -> Array: ...
def unalign_pose(
    aligned_cam_from_aligned_ref: CameraPose,
    gravity_alignment_ref: ArrayLike,
    gravity_alignment_cam: ArrayLike,
) -> CameraPose: ...

class InitialSolver:
    TRIFOCAL_3PT: ClassVar[InitialSolver]  # value = <InitialSolver.TRIFOCAL_3PT: 0>
    TRIFOCAL_3PT_SEXTIC: ClassVar[InitialSolver]  # value = <InitialSolver.TRIFOCAL_3PT_SEXTIC: 1>
    TRIFOCAL_4PT: ClassVar[InitialSolver]  # value = <InitialSolver.TRIFOCAL_4PT: 2>
    TRIFOCAL_LINEAR: ClassVar[InitialSolver]  # value = <InitialSolver.TRIFOCAL_LINEAR: 3>
    ESSENTIAL_5PT: ClassVar[InitialSolver]  # value = <InitialSolver.ESSENTIAL_5PT: 4>
    ESSENTIAL_8PT: ClassVar[InitialSolver]  # value = <InitialSolver.ESSENTIAL_8PT: 5>
    def __init__(self, value: int) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def value(self) -> int: ...
    @property
    def short_name(self) -> str: ...
    @property
    def sample_size(self) -> int: ...
    @property
    def uses_gravity(self) -> bool: ...
    @staticmethod
    def from_short_name(name: str) -> InitialSolver: ...

class Trifocal4ptRecovery:
    ENFORCED: ClassVar[Trifocal4ptRecovery]  # value = <Trifocal4ptRecovery.ENFORCED: 0>
    LEAST_SQUARES: ClassVar[Trifocal4ptRecovery]  # value = <Trifocal4ptRecovery.LEAST_SQUARES: 1>
    PAPER_CLOSED_FORM: ClassVar[Trifocal4ptRecovery]  # value = <Trifocal4ptRecovery.PAPER_CLOSED_FORM: 2>
    LEAST_SQUARES_IF_MINIMAL: ClassVar[Trifocal4ptRecovery]  # value = <Trifocal4ptRecovery.LEAST_SQUARES_IF_MINIMAL: 3>
    def __init__(self, value: int) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def value(self) -> int: ...

class Trifocal4ptEpipoles:
    LEAST_SQUARES_READ_IF_MINIMAL: ClassVar[Trifocal4ptEpipoles]  # value = <Trifocal4ptEpipoles.LEAST_SQUARES_READ_IF_MINIMAL: 0>
    TENSOR_NULL_VECTORS: ClassVar[Trifocal4ptEpipoles]  # value = <Trifocal4ptEpipoles.TENSOR_NULL_VECTORS: 1>
    def __init__(self, value: int) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def value(self) -> int: ...

class Trifocal4ptOptions:
    recovery: Trifocal4ptRecovery
    epipoles: Trifocal4ptEpipoles
    resolve_translations: bool
    epipole_iterations: int
    polish_iterations: int
    def __init__(
        self,
        *,
        recovery: Trifocal4ptRecovery = Trifocal4ptRecovery.LEAST_SQUARES_IF_MINIMAL,
        epipoles: Trifocal4ptEpipoles = Trifocal4ptEpipoles.LEAST_SQUARES_READ_IF_MINIMAL,
        resolve_translations: bool = True,
        epipole_iterations: int = 0,
        polish_iterations: int = 8,
    ) -> None: ...

# x1, x2, x3: N x 3 rays (one row per triplet); gravity_in_cam: 3 x 3 (row k: camera k + 1), or
# None for gravity-aligned rays.
def solve_trifocal_3pt(
    x1: ArrayLike, x2: ArrayLike, x3: ArrayLike, gravity_in_cam: Optional[ArrayLike] = None
) -> List[ThreeViewPose]: ...
def solve_trifocal_3pt_sextic(
    x1: ArrayLike, x2: ArrayLike, x3: ArrayLike, gravity_in_cam: Optional[ArrayLike] = None
) -> List[ThreeViewPose]: ...
def solve_trifocal_4pt(
    x1: ArrayLike,
    x2: ArrayLike,
    x3: ArrayLike,
    gravity_in_cam: Optional[ArrayLike] = None,
    options: Trifocal4ptOptions = Trifocal4ptOptions(),
) -> List[ThreeViewPose]: ...
def solve_trifocal_linear(x1: ArrayLike, x2: ArrayLike, x3: ArrayLike) -> List[ThreeViewPose]: ...
def solve_essential_5pt(x1: ArrayLike, x2: ArrayLike) -> List[CameraPose]: ...
def solve_essential_8pt(x1: ArrayLike, x2: ArrayLike) -> List[CameraPose]: ...
def combine_two_view_pairs(
    x1: ArrayLike,
    x2: ArrayLike,
    x3: ArrayLike,
    pair12: Sequence[CameraPose],
    pair13: Sequence[CameraPose],
) -> Tuple[List[ThreeViewPose], List[float]]: ...

class RansacOptions:
    max_error: float
    confidence: float
    min_iterations: int
    max_iterations: int
    seed: int
    min_inlier_ratio: float
    local_optimization: bool
    local_optimization_rounds: int
    local_optimization_threshold_multiplier: float
    def __init__(
        self,
        *,
        max_error: float = 2.0,
        confidence: float = 0.9999,
        min_iterations: int = 20,
        max_iterations: int = 10000,
        seed: int = 0,
        min_inlier_ratio: float = 0.25,
        local_optimization: bool = True,
        local_optimization_rounds: int = 3,
        local_optimization_threshold_multiplier: float = 3.0,
    ) -> None: ...

class RobustThreeViewOptions:
    TILT_CORRECTION_FROM_GRAVITY_SIGMA: ClassVar[float]  # value = -1.0
    GRAVITY_CONSISTENCY_FROM_GRAVITY_SIGMA: ClassVar[float]  # value = -1.0
    solver: InitialSolver
    ransac: RansacOptions
    max_bearing_error_deg: float
    max_tilt_correction_deg: float
    max_gravity_inconsistency_deg: float
    check_gravity_after_success: bool
    max_pose_sigma_deg: float
    min_inliers: int
    refined_afterwards: bool
    def __init__(
        self,
        *,
        solver: InitialSolver = InitialSolver.TRIFOCAL_3PT,
        ransac: RansacOptions = RansacOptions(),
        max_bearing_error_deg: float = 0.1,
        max_tilt_correction_deg: float = -1.0,
        max_gravity_inconsistency_deg: float = -1.0,
        check_gravity_after_success: bool = True,
        max_pose_sigma_deg: float = 1.25,
        min_inliers: int = 15,
        refined_afterwards: bool = False,
    ) -> None: ...

class RansacStatistics:
    @property
    def num_inliers(self) -> int: ...
    @property
    def iterations(self) -> int: ...
    @property
    def num_models_scored(self) -> int: ...
    @property
    def num_local_optimizations(self) -> int: ...
    @property
    def msac_cost(self) -> float: ...

class GravityConsistency:
    @property
    def measured(self) -> bool: ...
    @property
    def num_inliers(self) -> int: ...
    @property
    def pair_inconsistency_deg(self) -> List[float]: ...
    @property
    def swapped_pair_inconsistency_deg(self) -> List[float]: ...
    @property
    def rotation_disagreement_deg(self) -> List[float]: ...
    @property
    def direction_disagreement_deg(self) -> List[float]: ...
    @property
    def inconsistent_camera(self) -> int: ...

class FailureCause:
    NONE: ClassVar[FailureCause]  # value = <FailureCause.NONE: 0>
    TOO_FEW_TRIPLETS: ClassVar[FailureCause]  # value = <FailureCause.TOO_FEW_TRIPLETS: 1>
    BELOW_INLIER_FLOOR: ClassVar[FailureCause]  # value = <FailureCause.BELOW_INLIER_FLOOR: 2>
    TOO_FEW_INLIERS: ClassVar[FailureCause]  # value = <FailureCause.TOO_FEW_INLIERS: 3>
    CHANCE_CONSENSUS: ClassVar[FailureCause]  # value = <FailureCause.CHANCE_CONSENSUS: 4>
    UNCERTAIN_POSE: ClassVar[FailureCause]  # value = <FailureCause.UNCERTAIN_POSE: 5>
    NO_PARALLAX: ClassVar[FailureCause]  # value = <FailureCause.NO_PARALLAX: 6>
    PIXELS_VS_INTRINSICS: ClassVar[FailureCause]  # value = <FailureCause.PIXELS_VS_INTRINSICS: 7>
    VIEWS_OUT_OF_ORDER: ClassVar[FailureCause]  # value = <FailureCause.VIEWS_OUT_OF_ORDER: 8>
    CAMERA_GRAVITY: ClassVar[FailureCause]  # value = <FailureCause.CAMERA_GRAVITY: 9>
    NOISY_GRAVITY: ClassVar[FailureCause]  # value = <FailureCause.NOISY_GRAVITY: 10>
    OTHER_MOTION: ClassVar[FailureCause]  # value = <FailureCause.OTHER_MOTION: 11>
    REFINEMENT_SHIFT: ClassVar[FailureCause]  # value = <FailureCause.REFINEMENT_SHIFT: 12>
    STOPPED: ClassVar[FailureCause]  # value = <FailureCause.STOPPED: 13>
    def __init__(self, value: int) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def value(self) -> int: ...

class ConsensusEvidence:
    @property
    def log10_nfa(self) -> float: ...
    @property
    def rotation_sigma_deg(self) -> float: ...
    @property
    def direction_sigma_deg(self) -> float: ...
    @property
    def rotation_offset_deg(self) -> float: ...
    @property
    def direction_offset_deg(self) -> float: ...
    def sigma_with_offset_deg(self) -> float: ...

class RobustThreeViewEstimate:
    @property
    def success(self) -> bool: ...
    @property
    def message(self) -> str: ...
    @property
    def cause(self) -> FailureCause: ...
    @property
    def pose(self) -> ThreeViewPose: ...
    @property
    def inliers(self) -> Mask: ...
    @property
    def ransac(self) -> RansacStatistics: ...
    @property
    def gravity(self) -> GravityConsistency: ...
    @property
    def evidence(self) -> ConsensusEvidence: ...

def estimate_three_view_pose_robust(
    observations: ThreeViewObservations, options: RobustThreeViewOptions = RobustThreeViewOptions()
) -> RobustThreeViewEstimate: ...

class ThreeViewBundleAdjustmentOptions:
    class Engine:
        CERES: ClassVar[ThreeViewBundleAdjustmentOptions.Engine]  # value = <Engine.CERES: 0>
        CERES_POINTS_ELIMINATED: ClassVar[ThreeViewBundleAdjustmentOptions.Engine]  # value = <Engine.CERES_POINTS_ELIMINATED: 1>
        def __init__(self, value: int) -> None: ...
        @property
        def name(self) -> str: ...
        @property
        def value(self) -> int: ...
    class RotationModel:
        YAW_ONLY: ClassVar[ThreeViewBundleAdjustmentOptions.RotationModel]  # value = <RotationModel.YAW_ONLY: 0>
        GRAVITY_PRIOR: ClassVar[ThreeViewBundleAdjustmentOptions.RotationModel]  # value = <RotationModel.GRAVITY_PRIOR: 1>
        def __init__(self, value: int) -> None: ...
        @property
        def name(self) -> str: ...
        @property
        def value(self) -> int: ...
    class LossType:
        NONE: ClassVar[ThreeViewBundleAdjustmentOptions.LossType]  # value = <LossType.NONE: 0>
        HUBER: ClassVar[ThreeViewBundleAdjustmentOptions.LossType]  # value = <LossType.HUBER: 1>
        CAUCHY: ClassVar[ThreeViewBundleAdjustmentOptions.LossType]  # value = <LossType.CAUCHY: 2>
        def __init__(self, value: int) -> None: ...
        @property
        def name(self) -> str: ...
        @property
        def value(self) -> int: ...
    class LinearSolverType:
        DENSE_NORMAL_CHOLESKY: ClassVar[ThreeViewBundleAdjustmentOptions.LinearSolverType]  # value = <LinearSolverType.DENSE_NORMAL_CHOLESKY: 0>
        DENSE_QR: ClassVar[ThreeViewBundleAdjustmentOptions.LinearSolverType]  # value = <LinearSolverType.DENSE_QR: 1>
        SPARSE_NORMAL_CHOLESKY: ClassVar[ThreeViewBundleAdjustmentOptions.LinearSolverType]  # value = <LinearSolverType.SPARSE_NORMAL_CHOLESKY: 2>
        DENSE_SCHUR: ClassVar[ThreeViewBundleAdjustmentOptions.LinearSolverType]  # value = <LinearSolverType.DENSE_SCHUR: 3>
        SPARSE_SCHUR: ClassVar[ThreeViewBundleAdjustmentOptions.LinearSolverType]  # value = <LinearSolverType.SPARSE_SCHUR: 4>
        ITERATIVE_SCHUR: ClassVar[ThreeViewBundleAdjustmentOptions.LinearSolverType]  # value = <LinearSolverType.ITERATIVE_SCHUR: 5>
        CGNR: ClassVar[ThreeViewBundleAdjustmentOptions.LinearSolverType]  # value = <LinearSolverType.CGNR: 6>
        def __init__(self, value: int) -> None: ...
        @property
        def name(self) -> str: ...
        @property
        def value(self) -> int: ...
    engine: ThreeViewBundleAdjustmentOptions.Engine
    rotation_model: ThreeViewBundleAdjustmentOptions.RotationModel
    loss: ThreeViewBundleAdjustmentOptions.LossType
    loss_scale_px: float
    pixel_sigma_px: float
    loss_scale_deg: float
    bearing_sigma_deg: float
    gravity_sigma_deg: float
    compute_covariance: bool
    max_num_iterations: int
    num_threads: int
    linear_solver_type: ThreeViewBundleAdjustmentOptions.LinearSolverType
    function_tolerance: float
    gradient_tolerance: float
    parameter_tolerance: float
    def __init__(
        self,
        *,
        engine: ThreeViewBundleAdjustmentOptions.Engine = ThreeViewBundleAdjustmentOptions.Engine.CERES_POINTS_ELIMINATED,
        rotation_model: ThreeViewBundleAdjustmentOptions.RotationModel = ThreeViewBundleAdjustmentOptions.RotationModel.YAW_ONLY,
        loss: ThreeViewBundleAdjustmentOptions.LossType = ThreeViewBundleAdjustmentOptions.LossType.HUBER,
        loss_scale_px: float = 2.0,
        pixel_sigma_px: float = 1.0,
        loss_scale_deg: float = 0.1,
        bearing_sigma_deg: float = 0.05,
        gravity_sigma_deg: float = 0.5,
        compute_covariance: bool = False,
        max_num_iterations: int = 50,
        num_threads: int = 1,
        linear_solver_type: ThreeViewBundleAdjustmentOptions.LinearSolverType = ThreeViewBundleAdjustmentOptions.LinearSolverType.DENSE_SCHUR,
        function_tolerance: float = 1e-8,
        gradient_tolerance: float = 1e-10,
        parameter_tolerance: float = 1e-10,
    ) -> None: ...

class ThreeViewBundleAdjustmentSummary:
    @property
    def success(self) -> bool: ...
    @property
    def message(self) -> str: ...
    @property
    def engine(self) -> ThreeViewBundleAdjustmentOptions.Engine: ...
    @property
    def num_points(self) -> int: ...
    @property
    def num_residual_blocks(self) -> int: ...
    @property
    def solve_s(self) -> float: ...
    @property
    def initial_cost(self) -> float: ...
    @property
    def final_cost(self) -> float: ...
    @property
    def iterations(self) -> int: ...
    def brief_report(self) -> str: ...
    def full_report(self) -> str: ...

class ThreeViewRefinement:
    @property
    def pose(self) -> ThreeViewPose: ...
    @property
    def triplets(self) -> npt.NDArray[np.int32]: ...
    @property
    def points_in_cam1(self) -> Array: ...  # len(triplets) x 3
    @property
    def residual_norms(self) -> Array: ...  # len(triplets) x 3
    @property
    def residual_rms(self) -> float: ...
    @property
    def relative_scale(self) -> float: ...
    @property
    def covariance(self) -> Array: ...  # 7 x 7, 11 x 11, or 0 x 0
    @property
    def summary(self) -> ThreeViewBundleAdjustmentSummary: ...
    @property
    def build_s(self) -> float: ...
    @property
    def covariance_s(self) -> float: ...

def refine_three_view_pose(
    observations: ThreeViewObservations,
    initial: ThreeViewPose,
    inliers: ArrayLike,
    options: ThreeViewBundleAdjustmentOptions = ThreeViewBundleAdjustmentOptions(),
) -> ThreeViewRefinement: ...
def three_view_pose_difference(
    rotation_model: ThreeViewBundleAdjustmentOptions.RotationModel,
    pose: ThreeViewPose,
    reference: ThreeViewPose,
    gravity_in_cam: ArrayLike,
) -> Array: ...

class InitializeAndRefineOptions:
    robust: RobustThreeViewOptions
    refine: bool
    reclassification_rounds: int
    bundle_adjustment: ThreeViewBundleAdjustmentOptions
    def __init__(
        self,
        *,
        robust: RobustThreeViewOptions = RobustThreeViewOptions(),
        refine: bool = True,
        reclassification_rounds: int = 1,
        bundle_adjustment: ThreeViewBundleAdjustmentOptions = ThreeViewBundleAdjustmentOptions(),
    ) -> None: ...

class ThreeViewEstimateTimings:
    @property
    def ransac_s(self) -> float: ...
    @property
    def refinement_s(self) -> float: ...
    @property
    def total_s(self) -> float: ...
    @property
    def build_s(self) -> float: ...
    @property
    def solve_s(self) -> float: ...
    @property
    def covariance_s(self) -> float: ...
    @property
    def reclassification_s(self) -> float: ...

class ThreeViewEstimate:
    @property
    def success(self) -> bool: ...
    @property
    def message(self) -> str: ...
    @property
    def cause(self) -> FailureCause: ...
    @property
    def robust(self) -> RobustThreeViewEstimate: ...
    @property
    def refined(self) -> ThreeViewPose: ...
    @property
    def inliers(self) -> Mask: ...
    @property
    def num_inliers(self) -> int: ...
    @property
    def refinement(self) -> ThreeViewRefinement: ...
    @property
    def refinement_runs(self) -> int: ...
    @property
    def timings(self) -> ThreeViewEstimateTimings: ...

def initialize_and_refine(
    observations: ThreeViewObservations, options: InitializeAndRefineOptions = InitializeAndRefineOptions()
) -> ThreeViewEstimate: ...
def initialize_and_refine_batch(
    batch: Sequence[ThreeViewObservations],
    options: InitializeAndRefineOptions = InitializeAndRefineOptions(),
    num_threads: int = 0,
    return_exceptions: bool = False,
) -> List[Union[ThreeViewEstimate, ValueError]]: ...

class SyntheticSceneOptions:
    num_points: int
    focal_px: float
    opencv_distortion: List[float]
    width_px: float
    height_px: float
    max_yaw_deg: float
    max_tilt_deg: float
    max_center_m: float
    min_depth_m: float
    max_depth_m: float
    min_depth_all_views_m: float
    pixel_noise_px: float
    imu_pitch_noise_deg: float
    imu_roll_noise_deg: float
    outlier_ratio: float
    def __init__(
        self,
        *,
        num_points: int = 4,
        focal_px: float = 500.0,
        opencv_distortion: Sequence[float] = (0.0, 0.0, 0.0, 0.0),
        width_px: float = 640.0,
        height_px: float = 480.0,
        max_yaw_deg: float = 10.0,
        max_tilt_deg: float = 10.0,
        max_center_m: float = 10.0,
        min_depth_m: float = 10.0,
        max_depth_m: float = 40.0,
        min_depth_all_views_m: float = 1.0,
        pixel_noise_px: float = 0.0,
        imu_pitch_noise_deg: float = 0.0,
        imu_roll_noise_deg: float = 0.0,
        outlier_ratio: float = 0.0,
    ) -> None: ...

class SyntheticScene:
    @property
    def ground_truth(self) -> ThreeViewPose: ...
    @property
    def cam_from_world(self) -> List[Array]: ...
    @property
    def center_in_world(self) -> List[Array]: ...
    @property
    def pitch_rad(self) -> List[float]: ...
    @property
    def roll_rad(self) -> List[float]: ...
    @property
    def yaw_rad(self) -> List[float]: ...
    @property
    def points_in_world(self) -> Array: ...
    @property
    def pixels(self) -> List[Array]: ...
    @property
    def rays(self) -> List[Array]: ...
    @property
    def gravity_alignment_true(self) -> List[Array]: ...
    @property
    def gravity_alignment_measured(self) -> List[Array]: ...
    @property
    def gravity_in_cam_measured(self) -> Array: ...
    @property
    def camera(self) -> Camera: ...
    @property
    def is_inlier(self) -> Mask: ...

def generate_synthetic_scene(options: SyntheticSceneOptions = SyntheticSceneOptions(), seed: int = 0) -> SyntheticScene: ...
def to_observations(scene: SyntheticScene) -> ThreeViewObservations: ...
def to_bearing_observations(scene: SyntheticScene) -> ThreeViewObservations: ...

def rotation_error_deg(R_gt: ArrayLike, R: ArrayLike) -> float: ...
def direction_error_deg(a_gt: ArrayLike, a: ArrayLike) -> float: ...

class ThreeViewPoseErrors:
    @property
    def rotation_deg(self) -> List[float]: ...
    @property
    def translation_deg(self) -> List[float]: ...
    @property
    def relative_scale(self) -> float: ...
    def max_rotation_deg(self) -> float: ...
    def max_translation_deg(self) -> float: ...
    def max_angle_deg(self) -> float: ...

def compute_three_view_pose_errors(ground_truth: ThreeViewPose, estimate: ThreeViewPose) -> ThreeViewPoseErrors: ...

class YawTiltErrorDeg:
    @property
    def yaw_deg(self) -> float: ...
    @property
    def tilt_deg(self) -> float: ...

def split_rotation_error_deg(R_gt: ArrayLike, R: ArrayLike, gravity_in_cam: ArrayLike) -> YawTiltErrorDeg: ...
def three_view_errors(observations: ThreeViewObservations, pose: ThreeViewPose) -> Array: ...

# --- N-view gravity-aware bundle adjustment (bind_nview.cc) -----------------------------------

class NViewBundleAdjustmentOptions:
    """The enums are ThreeViewBundleAdjustmentOptions' (one C++ type)."""
    VERDICT_GRAVITY_SIGMA_DEG: ClassVar[float]  # value = 10.0
    MIN_GRAVITY_DISAGREEMENT_BOUND_DEG: ClassVar[float]  # value = 0.02
    MIN_ESTIMATED_GRAVITY_SIGMA_DEG: ClassVar[float]  # value = 0.005
    YAW_ONLY_TEST_SIGMAS: ClassVar[float]  # value = 4.0
    rotation_model: ThreeViewBundleAdjustmentOptions.RotationModel
    loss: ThreeViewBundleAdjustmentOptions.LossType
    loss_scale_px: float
    pixel_sigma_px: float
    gravity_sigma_deg: float
    compute_covariance: bool
    max_num_iterations: int
    num_threads: int
    linear_solver_type: ThreeViewBundleAdjustmentOptions.LinearSolverType
    function_tolerance: float
    gradient_tolerance: float
    parameter_tolerance: float
    check_gravity: bool
    gravity_sigma_from_data: bool
    max_gravity_disagreement_sigmas: float
    def __init__(
        self,
        *,
        rotation_model: ThreeViewBundleAdjustmentOptions.RotationModel = ThreeViewBundleAdjustmentOptions.RotationModel.YAW_ONLY,
        loss: ThreeViewBundleAdjustmentOptions.LossType = ThreeViewBundleAdjustmentOptions.LossType.HUBER,
        loss_scale_px: float = 2.0,
        pixel_sigma_px: float = 1.0,
        gravity_sigma_deg: float = 0.1,
        compute_covariance: bool = False,
        max_num_iterations: int = 100,
        num_threads: int = 1,
        linear_solver_type: ThreeViewBundleAdjustmentOptions.LinearSolverType = ThreeViewBundleAdjustmentOptions.LinearSolverType.SPARSE_SCHUR,
        function_tolerance: float = 1e-06,
        gradient_tolerance: float = 1e-10,
        parameter_tolerance: float = 1e-08,
        check_gravity: bool = True,
        gravity_sigma_from_data: bool = True,
        max_gravity_disagreement_sigmas: float = 5.0,
    ) -> None: ...

class NViewBundleAdjustmentConfig:
    reference_image: int
    scale_image: int
    constant_images: List[int]
    images_without_gravity: List[int]
    constant_points: bool
    def __init__(
        self,
        *,
        reference_image: int = 0,
        scale_image: int = -1,
        constant_images: List[int] = [],
        images_without_gravity: List[int] = [],
        constant_points: bool = False,
    ) -> None: ...

class NViewImage:
    camera_index: int
    cam_from_world: CameraPose
    gravity_in_cam: Array  # (3,), a copy
    def __init__(self, camera_index: int, cam_from_world: CameraPose, gravity_in_cam: ArrayLike) -> None: ...

class NViewReconstruction:
    """Array properties are copies; assign to change them."""
    cameras: List[Camera]
    images: List[NViewImage]
    points_in_world: Array  # P x 3
    def __init__(
        self,
        cameras: List[Camera] = [],
        images: List[NViewImage] = [],
        points_in_world: Optional[ArrayLike] = None,  # P x 3
        observation_image_indices: Optional[ArrayLike] = None,  # (M,)
        observation_point_indices: Optional[ArrayLike] = None,  # (M,)
        observation_pixels: Optional[ArrayLike] = None,  # M x 2
    ) -> None: ...
    @property
    def observation_image_indices(self) -> npt.NDArray[np.int32]: ...
    @property
    def observation_point_indices(self) -> npt.NDArray[np.int32]: ...
    @property
    def observation_pixels(self) -> Array: ...  # M x 2
    @property
    def cams_from_world_R(self) -> Array: ...  # N x 3 x 3
    @property
    def cams_from_world_t(self) -> Array: ...  # N x 3
    @property
    def centers(self) -> Array: ...  # N x 3
    @property
    def gravity_in_cam(self) -> Array: ...  # N x 3
    @property
    def num_observations(self) -> int: ...
    def check(self) -> None: ...

class NViewBundleAdjustmentSummary:
    @property
    def success(self) -> bool: ...
    @property
    def message(self) -> str: ...
    @property
    def num_images(self) -> int: ...
    @property
    def num_points(self) -> int: ...
    @property
    def num_observations(self) -> int: ...
    @property
    def num_skipped_observations(self) -> int: ...
    @property
    def gravity_in_world(self) -> Array: ...  # (3,)
    @property
    def residual_rms_px(self) -> Array: ...  # (N,)
    @property
    def covariances(self) -> List[Array]: ...  # N of 4 x 4 or 6 x 6, or []
    @property
    def observations_per_image(self) -> npt.NDArray[np.int32]: ...
    @property
    def images_losing_observations(self) -> npt.NDArray[np.int32]: ...
    @property
    def rotation_model(self) -> ThreeViewBundleAdjustmentOptions.RotationModel: ...
    @property
    def gravity_sigma_deg(self) -> float: ...
    @property
    def gravity_disagreement_deg(self) -> Array: ...  # (N,), empty without the verdict
    @property
    def gravity_used(self) -> Mask: ...  # (N,), empty without the verdict
    @property
    def estimated_gravity_sigma_deg(self) -> float: ...
    @property
    def solve_s(self) -> float: ...
    @property
    def covariance_s(self) -> float: ...
    @property
    def initial_cost(self) -> float: ...
    @property
    def final_cost(self) -> float: ...
    @property
    def iterations(self) -> int: ...
    def brief_report(self) -> str: ...
    def full_report(self) -> str: ...

def refine_with_gravity(
    reconstruction: NViewReconstruction,
    config: NViewBundleAdjustmentConfig = NViewBundleAdjustmentConfig(),
    options: NViewBundleAdjustmentOptions = NViewBundleAdjustmentOptions(),
) -> Tuple[NViewBundleAdjustmentSummary, NViewReconstruction]: ...
def upright_reconstruction(reconstruction: NViewReconstruction, gravity_in_world: ArrayLike) -> NViewReconstruction: ...

# --- COLMAP: models, database, gravity CSV, triplets (bind_colmap.cc; built with trigrav::colmap)

class ModelFormat:
    TEXT: ClassVar[ModelFormat]  # value = <ModelFormat.TEXT: 0>
    BINARY: ClassVar[ModelFormat]  # value = <ModelFormat.BINARY: 1>
    def __init__(self, value: int) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def value(self) -> int: ...

class ColmapCamera:
    camera_id: int
    camera: Camera
    width: int
    height: int
    def __init__(self, camera_id: int, camera: Camera, width: int, height: int) -> None: ...

class ColmapImage:
    image_id: int
    name: str
    camera_id: int
    cam_from_world: CameraPose
    points2D: Array  # N x 2, a copy
    point3D_ids: npt.NDArray[np.int64]  # (N,), -1 for none, a copy
    def __init__(
        self,
        image_id: int,
        name: str,
        camera_id: int,
        cam_from_world: CameraPose = CameraPose(),
        points2D: Optional[ArrayLike] = None,
        point3D_ids: Optional[ArrayLike] = None,
    ) -> None: ...

class ColmapPoint3D:
    xyz: Array  # (3,), a copy
    color: npt.NDArray[np.uint8]  # (3,)
    error: float
    track: npt.NDArray[np.uint32]  # K x 2 (image_id, point2D_idx)
    def __init__(
        self, xyz: ArrayLike, color: Optional[ArrayLike] = None, error: float = -1.0, track: Optional[ArrayLike] = None
    ) -> None: ...

class Reconstruction:
    """cameras, images, points3D: dicts of copies keyed by id; assign a dict to change them."""
    cameras: Dict[int, ColmapCamera]
    images: Dict[int, ColmapImage]
    points3D: Dict[int, ColmapPoint3D]
    def __init__(self) -> None: ...
    @property
    def num_cameras(self) -> int: ...
    @property
    def num_images(self) -> int: ...
    @property
    def num_points3D(self) -> int: ...
    @property
    def point3D_ids(self) -> npt.NDArray[np.uint64]: ...
    @property
    def points3D_xyz(self) -> Array: ...  # P x 3
    def check(self) -> None: ...

def read_model(folder: str, format: Optional[ModelFormat] = None) -> Reconstruction: ...
def write_model(
    reconstruction: Reconstruction, folder: str, format: ModelFormat = ModelFormat.BINARY, create_parents: bool = False
) -> None: ...

class DatabaseImage:
    image_id: int
    name: str
    camera_id: int
    def __init__(self, image_id: int, name: str, camera_id: int) -> None: ...

class TwoViewGeometry:
    image_id1: int
    image_id2: int
    config: int
    matches: npt.NDArray[np.uint32]  # K x 2, a copy
    def __init__(self, image_id1: int, image_id2: int, config: int, matches: ArrayLike) -> None: ...

class Database:
    def __init__(self, path: str) -> None: ...
    @property
    def path(self) -> str: ...
    def read_cameras(self) -> List[ColmapCamera]: ...
    def read_images(self) -> List[DatabaseImage]: ...
    def read_keypoints(self, image_id: int) -> Array: ...  # N x 2
    def read_two_view_geometries(self) -> List[TwoViewGeometry]: ...
    def close(self) -> None: ...
    @property
    def closed(self) -> bool: ...
    def __enter__(self) -> Database: ...
    def __exit__(self, exc_type: object, exc_value: object, traceback: object) -> None: ...

def pair_id(image_id1: int, image_id2: int) -> int: ...
def images_of_pair_id(pair_id: int) -> Tuple[int, int]: ...
def read_gravity_csv(path: str) -> Dict[str, Array]: ...
def write_gravity_csv(gravity: Dict[str, ArrayLike], path: str) -> None: ...
def gravity_of_images(gravity: Dict[str, ArrayLike], image_names: List[str]) -> Array: ...  # N x 3

class MatchGraph:
    def __init__(self, geometries: List[TwoViewGeometry]) -> None: ...
    def num_matches(self, a: int, b: int) -> int: ...
    def match(self, a: int, keypoint_a: int, b: int) -> Optional[int]: ...
    def matches(self, a: int, b: int) -> npt.NDArray[np.uint32]: ...  # K x 2
    def neighbors(self, image: int) -> npt.NDArray[np.uint32]: ...

def three_view_tracks(graph: MatchGraph, images: ArrayLike) -> npt.NDArray[np.uint32]: ...  # N x 3
def consecutive_triplets(images_by_name: ArrayLike) -> npt.NDArray[np.uint32]: ...  # M x 3
def connected_triplets(graph: MatchGraph, images_by_name: ArrayLike, max_triplets: int) -> npt.NDArray[np.uint32]: ...

class TripletResult:
    images: List[DatabaseImage]  # 3, a copy
    num_tracks: int
    estimated: bool
    estimate: ThreeViewEstimate
    def __init__(
        self,
        images: Sequence[DatabaseImage],
        num_tracks: int = 0,
        estimated: bool = False,
        estimate: Optional[ThreeViewEstimate] = None,
    ) -> None: ...
    @property
    def verdict(self) -> str: ...

def triplet_verdict(result: TripletResult) -> str: ...
def format_triplet_csv(results: List[TripletResult], rotation_model: ThreeViewBundleAdjustmentOptions.RotationModel) -> str: ...
def triplet_model(
    cameras: List[ColmapCamera],
    images: Sequence[DatabaseImage],
    keypoints: Sequence[ArrayLike],
    tracks: ArrayLike,
    estimate: ThreeViewEstimate,
) -> Reconstruction: ...

class NViewInput:
    reconstruction: NViewReconstruction
    @property
    def image_ids(self) -> npt.NDArray[np.uint32]: ...
    @property
    def point_ids(self) -> npt.NDArray[np.uint64]: ...

def to_nview(model: Reconstruction, gravity: Dict[str, ArrayLike]) -> NViewInput: ...
def from_nview(model: Reconstruction, input: NViewInput, refined: NViewReconstruction) -> Reconstruction: ...
