# The Python KITTI example (examples/python/kitti_triplet.py) on frames 100-102 of KITTI 00 in
# ../shared/data/kitti, with the module's interpreter; skipped (exit status 77) when that folder is
# missing. Registered when the module is built and its interpreter has cv2 and matplotlib.
if(NOT TARGET trigrav_python)
  return()
endif()
execute_process(COMMAND ${Python_EXECUTABLE} -c "import cv2, matplotlib"
                RESULT_VARIABLE no_cv2 OUTPUT_QUIET ERROR_QUIET)
if(NOT no_cv2 EQUAL 0)
  message(STATUS "cv2 or matplotlib not found for ${Python_EXECUTABLE}: the Python KITTI example "
                 "is not tested (install python3-opencv and python3-matplotlib)")
  return()
endif()
add_test(NAME python_kitti_triplet
  COMMAND ${Python_EXECUTABLE} ${PROJECT_SOURCE_DIR}/examples/python/kitti_triplet.py
    --kitti_dir ${PROJECT_SOURCE_DIR}/../shared/data/kitti --sequence 00 --frames 100 101 102
    --figure ${CMAKE_CURRENT_BINARY_DIR}/kitti_triplet.png)
set_tests_properties(python_kitti_triplet PROPERTIES
  SKIP_RETURN_CODE 77
  TIMEOUT 300
  ENVIRONMENT "PYTHONPATH=${TRIGRAV_PYTHON_BUILD_DIR};PYTHONDONTWRITEBYTECODE=1")
