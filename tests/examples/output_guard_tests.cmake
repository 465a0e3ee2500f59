# Every tool that writes files, given an output that is (or lies inside, or contains) one of its
# inputs, also through a symbolic link, "./x", a hard link or a --flagfile: refused before any
# work (exit status 2, "error: <which paths>"), the inputs unchanged byte for byte and nothing
# created (run_output_guard_test.cmake). The guard: examples/common/output_paths.h.
#   trigrav_add_output_guard_test(<name> <target> REGEX <regex> SETUP <ops...> ARGS <args...>)
# adds the ctest output_guard_<name> when <target> is built.
set(TRIGRAV_RUN_OUTPUT_GUARD_TEST ${CMAKE_CURRENT_LIST_DIR}/run_output_guard_test.cmake)

function(trigrav_add_output_guard_test name target)
  cmake_parse_arguments(arg "" "REGEX" "SETUP;ARGS" ${ARGN})
  if(NOT TARGET ${target})
    return()
  endif()
  set(definitions "")
  foreach(kind SETUP ARGS)
    set(count 0)
    foreach(item IN LISTS arg_${kind})
      if(kind STREQUAL "SETUP")
        list(APPEND definitions "-DSETUP${count}=${item}")
      else()
        list(APPEND definitions "-DARG${count}=${item}")
      endif()
      math(EXPR count "${count} + 1")
    endforeach()
    list(APPEND definitions "-DNUM_${kind}=${count}")
  endforeach()
  add_test(NAME output_guard_${name}
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:${target}> "-DREGEX=${arg_REGEX}"
      -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/output_guard/${name} ${definitions}
      -P ${TRIGRAV_RUN_OUTPUT_GUARD_TEST})
  set_tests_properties(output_guard_${name} PROPERTIES LABELS output_guard TIMEOUT 120)
endfunction()

set(same "is the same path as")

# The guard itself, as a unit test (header only: examples/common/output_paths.h).
if(TRIGRAV_BUILD_EXAMPLES)
  find_package(gflags REQUIRED)
  trigrav_add_gtest(trigrav_output_paths_test
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/output_paths_test.cc
    LIBRARIES gflags)
  target_include_directories(trigrav_output_paths_test PRIVATE ${PROJECT_SOURCE_DIR}/examples)
endif()

# triplet_initializer: the database, the gravity CSV, the --flagfile.
set(initializer_inputs file:db.db file:g.csv)
set(initializer_flags --database_path=db.db --gravity_csv=g.csv)
trigrav_add_output_guard_test(triplet_initializer_csv_is_database triplet_initializer
  REGEX "--output_csv \\(db\\.db\\) ${same} --database_path" SETUP ${initializer_inputs}
  ARGS ${initializer_flags} --output_csv=db.db --output_model_path=seed)
trigrav_add_output_guard_test(triplet_initializer_csv_is_gravity_dot_slash triplet_initializer
  REGEX "--output_csv \\(\\./g\\.csv\\) ${same} --gravity_csv" SETUP ${initializer_inputs}
  ARGS ${initializer_flags} --output_csv=./g.csv --output_model_path=seed)
trigrav_add_output_guard_test(triplet_initializer_csv_is_symlink_to_database triplet_initializer
  REGEX "--output_csv \\(link\\.db\\) ${same} --database_path"
  SETUP ${initializer_inputs} symlink:link.db=db.db
  ARGS ${initializer_flags} --output_csv=link.db --output_model_path=seed)
trigrav_add_output_guard_test(triplet_initializer_csv_is_hard_link_to_database
  triplet_initializer
  REGEX "--output_csv \\(hard\\.db\\) ${same} --database_path"
  SETUP ${initializer_inputs} hardlink:hard.db=db.db
  ARGS ${initializer_flags} --output_csv=hard.db --output_model_path=seed)
trigrav_add_output_guard_test(triplet_initializer_model_is_gravity triplet_initializer
  REGEX "--output_model_path \\(g\\.csv\\) ${same} --gravity_csv" SETUP ${initializer_inputs}
  ARGS ${initializer_flags} --output_csv=t.csv --output_model_path=g.csv)
trigrav_add_output_guard_test(triplet_initializer_model_contains_database triplet_initializer
  REGEX "--output_model_path \\(project\\) contains --database_path"
  SETUP dir:project file:project/db.db file:g.csv
  ARGS --database_path=project/db.db --gravity_csv=g.csv --output_csv=t.csv
    --output_model_path=project)
trigrav_add_output_guard_test(triplet_initializer_csv_is_flagfile triplet_initializer
  REGEX "--output_csv \\(run\\.flags\\) ${same} --flagfile"
  SETUP ${initializer_inputs}
    "flags:run.flags=--database_path=db.db|--gravity_csv=g.csv|--output_csv=run.flags|--output_model_path=seed"
  ARGS --flagfile=run.flags)

# make_gravity_csv: the pose file and the image folder.
set(gravity_inputs file:poses.txt dir:images file:images/a.png)
trigrav_add_output_guard_test(make_gravity_csv_output_is_poses make_gravity_csv
  REGEX "--output_path \\(poses\\.txt\\) ${same} --poses_path" SETUP ${gravity_inputs}
  ARGS --poses_path=poses.txt --image_path=images --output_path=poses.txt)
trigrav_add_output_guard_test(make_gravity_csv_output_is_poses_through_symlink make_gravity_csv
  REGEX "--output_path \\(imgs/\\.\\./poses\\.txt\\) ${same} --poses_path"
  SETUP ${gravity_inputs} symlink:imgs=images
  ARGS --poses_path=poses.txt --image_path=images --output_path=imgs/../poses.txt)
trigrav_add_output_guard_test(make_gravity_csv_output_inside_images make_gravity_csv
  REGEX "--output_path \\(images/g\\.csv\\) lies inside --image_path" SETUP ${gravity_inputs}
  ARGS --poses_path=poses.txt --image_path=images --output_path=images/g.csv)

# gravity_bundle_adjuster: the model folder and the gravity CSV; the covariance CSV is an output.
set(model_files file:model/cameras.bin file:model/images.bin file:model/points3D.bin)
set(adjuster_inputs dir:model ${model_files} file:g.csv)
trigrav_add_output_guard_test(gravity_bundle_adjuster_output_is_input gravity_bundle_adjuster
  REGEX "--output_path \\(model\\) ${same} --input_path" SETUP ${adjuster_inputs}
  ARGS --input_path=model --gravity_csv=g.csv --output_path=model)
trigrav_add_output_guard_test(gravity_bundle_adjuster_output_is_input_through_symlink
  gravity_bundle_adjuster
  REGEX "--output_path \\(alias/\\) ${same} --input_path"
  SETUP ${adjuster_inputs} symlink:alias=model
  ARGS --input_path=model --gravity_csv=g.csv --output_path=alias/)
trigrav_add_output_guard_test(gravity_bundle_adjuster_output_contains_input
  gravity_bundle_adjuster
  REGEX "--output_path \\(\\.\\) contains --input_path" SETUP ${adjuster_inputs}
  ARGS --input_path=model --gravity_csv=g.csv --output_path=.)
trigrav_add_output_guard_test(gravity_bundle_adjuster_covariance_is_gravity
  gravity_bundle_adjuster
  REGEX "--covariance_csv \\(g\\.csv\\) ${same} --gravity_csv" SETUP ${adjuster_inputs}
  ARGS --input_path=model --gravity_csv=g.csv --output_path=out --covariance_csv=g.csv)
trigrav_add_output_guard_test(gravity_bundle_adjuster_covariance_inside_model
  gravity_bundle_adjuster
  REGEX "--covariance_csv \\(model/cov\\.csv\\) lies inside --input_path" SETUP ${adjuster_inputs}
  ARGS --input_path=model --gravity_csv=g.csv --output_path=out --covariance_csv=model/cov.csv)
trigrav_add_output_guard_test(gravity_bundle_adjuster_covariance_inside_output
  gravity_bundle_adjuster
  REGEX "--output_path \\(out\\) contains --covariance_csv" SETUP ${adjuster_inputs}
  ARGS --input_path=model --gravity_csv=g.csv --output_path=out --covariance_csv=out/cov.csv)

# kitti_triplets: the dataset folder; its CSVs against a --flagfile.
trigrav_add_output_guard_test(kitti_triplets_output_is_dataset kitti_triplets
  REGEX "--output_dir must not be inside the dataset --kitti_dir" SETUP dir:kitti file:kitti/x
  ARGS --kitti_dir=kitti --output_dir=./kitti)
trigrav_add_output_guard_test(kitti_triplets_csv_is_flagfile kitti_triplets
  REGEX "poses\\.csv of --output_dir \\(out/poses\\.csv\\) ${same} --flagfile"
  SETUP dir:kitti dir:out "flags:out/poses.csv=--kitti_dir=kitti|--output_dir=out"
  ARGS --flagfile=out/poses.csv)

# The synthetic tools read no file but a --flagfile.
trigrav_add_output_guard_test(initialize_and_refine_synthetic_output_is_flagfile
  initialize_and_refine_synthetic
  REGEX "--output \\(sweep\\.flags\\) ${same} --flagfile"
  SETUP "flags:sweep.flags=--experiment=sweep|--quick|--output=sweep.flags"
  ARGS --flagfile=sweep.flags)
trigrav_add_output_guard_test(paper_experiments_csv_is_flagfile paper_experiments
  REGEX "timing\\.csv of --output_dir \\(out/timing\\.csv\\) ${same} --flagfile"
  SETUP dir:out "flags:out/timing.csv=--output_dir=out|--quick"
  ARGS --flagfile=out/timing.csv)
