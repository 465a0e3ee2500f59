# End to end on synthetic input, without COLMAP: make_gravity_csv and gravity_bundle_adjuster
# (examples/colmap/), good and bad input.
#   cmake -DMAKE_GRAVITY=<make_gravity_csv> -DADJUSTER=<gravity_bundle_adjuster>
#         -DWRITER=<write_synthetic_colmap_model> -DWORK_DIR=<folder> -P check_colmap_tools.cmake
# 1. make_gravity_csv: a pose file of 3 frames and 3 images (one in a subfolder) give
#    R_k^T e_y per image in sorted name order; noise moves the vectors; 3 poses for 4 images fail.
# 2. gravity_bundle_adjuster on a synthetic model with perturbed poses
#    (write_synthetic_colmap_model): both rotation models, binary and text output, the covariance
#    CSV; the cost decreases; the written model reads back (the tool runs on it).
# 3. Bad input: a gravity CSV missing an image, NaN gravity, a missing model folder, an unwritable
#    covariance CSV: non-zero exit, a message naming the problem, no output folder.
cmake_minimum_required(VERSION 3.21)
include(${CMAKE_CURRENT_LIST_DIR}/script_checks.cmake)


# Runs the command in ARGN; sets <name>_status, <name>_out, <name>_err.
macro(run name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE ${name}_status OUTPUT_VARIABLE ${name}_out
    ERROR_VARIABLE ${name}_err TIMEOUT 100)
  message(STATUS "${name}: exit ${${name}_status}\n${${name}_out}${${name}_err}")
endmacro()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/images/sub")

# 1. make_gravity_csv. Frame 0 identity, frame 1 rotated 90 deg about z (R^T e_y = e_x), frame 2
# translated only.
file(WRITE "${WORK_DIR}/poses.txt" "1 0 0 0 0 1 0 0 0 0 1 0\n0 -1 0 0 1 0 0 0 0 0 1 0\n"
  "1 0 0 3 0 1 0 0 0 0 1 5\n")
foreach(name a.png b.png sub/c.png)
  file(WRITE "${WORK_DIR}/images/${name}" "not an image; only the name counts")
endforeach()
run(exact ${MAKE_GRAVITY} --poses_path=${WORK_DIR}/poses.txt --image_path=${WORK_DIR}/images
  --output_path=${WORK_DIR}/exact.csv)
expect("make_gravity_csv exits 0" exact_status EQUAL 0)
file(READ "${WORK_DIR}/exact.csv" exact_csv)
expect_match("frame 0 (a.png) has gravity e_y" "${exact_csv}" "\na\\.png,-?0,1,-?0\n")
expect_match("frame 1 (b.png) has gravity e_x" "${exact_csv}" "\nb\\.png,1,-?0,-?0\n")
expect_match("frame 2 (sub/c.png) has gravity e_y" "${exact_csv}" "\nsub/c\\.png,-?0,1,-?0\n")
run(noisy ${MAKE_GRAVITY} --poses_path=${WORK_DIR}/poses.txt --image_path=${WORK_DIR}/images
  --output_path=${WORK_DIR}/noisy.csv --noise_deg=1 --seed=3)
expect("make_gravity_csv --noise_deg=1 exits 0" noisy_status EQUAL 0)
file(READ "${WORK_DIR}/noisy.csv" noisy_csv)
expect("noise moves frame 0's gravity" NOT noisy_csv MATCHES "\na\\.png,-?0,1,-?0\n")
expect_match("noisy rows for the three images" "${noisy_csv}"
  "\na\\.png,[-0-9.e]+,[-0-9.e]+,[-0-9.e]+\nb\\.png,.*\nsub/c\\.png,")
file(WRITE "${WORK_DIR}/images/d.png" "a fourth image")
run(few_poses ${MAKE_GRAVITY} --poses_path=${WORK_DIR}/poses.txt --image_path=${WORK_DIR}/images
  --output_path=${WORK_DIR}/few.csv)
expect("3 poses for 4 images: exit 1" few_poses_status EQUAL 1)
expect_match("3 poses for 4 images: the message" "${few_poses_err}"
  "error: .*has 3 poses for 4 images")
expect("3 poses for 4 images: no CSV" NOT EXISTS "${WORK_DIR}/few.csv")

# 2. gravity_bundle_adjuster.
run(writer ${WRITER} ${WORK_DIR}/synthetic)
expect("write_synthetic_colmap_model exits 0" writer_status EQUAL 0)
set(model ${WORK_DIR}/synthetic/model)
set(gravity ${WORK_DIR}/synthetic/gravity.csv)
foreach(rotation_model gravity_prior yaw_only)
  run(${rotation_model} ${ADJUSTER} --input_path=${model} --gravity_csv=${gravity}
    --output_path=${WORK_DIR}/${rotation_model} --rotation_model=${rotation_model})
  expect("${rotation_model}: exit 0" ${rotation_model}_status EQUAL 0)
  foreach(file cameras.bin images.bin points3D.bin)
    expect("${rotation_model}: ${file} written" EXISTS "${WORK_DIR}/${rotation_model}/${file}")
  endforeach()
  if(${rotation_model}_out MATCHES "cost ([-0-9.e+]+) -> ([-0-9.e+]+)")
    expect("${rotation_model}: the cost decreases (${CMAKE_MATCH_1} -> ${CMAKE_MATCH_2})"
      CMAKE_MATCH_2 LESS CMAKE_MATCH_1)
  else()
    list(APPEND failures "${rotation_model}: no cost line")
  endif()
  expect_match("${rotation_model}: 5 images, 150 points, 750 observations"
    "${${rotation_model}_out}" "5 images, 150 points, 750 observations \\(0 skipped\\)")
endforeach()
run(text ${ADJUSTER} --input_path=${WORK_DIR}/yaw_only --gravity_csv=${gravity}
  --output_path=${WORK_DIR}/text --output_format=text --covariance_csv=${WORK_DIR}/covariance.csv)
expect("reading the written model back, text output: exit 0" text_status EQUAL 0)
foreach(file cameras.txt images.txt points3D.txt)
  expect("text: ${file} written" EXISTS "${WORK_DIR}/text/${file}")
endforeach()
file(STRINGS "${WORK_DIR}/covariance.csv" covariance_rows REGEX "^frame[0-4]\\.png,[1-5],")
list(LENGTH covariance_rows num_covariance_rows)
expect("a covariance row per image (${num_covariance_rows})" num_covariance_rows EQUAL 5)
expect("no temporary covariance file left" NOT EXISTS "${WORK_DIR}/covariance.csv.tmp")
run(bad_csv ${ADJUSTER} --input_path=${model} --gravity_csv=${gravity}
  --output_path=${WORK_DIR}/out_bad_csv --covariance_csv=${WORK_DIR}/no_such_folder/cov.csv)
expect("an unwritable covariance CSV: exit 1" bad_csv_status EQUAL 1)
expect_match("an unwritable covariance CSV: the file named" "${bad_csv_err}"
  "error: cannot write .*no_such_folder/cov\\.csv\\.tmp; nothing written")
expect("an unwritable covariance CSV: no model" NOT EXISTS "${WORK_DIR}/out_bad_csv")

# 3. Bad input: nothing written.
file(STRINGS "${gravity}" gravity_lines)
list(FILTER gravity_lines EXCLUDE REGEX "^frame2\\.png,")
list(JOIN gravity_lines "\n" missing_csv)
file(WRITE "${WORK_DIR}/gravity_missing.csv" "${missing_csv}\n")
run(missing ${ADJUSTER} --input_path=${model} --gravity_csv=${WORK_DIR}/gravity_missing.csv
  --output_path=${WORK_DIR}/out_missing)
expect("a gravity CSV missing an image: exit 1" missing_status EQUAL 1)
expect_match("a gravity CSV missing an image: the image named" "${missing_err}"
  "error: no gravity for 1 of 5 images: frame2\\.png")
expect("a gravity CSV missing an image: no output" NOT EXISTS "${WORK_DIR}/out_missing")

file(READ "${gravity}" gravity_csv)
string(REGEX REPLACE "\nframe1\\.png,[^\n]*" "\nframe1.png,nan,1,0" nan_csv "${gravity_csv}")
file(WRITE "${WORK_DIR}/gravity_nan.csv" "${nan_csv}")
run(nan ${ADJUSTER} --input_path=${model} --gravity_csv=${WORK_DIR}/gravity_nan.csv
  --output_path=${WORK_DIR}/out_nan)
expect("NaN gravity: exit 1" nan_status EQUAL 1)
expect_match("NaN gravity: the file and line named" "${nan_err}"
  "error: .*gravity_nan\\.csv:3: .*frame1\\.png")
expect("NaN gravity: no output" NOT EXISTS "${WORK_DIR}/out_nan")

run(no_model ${ADJUSTER} --input_path=${WORK_DIR}/no_such_model --gravity_csv=${gravity}
  --output_path=${WORK_DIR}/out_no_model)
expect("a missing model folder: exit 2" no_model_status EQUAL 2)
expect_match("a missing model folder: the message" "${no_model_err}"
  "error: --input_path=.* is not a folder")
expect("a missing model folder: no output" NOT EXISTS "${WORK_DIR}/out_no_model")

file(MAKE_DIRECTORY "${WORK_DIR}/empty_model")
run(empty_model ${ADJUSTER} --input_path=${WORK_DIR}/empty_model --gravity_csv=${gravity}
  --output_path=${WORK_DIR}/out_empty_model)
expect("an empty model folder: exit 1" empty_model_status EQUAL 1)
expect("an empty model folder: no output" NOT EXISTS "${WORK_DIR}/out_empty_model")

report_failures(colmap_tools)
