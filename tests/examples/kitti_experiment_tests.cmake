# The evaluation of run_kitti_experiment.py (examples/colmap/kitti_experiment/): synthetic poses with
# known errors, the binary model reader. Needs a python3 with numpy and matplotlib (Debian's, first).
find_program(TRIGRAV_SYSTEM_PYTHON3 NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
find_program(TRIGRAV_SYSTEM_PYTHON3 NAMES python3)
if(NOT TRIGRAV_SYSTEM_PYTHON3)
  return()
endif()
execute_process(COMMAND ${TRIGRAV_SYSTEM_PYTHON3} -c "import numpy, matplotlib"
                RESULT_VARIABLE no_numpy OUTPUT_QUIET ERROR_QUIET)
if(NOT no_numpy EQUAL 0)
  message(STATUS "numpy or matplotlib not found for ${TRIGRAV_SYSTEM_PYTHON3}: the KITTI "
                 "experiment's evaluation is not tested (install python3-numpy python3-matplotlib)")
  return()
endif()
add_test(NAME kitti_experiment_evaluation
  COMMAND ${TRIGRAV_SYSTEM_PYTHON3} -m unittest discover
    -s ${PROJECT_SOURCE_DIR}/examples/colmap/kitti_experiment -p test_*.py)
set_tests_properties(kitti_experiment_evaluation PROPERTIES
  ENVIRONMENT "PYTHONDONTWRITEBYTECODE=1")
