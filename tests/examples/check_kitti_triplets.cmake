# Runs kitti_triplets on frames 20-29 of KITTI sequence 00 (8 triplets) and checks its output:
#   cmake -DEXE=<kitti_triplets> -DKITTI_DIR=<folder> -DWORK_DIR=<folder> [-DPEERS=ON]
#         -P check_kitti_triplets.cmake
# $TRIGRAV_KITTI_DIR, when set, replaces KITTI_DIR. Without the data the script prints
# "kitti_triplets test skipped: ..." and succeeds (the ctest's SKIP_REGULAR_EXPRESSION).
#
# 1. Exact gravity, 3pt raw and refined: the calibration of calib.txt, at least 300 tracks in every
#    triplet, ground-truth steps of 0.3-1.5 m (10 Hz), every stage without failure or gross error,
#    rotation below 0.1 deg, translation below 3 deg, inliers above 80 % of the tracks, ATE below
#    0.5 m over the 8 m driven; the raw upright estimate has no tilt error, only yaw.
# 2. The same run again from the feature and match cache of run 1 (9 pair matches; one of them
#    overwritten with a foreign file first, which must be matched again and rewritten) (with PEERS,
#    the peers too): no frame is detected and the 3pt rows of poses.csv are those of run 1 (the
#    cache round-trips). With PEERS:
#    OpenCV's USAC-MAGSAC row below 0.1 deg and the ratio table trigrav / peer.
# 3. 0.1 deg of IMU noise on each frame's pitch and roll: the upright raw estimate inherits the
#    tilt error (> 0.05 deg), and the gravity-prior refinement, whose RANSAC corrects the tilt, wins
#    it back (no gross error, rotation below 0.08 deg, tilt below half the raw one).

cmake_minimum_required(VERSION 3.21)
include(${CMAKE_CURRENT_LIST_DIR}/script_checks.cmake)

if(NOT IS_DIRECTORY "${KITTI_DIR}/sequences/00/image_0" OR NOT EXISTS "${KITTI_DIR}/poses/00.txt")
  message("kitti_triplets test skipped: KITTI odometry data not found in ${KITTI_DIR} (set "
          "TRIGRAV_KITTI_DIR to a folder with sequences/00 and poses/00.txt)")
  return()
endif()


# <out> = floor(|value| * 1e6) with value's sign, an integer for math(EXPR); value as printed by
# %g or %f ("0.0227", "-1.5e-07", "662.5"); "inf" gives 10^15.
function(to_micro value out)
  if(value MATCHES "^-?inf$")
    set(${out} 1000000000000000 PARENT_SCOPE)
    return()
  endif()
  if(NOT value MATCHES "^(-?)([0-9]*)\\.?([0-9]*)([eE]([-+]?[0-9]+))?$")
    message(FATAL_ERROR "not a number: \"${value}\"")
  endif()
  set(sign "${CMAKE_MATCH_1}")
  set(digits "${CMAKE_MATCH_2}${CMAKE_MATCH_3}")
  string(LENGTH "${CMAKE_MATCH_3}" num_fraction_digits)
  set(exponent 0)
  if(NOT "${CMAKE_MATCH_5}" STREQUAL "")
    set(exponent "${CMAKE_MATCH_5}")
  endif()
  math(EXPR shift "${exponent} - ${num_fraction_digits} + 6")
  if(shift GREATER_EQUAL 0)
    string(REPEAT "0" ${shift} zeros)
    string(APPEND digits "${zeros}")
  else()
    string(LENGTH "${digits}" length)
    math(EXPR keep "${length} + ${shift}")
    if(keep LESS_EQUAL 0)
      set(digits "0")
    else()
      string(SUBSTRING "${digits}" 0 ${keep} digits)
    endif()
  endif()
  string(REGEX REPLACE "^0+" "" digits "${digits}")
  if(digits STREQUAL "")
    set(${out} 0 PARENT_SCOPE)
  else()
    set(${out} "${sign}${digits}" PARENT_SCOPE)
  endif()
endfunction()

# Runs kitti_triplets with the common flags and ARGN; sets <name>_output (stdout).
function(run_kitti_triplets name)
  execute_process(
    COMMAND ${EXE} --kitti_dir=${KITTI_DIR} --sequence=00 --first_frame=20 --last_frame=29
      --methods=3pt --cache_dir=${WORK_DIR}/cache --output_dir=${WORK_DIR}/${name} ${ARGN}
    RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
  message("--- kitti_triplets ${ARGN} (${name}):\n${output}")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "kitti_triplets (${name}) exited with ${result}:\n${errors}")
  endif()
  set(${name}_output "${output}" PARENT_SCOPE)
endfunction()

# Sets <prefix>_<method>_<stage>_<column> for every row and column of a summary.csv (numbers as
# to_micro integers, "triplets", "failures" and "gross" as they are), and <prefix>_rows.
function(read_summary path prefix)
  file(STRINGS "${path}" lines)
  list(POP_FRONT lines header_line)
  string(REPLACE "," ";" header "${header_line}")
  list(LENGTH header num_columns)
  math(EXPR last "${num_columns} - 1")
  set(rows "")
  foreach(line IN LISTS lines)
    string(REPLACE "," ";" fields "${line}")
    list(GET fields 0 method)
    list(GET fields 1 stage)
    list(APPEND rows "${method}_${stage}")
    foreach(c RANGE 2 ${last})
      list(GET header ${c} column)
      list(GET fields ${c} value)
      if(NOT column MATCHES "^(triplets|failures|gross)$")
        to_micro("${value}" value)
      endif()
      set(${prefix}_${method}_${stage}_${column} "${value}" PARENT_SCOPE)
    endforeach()
  endforeach()
  set(${prefix}_rows "${rows}" PARENT_SCOPE)
endfunction()

# The rows of a poses.csv whose method is `method`, without the time column (the last one).
function(read_poses path method out)
  file(STRINGS "${path}" lines)
  set(rows "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^[0-9]+,${method},")
      # Without time_ms, the 20th column (the message, quoted, may hold commas: it comes last).
      string(REGEX REPLACE "^(([^,]*,)[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,)[^,]*,(.*)$" "\\1\\3" line "${line}")
      list(APPEND rows "${line}")
    endif()
  endforeach()
  set(${out} "${rows}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")

# 1. Exact gravity.
run_kitti_triplets(exact)
expect_match("calibration of sequence 00 (fx 718.856, fy 718.856, cx 607.193, cy 185.216)"
  "${exact_output}" "camera \\(P0 of calib.txt\\): fx 718.856, fy 718.856, cx 607.193, cy 185.216 px")
expect_match("every frame detected in the first run" "${exact_output}" "\\(10 frames detected")
if(exact_output MATCHES "tracks per triplet: median [0-9]+, min ([0-9]+)")
  expect("at least 300 tracks per triplet (min ${CMAKE_MATCH_1})" CMAKE_MATCH_1 GREATER_EQUAL 300)
else()
  list(APPEND failures "no line \"tracks per triplet\"")
endif()
file(STRINGS "${WORK_DIR}/exact/trajectories.csv" trajectory)
set(previous "")
foreach(line IN LISTS trajectory)
  if(NOT line MATCHES "^3pt,raw,([0-9]+),[^,]*,[^,]*,[^,]*,([^,]*),([^,]*),([^,]*),")
    continue()
  endif()
  set(frame ${CMAKE_MATCH_1})
  to_micro(${CMAKE_MATCH_2} x)
  to_micro(${CMAKE_MATCH_3} y)
  to_micro(${CMAKE_MATCH_4} z)
  if(previous)
    list(GET previous 0 px)
    list(GET previous 1 py)
    list(GET previous 2 pz)
    math(EXPR squared "(${x} - ${px}) * (${x} - ${px}) + (${y} - ${py}) * (${y} - ${py}) + (${z} - ${pz}) * (${z} - ${pz})")
    expect("ground-truth step to frame ${frame} between 0.3 and 1.5 m"
      squared GREATER 90000000000 AND squared LESS 2250000000000)
  endif()
  set(previous ${x} ${y} ${z})
endforeach()
read_summary("${WORK_DIR}/exact/summary.csv" exact)
list(JOIN exact_rows " " exact_rows_text)
expect("stages 3pt raw, yaw-only, gravity-prior (got ${exact_rows_text})"
  exact_rows_text STREQUAL "3pt_raw 3pt_yaw-only 3pt_gravity-prior")
foreach(stage raw yaw-only gravity-prior)
  set(p exact_3pt_${stage})
  expect("${stage}: 8 triplets" ${p}_triplets EQUAL 8)
  expect("${stage}: no failure" ${p}_failures EQUAL 0)
  expect("${stage}: no gross error" ${p}_gross EQUAL 0)
  expect("${stage}: rotation < 0.1 deg" ${p}_median_rot_deg LESS 100000)
  expect("${stage}: translation < 3 deg" ${p}_median_trans_deg LESS 3000000)
  math(EXPR inliers_x5 "${${p}_median_inliers} * 5")
  math(EXPR tracks_x4 "${${p}_median_tracks} * 4")
  expect("${stage}: inliers > 80 % of the tracks" inliers_x5 GREATER tracks_x4)
  expect("${stage}: ATE < 0.5 m" ${p}_ate_rmse_m LESS 500000)
endforeach()
expect("exact gravity: raw tilt error 0" exact_3pt_raw_median_tilt_deg EQUAL 0)
math(EXPR yaw_minus_rotation "${exact_3pt_raw_median_yaw_deg} - ${exact_3pt_raw_median_rot_deg}")
expect("exact gravity: raw rotation error is all yaw"
  yaw_minus_rotation GREATER_EQUAL -1 AND yaw_minus_rotation LESS_EQUAL 1)

# 2. From the cache (and the peers).
file(GLOB match_files "${WORK_DIR}/cache/*.match")
list(LENGTH match_files num_match_files)
expect("the first run caches the 9 pair matches (${num_match_files})" num_match_files EQUAL 9)
list(GET match_files 4 foreign_match_file)
file(WRITE "${foreign_match_file}" "not a match cache")
if(PEERS)
  run_kitti_triplets(cached --peers)
else()
  run_kitti_triplets(cached)
endif()
expect_match("second run: every frame from the cache"
  "${cached_output}" "\\(0 frames detected, median 0 ms per frame on one thread; 10 from the cache\\)")
read_poses("${WORK_DIR}/exact/poses.csv" 3pt exact_poses)
read_poses("${WORK_DIR}/cached/poses.csv" 3pt cached_poses)
expect("cached features and matches give the same 3pt estimates" exact_poses STREQUAL cached_poses)
file(SIZE "${foreign_match_file}" rewritten_size)
expect("a foreign match cache file is rewritten (${rewritten_size} bytes)" rewritten_size GREATER 100)
if(PEERS)
  read_summary("${WORK_DIR}/cached/summary.csv" cached)
  expect("an opencv-usac-magsac row" "opencv-usac-magsac_raw" IN_LIST cached_rows)
  expect("opencv-usac-magsac: rotation < 0.1 deg"
    cached_opencv-usac-magsac_raw_median_rot_deg LESS 100000)
  expect_match("a ratio table trigrav / peer with a row 3pt gravity-prior"
    "${cached_output}" "ratios trigrav / peer.*\n3pt +gravity-prior +[0-9.]+ / [0-9.]+ / [0-9.]+")
endif()
expect_match("second run: last line" "${cached_output}" "\ntime: features [^\n]*threads\n$")

# 3. IMU noise.
run_kitti_triplets(imu --imu_noise_deg=0.1)
read_summary("${WORK_DIR}/imu/summary.csv" imu)
expect_match("0.1 deg IMU: gravity sigma 0.1 deg" "${imu_output}" "gravity sigma 0.100 deg")
expect("0.1 deg IMU: raw tilt error > 0.05 deg" imu_3pt_raw_median_tilt_deg GREATER 50000)
expect("0.1 deg IMU: gravity-prior without gross error" imu_3pt_gravity-prior_gross EQUAL 0)
expect("0.1 deg IMU: gravity-prior rotation < 0.08 deg"
  imu_3pt_gravity-prior_median_rot_deg LESS 80000)
math(EXPR tilt_x2 "${imu_3pt_gravity-prior_median_tilt_deg} * 2")
expect("0.1 deg IMU: gravity-prior tilt below half the raw tilt"
  tilt_x2 LESS imu_3pt_raw_median_tilt_deg)
expect("0.1 deg IMU: gravity-prior translation < 3 deg"
  imu_3pt_gravity-prior_median_trans_deg LESS 3000000)

report_failures(kitti_triplets)
