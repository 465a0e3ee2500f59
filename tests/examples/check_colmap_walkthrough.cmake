# The README's walkthrough (examples/colmap/README.md) with the real COLMAP on KITTI 00 frames 0-4:
# feature_extractor, sequential_matcher, make_gravity_csv, triplet_initializer, mapper continuing
# from the seed triplet, gravity_bundle_adjuster.
#   cmake -DCOLMAP=<colmap> -DMAKE_GRAVITY=<make_gravity_csv> -DINITIALIZER=<triplet_initializer>
#         -DADJUSTER=<gravity_bundle_adjuster> -DKITTI_DIR=<folder> -DWORK_DIR=<folder>
#         -P check_colmap_walkthrough.cmake
# $TRIGRAV_KITTI_DIR, when set, replaces KITTI_DIR. Without colmap or the data the script prints
# "colmap walkthrough test skipped: ..." and succeeds (the ctest's SKIP_REGULAR_EXPRESSION).
# Checks: 3 consecutive triplets, at least one trusted; the seed model has 3 images; COLMAP's
# mapper registers all 5 frames from it; the gravity bundle adjustment of the result succeeds.
cmake_minimum_required(VERSION 3.21)
include(${CMAKE_CURRENT_LIST_DIR}/script_checks.cmake)

if(NOT COLMAP)
  message("colmap walkthrough test skipped: the colmap executable was not found")
  return()
endif()
set(frames "${KITTI_DIR}/sequences/00/image_0")
if(NOT EXISTS "${frames}/000004.png" OR NOT EXISTS "${KITTI_DIR}/poses/00.txt")
  message("colmap walkthrough test skipped: KITTI odometry data not found in ${KITTI_DIR} (set "
          "TRIGRAV_KITTI_DIR to a folder with sequences/00/image_0 and poses/00.txt)")
  return()
endif()

# Runs the command in ARGN; sets <name>_status, <name>_out, <name>_err; stops on a failure.
macro(run name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE ${name}_status OUTPUT_VARIABLE ${name}_out
    ERROR_VARIABLE ${name}_err TIMEOUT 120)
  message(STATUS "${name}: exit ${${name}_status}")
  if(NOT ${name}_status EQUAL 0)
    message(FATAL_ERROR "${name} failed (${${name}_status}):\n${${name}_out}\n${${name}_err}")
  endif()
endmacro()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/images")
foreach(frame 000000 000001 000002 000003 000004)
  file(CREATE_LINK "${frames}/${frame}.png" "${WORK_DIR}/images/${frame}.png" SYMBOLIC)
endforeach()
set(ENV{QT_QPA_PLATFORM} offscreen)
set(db ${WORK_DIR}/database.db)
run(feature_extractor ${COLMAP} feature_extractor --database_path ${db}
  --image_path ${WORK_DIR}/images --ImageReader.camera_model PINHOLE
  --ImageReader.single_camera 1 --ImageReader.camera_params 718.856,718.856,607.1928,185.2157
  --SiftExtraction.use_gpu 0 --SiftExtraction.max_num_features 2000)
run(sequential_matcher ${COLMAP} sequential_matcher --database_path ${db}
  --SiftMatching.use_gpu 0)
run(make_gravity_csv ${MAKE_GRAVITY} --poses_path=${KITTI_DIR}/poses/00.txt
  --image_path=${WORK_DIR}/images --output_path=${WORK_DIR}/gravity.csv)
run(triplet_initializer ${INITIALIZER} --database_path=${db} --gravity_csv=${WORK_DIR}/gravity.csv
  --output_csv=${WORK_DIR}/triplets.csv --output_model_path=${WORK_DIR}/seed)
message(STATUS "${triplet_initializer_out}")
expect_match("3 triplets, at least one trusted" "${triplet_initializer_out}"
  "3 triplets \\(consecutive\\): [0-9] estimated, [1-3] trusted")
file(STRINGS "${WORK_DIR}/triplets.csv" rows REGEX "^0000")
list(LENGTH rows num_rows)
expect("3 rows in triplets.csv (${num_rows})" num_rows EQUAL 3)
foreach(file cameras.bin images.bin points3D.bin)
  expect("seed ${file} written" EXISTS "${WORK_DIR}/seed/${file}")
endforeach()

file(MAKE_DIRECTORY "${WORK_DIR}/mapped")
run(mapper ${COLMAP} mapper --database_path ${db} --image_path ${WORK_DIR}/images
  --input_path ${WORK_DIR}/seed --output_path ${WORK_DIR}/mapped)
run(model_analyzer ${COLMAP} model_analyzer --path ${WORK_DIR}/mapped)
set(analysis "${model_analyzer_out}${model_analyzer_err}")
message(STATUS "${analysis}")
expect_match("COLMAP's mapper registers the 5 frames from the seed" "${analysis}"
  "Registered images: 5\n")

run(gravity_bundle_adjuster ${ADJUSTER} --input_path=${WORK_DIR}/mapped
  --gravity_csv=${WORK_DIR}/gravity.csv --output_path=${WORK_DIR}/refined)
message(STATUS "${gravity_bundle_adjuster_out}")
expect("the gravity bundle adjustment writes a model" EXISTS "${WORK_DIR}/refined/images.bin")

report_failures(colmap_walkthrough)
