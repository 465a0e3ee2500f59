# The real COLMAP 3.8 CLI on frames 000000-000004 of KITTI 00, read by trigrav::colmap:
#   cmake -DSTEP=database|model -DCOLMAP=<colmap> -DCHECKER=<colmap_real_check>
#         -DKITTI_DIR=<folder> -DWORK_DIR=<scratch folder> -P run_colmap_real.cmake
# database: feature_extractor (PINHOLE with KITTI's intrinsics, one camera, CPU SIFT, 2000
#   features) and sequential_matcher, then the checker reads the database and compares the keypoint
#   counts with those feature_extractor printed.
# model: mapper (with the initialisation options driving data needs) on that database (made first
#   when the database step has not run). Its default 1.5 deg triangulation-angle floor drops most
#   of these forward-motion points, and what survives varies from run to run: 25 (one CI run) to
#   999 points3D in 8 runs. With a 0.5 deg floor, 12 runs kept 1268 to 1531.
#   Then ours reads its model and writes it as text and binary;
#   COLMAP's model_converter converts ours (text to BIN, binary to TXT) and COLMAP's own model to
#   TXT; ours reads all of them back, equal to COLMAP's model.
# Prints "colmap_real test skipped: ..." and succeeds when COLMAP or the KITTI frames are missing
# (the tests' SKIP_REGULAR_EXPRESSION).
cmake_minimum_required(VERSION 3.21)

set(images_dir ${KITTI_DIR}/sequences/00/image_0)
if(NOT COLMAP OR NOT EXISTS "${COLMAP}")
  message("colmap_real test skipped: the colmap executable was not found (install colmap)")
  return()
endif()
if(NOT EXISTS ${images_dir}/000004.png)
  message("colmap_real test skipped: KITTI frames not found in ${images_dir}")
  return()
endif()
set(ENV{QT_QPA_PLATFORM} offscreen)

function(run log)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output
                  ERROR_VARIABLE output)
  file(WRITE ${WORK_DIR}/${log}.log "${output}")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed (${result}): ${ARGN}\n${output}")
  endif()
  set(output "${output}" PARENT_SCOPE)
endfunction()

set(database ${WORK_DIR}/database.db)
function(make_database)
  file(REMOVE_RECURSE ${WORK_DIR})
  file(MAKE_DIRECTORY ${WORK_DIR}/images)
  foreach(frame 000000 000001 000002 000003 000004)
    file(CREATE_LINK ${images_dir}/${frame}.png ${WORK_DIR}/images/${frame}.png SYMBOLIC)
  endforeach()
  run(feature_extractor ${COLMAP} feature_extractor --database_path ${database}
      --image_path ${WORK_DIR}/images --ImageReader.camera_model PINHOLE
      --ImageReader.single_camera 1
      --ImageReader.camera_params 718.856,718.856,607.1928,185.2157
      --SiftExtraction.use_gpu 0 --SiftExtraction.num_threads 2
      --SiftExtraction.max_num_features 2000)
  # "Name: 000000.png" ... "Features: 3422" per image, in that order: the counts to compare with
  # the database.
  string(REGEX MATCHALL "Name: +[^\n]+\.png" names "${output}")
  string(REGEX MATCHALL "Features: +[0-9]+" features "${output}")
  set(counts "")
  foreach(name feature IN ZIP_LISTS names features)
    string(REGEX REPLACE "Name: +" "" name "${name}")
    string(REGEX REPLACE "Features: +" "" feature "${feature}")
    list(APPEND counts "${name}=${feature}")
  endforeach()
  file(WRITE ${WORK_DIR}/feature_counts.txt "${counts}")
  run(sequential_matcher ${COLMAP} sequential_matcher --database_path ${database}
      --SiftMatching.use_gpu 0 --SiftMatching.num_threads 2)
  file(TOUCH ${WORK_DIR}/database.done)
endfunction()

if(STEP STREQUAL "database")
  make_database()
  file(READ ${WORK_DIR}/feature_counts.txt counts)
  list(LENGTH counts num_counts)
  if(NOT num_counts EQUAL 5)
    message(FATAL_ERROR "feature_extractor's log gave ${num_counts} feature counts, not 5")
  endif()
  run(check_database ${CHECKER} database ${database} ${counts})
  message("${output}")
elseif(STEP STREQUAL "model")
  if(NOT EXISTS ${WORK_DIR}/database.done)
    make_database()
  endif()
  set(model ${WORK_DIR}/model)
  file(REMOVE_RECURSE ${model})
  file(MAKE_DIRECTORY ${model}/sparse ${model}/ours_txt ${model}/ours_bin ${model}/colmap_txt
       ${model}/ours_txt_to_bin ${model}/ours_bin_to_txt)
  run(mapper ${COLMAP} mapper --database_path ${database} --image_path ${WORK_DIR}/images
      --output_path ${model}/sparse --Mapper.num_threads 2
      --Mapper.init_max_forward_motion 1.0 --Mapper.init_min_tri_angle 4
      --Mapper.tri_min_angle 0.5 --Mapper.filter_min_tri_angle 0.5)
  if(NOT EXISTS ${model}/sparse/0/images.bin)
    message(FATAL_ERROR "colmap mapper made no model (see ${WORK_DIR}/mapper.log)")
  endif()
  run(write ${CHECKER} write ${model}/sparse/0 ${model}/ours_txt ${model}/ours_bin)
  message("${output}")
  run(convert_txt ${COLMAP} model_converter --input_path ${model}/ours_bin
      --output_path ${model}/ours_bin_to_txt --output_type TXT)
  run(convert_bin ${COLMAP} model_converter --input_path ${model}/ours_txt
      --output_path ${model}/ours_txt_to_bin --output_type BIN)
  run(convert_colmap ${COLMAP} model_converter --input_path ${model}/sparse/0
      --output_path ${model}/colmap_txt --output_type TXT)
  run(compare ${CHECKER} compare ${model}/sparse/0 ${model}/ours_txt ${model}/ours_bin
      ${model}/ours_bin_to_txt ${model}/ours_txt_to_bin ${model}/colmap_txt)
  message("${output}")
else()
  message(FATAL_ERROR "STEP must be database or model")
endif()
