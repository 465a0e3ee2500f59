# The ctests of the COLMAP tools (examples/colmap/), added when they are built (with
# trigrav::colmap; the library code they call is tested in tests/colmap/): bad flags (exit
# status 2 and "error: <message>", bad_flag_test.cmake), the synthetic end-to-end run of
# make_gravity_csv and gravity_bundle_adjuster with bad input (check_colmap_tools.cmake), and the
# README's walkthrough with the real COLMAP on five KITTI frames (check_colmap_walkthrough.cmake;
# skipped with a message without colmap or the data).
if(NOT TARGET gravity_bundle_adjuster)
  return()
endif()

set(positive "must be positive and finite")
set(no_dir /nonexistent_trigrav_dir)

# make_gravity_csv: flags are checked before any file is read.
set(gravity_ok --poses_path=${CMAKE_CURRENT_LIST_FILE} --image_path=${CMAKE_CURRENT_LIST_DIR}
  --output_path=${CMAKE_CURRENT_BINARY_DIR}/bad_flag_gravity.csv)
trigrav_add_bad_flag_test(make_gravity_csv_no_poses make_gravity_csv "--poses_path is required"
  --image_path=${CMAKE_CURRENT_LIST_DIR} --output_path=g.csv)
trigrav_add_bad_flag_test(make_gravity_csv_missing_poses make_gravity_csv
  "--poses_path=${no_dir}/poses.txt is not a file" --poses_path=${no_dir}/poses.txt
  --image_path=${CMAKE_CURRENT_LIST_DIR} --output_path=g.csv)
trigrav_add_bad_flag_test(make_gravity_csv_missing_images make_gravity_csv
  "--image_path=${no_dir} is not a folder" --poses_path=${CMAKE_CURRENT_LIST_FILE}
  --image_path=${no_dir} --output_path=g.csv)
trigrav_add_bad_flag_test(make_gravity_csv_no_output make_gravity_csv
  "--output_path is required" --poses_path=${CMAKE_CURRENT_LIST_FILE}
  --image_path=${CMAKE_CURRENT_LIST_DIR})
trigrav_add_bad_flag_test(make_gravity_csv_negative_noise make_gravity_csv
  "--noise_deg must be finite and >= 0" ${gravity_ok} --noise_deg=-1)
trigrav_add_bad_flag_test(make_gravity_csv_nan_noise make_gravity_csv
  "--noise_deg must be finite and >= 0" ${gravity_ok} --noise_deg=nan)

# triplet_initializer: any existing file passes --database_path's check.
set(initializer_ok --database_path=${CMAKE_CURRENT_LIST_FILE} --gravity_csv=g.csv
  --output_csv=${CMAKE_CURRENT_BINARY_DIR}/bad_flag_triplets.csv
  --output_model_path=${CMAKE_CURRENT_BINARY_DIR}/bad_flag_seed)
trigrav_add_bad_flag_test(triplet_initializer_no_database triplet_initializer
  "--database_path is required" --gravity_csv=g.csv --output_csv=t.csv --output_model_path=m)
trigrav_add_bad_flag_test(triplet_initializer_missing_database triplet_initializer
  "--database_path=${no_dir}/db.db is not a file" --database_path=${no_dir}/db.db
  --gravity_csv=g.csv --output_csv=t.csv --output_model_path=m)
trigrav_add_bad_flag_test(triplet_initializer_no_gravity triplet_initializer
  "--gravity_csv is required" --database_path=${CMAKE_CURRENT_LIST_FILE} --output_csv=t.csv
  --output_model_path=m)
trigrav_add_bad_flag_test(triplet_initializer_unknown_triplets triplet_initializer
  "--triplets must be consecutive or connected" ${initializer_ok} --triplets=all)
trigrav_add_bad_flag_test(triplet_initializer_negative_max_triplets triplet_initializer
  "--max_triplets must be >= 0" ${initializer_ok} --max_triplets=-1)
trigrav_add_bad_flag_test(triplet_initializer_two_tracks triplet_initializer
  "--min_tracks must be >= 3" ${initializer_ok} --min_tracks=2)
trigrav_add_bad_flag_test(triplet_initializer_nan_threshold triplet_initializer
  "--threshold_px ${positive}" ${initializer_ok} --threshold_px=nan)
trigrav_add_bad_flag_test(triplet_initializer_zero_threshold triplet_initializer
  "--threshold_px ${positive}" ${initializer_ok} --threshold_px=0)
trigrav_add_bad_flag_test(triplet_initializer_unknown_rotation_model triplet_initializer
  "--rotation_model must be yaw_only or gravity_prior" ${initializer_ok} --rotation_model=free)
trigrav_add_bad_flag_test(triplet_initializer_zero_gravity_sigma triplet_initializer
  "--gravity_sigma_deg ${positive}" ${initializer_ok} --gravity_sigma_deg=0)
trigrav_add_bad_flag_test(triplet_initializer_unknown_engine triplet_initializer
  "--engine must be ceres or ceres_points_eliminated" ${initializer_ok} --engine=gpu)
trigrav_add_bad_flag_test(triplet_initializer_zero_threads triplet_initializer
  "--threads must be in \\[1, 256\\]" ${initializer_ok} --threads=0)
trigrav_add_bad_flag_test(triplet_initializer_unknown_solver triplet_initializer
  "unknown --solver=6pt" ${initializer_ok} --solver=6pt)

# gravity_bundle_adjuster: any existing folder passes --input_path's check.
set(adjuster_ok --input_path=${CMAKE_CURRENT_LIST_DIR} --gravity_csv=g.csv
  --output_path=${CMAKE_CURRENT_BINARY_DIR}/bad_flag_refined)
trigrav_add_bad_flag_test(gravity_bundle_adjuster_no_input gravity_bundle_adjuster
  "--input_path is required" --gravity_csv=g.csv --output_path=out)
trigrav_add_bad_flag_test(gravity_bundle_adjuster_missing_input gravity_bundle_adjuster
  "--input_path=${no_dir} is not a folder" --input_path=${no_dir} --gravity_csv=g.csv
  --output_path=out)
trigrav_add_bad_flag_test(gravity_bundle_adjuster_no_output gravity_bundle_adjuster
  "--output_path is required" --input_path=${CMAKE_CURRENT_LIST_DIR} --gravity_csv=g.csv)
trigrav_add_bad_flag_test(gravity_bundle_adjuster_unknown_format gravity_bundle_adjuster
  "--output_format must be binary or text" ${adjuster_ok} --output_format=ply)
trigrav_add_bad_flag_test(gravity_bundle_adjuster_unknown_rotation_model gravity_bundle_adjuster
  "--rotation_model must be yaw_only or gravity_prior" ${adjuster_ok} --rotation_model=free)
trigrav_add_bad_flag_test(gravity_bundle_adjuster_nan_gravity_sigma gravity_bundle_adjuster
  "--gravity_sigma_deg must be >= 0 and finite" ${adjuster_ok} --gravity_sigma_deg=nan)
trigrav_add_bad_flag_test(gravity_bundle_adjuster_negative_gravity_sigma gravity_bundle_adjuster
  "--gravity_sigma_deg must be >= 0 and finite" ${adjuster_ok} --gravity_sigma_deg=-1)
trigrav_add_bad_flag_test(gravity_bundle_adjuster_small_rms_growth gravity_bundle_adjuster
  "--max_rms_growth must be 0 \\(off\\) or a finite factor >= 1" ${adjuster_ok}
  --max_rms_growth=0.5)
trigrav_add_bad_flag_test(gravity_bundle_adjuster_unknown_loss gravity_bundle_adjuster
  "--loss must be huber, cauchy or none" ${adjuster_ok} --loss=l1)
trigrav_add_bad_flag_test(gravity_bundle_adjuster_zero_loss_scale gravity_bundle_adjuster
  "--loss_scale_px ${positive}" ${adjuster_ok} --loss_scale_px=0)
trigrav_add_bad_flag_test(gravity_bundle_adjuster_negative_iterations gravity_bundle_adjuster
  "--max_iterations must be >= 0" ${adjuster_ok} --max_iterations=-1)
trigrav_add_bad_flag_test(gravity_bundle_adjuster_zero_threads gravity_bundle_adjuster
  "--threads must be in \\[1, 256\\]" ${adjuster_ok} --threads=0)

# The synthetic end-to-end run and its bad input.
add_executable(write_synthetic_colmap_model
  ${CMAKE_CURRENT_LIST_DIR}/write_synthetic_colmap_model.cc)
target_link_libraries(write_synthetic_colmap_model PRIVATE trigrav::colmap trigrav_warnings)
add_test(NAME colmap_tools_synthetic
  COMMAND ${CMAKE_COMMAND} -DMAKE_GRAVITY=$<TARGET_FILE:make_gravity_csv>
    -DADJUSTER=$<TARGET_FILE:gravity_bundle_adjuster>
    -DWRITER=$<TARGET_FILE:write_synthetic_colmap_model>
    -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/colmap_tools_synthetic
    -P ${CMAKE_CURRENT_LIST_DIR}/check_colmap_tools.cmake)
set_tests_properties(colmap_tools_synthetic PROPERTIES TIMEOUT 300)

# The README's walkthrough with the real COLMAP (about 30 s on 2 cores).
find_program(TRIGRAV_COLMAP_EXECUTABLE colmap)
if(NOT TRIGRAV_COLMAP_EXECUTABLE)
  set(TRIGRAV_COLMAP_EXECUTABLE "")
endif()
add_test(NAME colmap_walkthrough_kitti
  COMMAND ${CMAKE_COMMAND} -DCOLMAP=${TRIGRAV_COLMAP_EXECUTABLE}
    -DMAKE_GRAVITY=$<TARGET_FILE:make_gravity_csv>
    -DINITIALIZER=$<TARGET_FILE:triplet_initializer>
    -DADJUSTER=$<TARGET_FILE:gravity_bundle_adjuster>
    -DKITTI_DIR=${PROJECT_SOURCE_DIR}/../shared/data/kitti
    -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/colmap_walkthrough_kitti
    -P ${CMAKE_CURRENT_LIST_DIR}/check_colmap_walkthrough.cmake)
set_tests_properties(colmap_walkthrough_kitti PROPERTIES TIMEOUT 300
  SKIP_REGULAR_EXPRESSION "colmap walkthrough test skipped")
