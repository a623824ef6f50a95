# The tests mirror the source tree: the tests of mb_kinematics/<folder>/ are in test/<folder>/.
# Every test/{core,estimation,io,offline,tools,analysis,stability}/*_test.cc is a GoogleTest
# executable of its own (but test/offline/bag_test.cc and output_file_test.cc, which need ROS:
# test/ros.cmake);
# test/peers/*_test.cc also link the peer libraries (Orocos KDL, found
# in CMakeLists.txt also when the benchmarks are not built).

# The test models (test/support/test_models.h), compiled once for every test that uses them.
add_library(mbk_test_models STATIC test/support/test_models.cc)
target_compile_definitions(mbk_test_models PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
target_link_libraries(mbk_test_models mbk_analysis mbk_core)

file(GLOB MBK_UNIT_TESTS CONFIGURE_DEPENDS test/core/*_test.cc test/estimation/*_test.cc
  test/io/*_test.cc test/offline/*_test.cc test/tools/*_test.cc test/analysis/*_test.cc
  test/stability/*_test.cc)
list(FILTER MBK_UNIT_TESTS EXCLUDE REGEX "/test/offline/(bag|output_file)_test\\.cc$")
file(GLOB MBK_PEER_TESTS CONFIGURE_DEPENDS test/peers/*_test.cc)
# test/peers/mujoco_test.cc runs MuJoCo itself (libmujoco-dev), sdformat_test.cc libsdformat12
# (libsdformat-dev), when they are installed.
find_library(MBK_MUJOCO_LIBRARY mujoco)  # not find_package: Debian's config names a folder
find_path(MBK_MUJOCO_INCLUDE mujoco/mujoco.h)  # it does not install (/usr/include/libqhull_r)
if(NOT MBK_MUJOCO_LIBRARY OR NOT MBK_MUJOCO_INCLUDE)
  list(FILTER MBK_PEER_TESTS EXCLUDE REGEX "/test/peers/mujoco_test\\.cc$")
endif()
if(NOT TARGET mbk_sdformat)
  list(FILTER MBK_PEER_TESTS EXCLUDE REGEX "/test/peers/sdformat_test\\.cc$")
  list(FILTER MBK_UNIT_TESTS EXCLUDE REGEX "/test/io/sdf_model_test\\.cc$")
endif()
foreach(source ${MBK_UNIT_TESTS} ${MBK_PEER_TESTS})
  get_filename_component(name ${source} NAME_WE)
  catkin_add_gtest(${name} ${source} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} mbk_test_models mbk_analysis mbk_engine mbk_io mbk_core gtest_main)
  target_compile_definitions(${name} PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  mbk_test_compile(mbk_test_headers ${name})
endforeach()
foreach(source ${MBK_PEER_TESTS})
  get_filename_component(name ${source} NAME_WE)
  target_include_directories(${name} SYSTEM PRIVATE ${orocos_kdl_INCLUDE_DIRS}
    ${kdl_parser_INCLUDE_DIRS})
  target_link_libraries(${name} ${orocos_kdl_LIBRARIES} ${kdl_parser_LIBRARIES})
endforeach()
if(TARGET mujoco_test)
  target_link_libraries(mujoco_test ${MBK_MUJOCO_LIBRARY})
endif()
if(TARGET sdformat_test)
  target_link_libraries(sdformat_test sdformat12::sdformat12)
endif()

# A memcheck of the loaders (doc/reliability.md): the BVH reader, model and anthropometry tests and
# the URDF/YAML/STATE.json error tests under valgrind, when it is installed (not in a sanitizer
# build): any invalid read or write, use of uninitialised memory or definite leak (but urdfdom's
# own, test/valgrind.supp) fails them. 9-46 s in all (doc/reliability.md).
find_program(MBK_VALGRIND valgrind)
if(MBK_VALGRIND AND NOT CMAKE_CXX_FLAGS MATCHES "sanitize" AND TARGET bvh_test)
  foreach(name bvh_test bvh_model_test bvh_anthropometry_test loader_errors_test)
    add_test(NAME memcheck_${name} COMMAND ${MBK_VALGRIND} --error-exitcode=3 -q
      --leak-check=full --errors-for-leak-kinds=definite
      --suppressions=${PROJECT_SOURCE_DIR}/test/valgrind.supp $<TARGET_FILE:${name}>
      WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
    set_tests_properties(memcheck_${name} PROPERTIES TIMEOUT 120)
  endforeach()
endif()

# The fuzz smoke (doc/reliability.md): builds the libFuzzer harnesses of test/fuzz/ (clang, in
# <workspace>/fuzz/build; scripts/test.sh starts that build beside the tests' build, and this
# test waits for it, then finds the harnesses built) and runs each from its seeds with a fixed seed and number of runs (about 5 s each, the same
# inputs every time); fails on any crash, hang, leak or sanitizer report.
get_filename_component(MBK_WORKSPACE ${CMAKE_BINARY_DIR} DIRECTORY)
add_test(NAME fuzz_smoke COMMAND ${PROJECT_SOURCE_DIR}/scripts/fuzz.sh --smoke)
set_tests_properties(fuzz_smoke PROPERTIES ENVIRONMENT MBK_WS=${MBK_WORKSPACE} TIMEOUT 1200)

# The docs (doc/ and the README's front page): every relative link and #anchor of README.md and
# doc/*.md resolves, and the README's Quick start blocks run against this workspace on a ROS
# master of the test's own (test/doc/doc_check.py; needs mbk, mb_kinematics_node, demo_publisher).
add_test(NAME doc_check COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/doc/doc_check.py)
set_tests_properties(doc_check PROPERTIES ENVIRONMENT MBK_WS=${MBK_WORKSPACE} TIMEOUT 90)
# Every command block of doc/*.md as written, from a fresh shell in a fresh folder
# (test/doc/doc_check.py --pages; needs the node, mbk, demo_publisher, rviz and Xvfb).
add_test(NAME doc_pages COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/doc/doc_check.py --pages)
set_tests_properties(doc_pages PROPERTIES ENVIRONMENT MBK_WS=${MBK_WORKSPACE} TIMEOUT 900)
# The layers of mb_kinematics/ (doc/architecture.md): no #include from a lower layer to a higher
# one, no ROS in core/ or estimation/ (scripts/check_layers.py, tested on planted includes).
add_test(NAME layer_includes COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/layers_test.py)
# The update in double compiled in core/kinematics_double.cc's object alone, no other object of the
# build holding a copy of its own (test/update_once_test.py, nm on every object; doc/building.md).
add_test(NAME update_once COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/update_once_test.py
  ${CMAKE_BINARY_DIR})
# scripts/plot_kinematics.py (its overview and --walk figures, its refusals) on a CSV of its own.
add_test(NAME plot_kinematics COMMAND /usr/bin/python3
  ${PROJECT_SOURCE_DIR}/test/scripts/plot_kinematics_test.py)
# doc/recorded_data.md's table of the right hand's angular velocity spikes: each figure is
# test/mocap/euler_spikes.py's on the shipped CMU recordings, the spikes are the same samples
# from the Euler angles and from the orientations, and a representation flip is told apart.
add_test(NAME euler_spikes COMMAND /usr/bin/python3
  ${PROJECT_SOURCE_DIR}/test/mocap/euler_spikes_test.py)
# plot_kinematics.py --bvh: from a BVH file to the CSV and the figure with the workspace's mbk.
add_test(NAME plot_kinematics_bvh COMMAND /usr/bin/python3
  ${PROJECT_SOURCE_DIR}/test/scripts/plot_kinematics_test.py --bvh)
set_tests_properties(plot_kinematics_bvh PROPERTIES ENVIRONMENT
  "CMAKE_PREFIX_PATH=${CATKIN_DEVEL_PREFIX}")
# The Python module (doc/python.md): test/python/ under pytest, run from the build folder (from
# the repository root the C++ folder mb_kinematics/ would shadow the package) on the devel
# space's package, its numbers against the workspace's mbk and the peers PyKDL and dartpy.
add_test(NAME python_module COMMAND /usr/bin/python3 -m pytest -q -p no:cacheprovider
  ${PROJECT_SOURCE_DIR}/test/python WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(python_module PROPERTIES TIMEOUT 300 ENVIRONMENT
  "PYTHONPATH=${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_PYTHON_DESTINATION};MBK_DEVEL=${CATKIN_DEVEL_PREFIX};PYTHONNOUSERSITE=1")
# mbk batch (doc/batch.md): test/batch/ under pytest, as python_module, on a small collection.
add_test(NAME python_batch COMMAND /usr/bin/python3 -m pytest -q -p no:cacheprovider
  ${PROJECT_SOURCE_DIR}/test/batch WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(python_batch PROPERTIES TIMEOUT 600 ENVIRONMENT
  "PYTHONPATH=${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_PYTHON_DESTINATION};MBK_DEVEL=${CATKIN_DEVEL_PREFIX};PYTHONNOUSERSITE=1")
# Every JSON `mbk eval` writes parses as JSON (no inf or nan), on the fuzzers' starting models,
# the workspace's fuzz corpus when a fuzz run left one, and models at a double's limits; a
# refused model is one error line and nothing on stdout (test/tools/eval_json_test.py).
add_test(NAME eval_json COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/tools/eval_json_test.py
  $<TARGET_FILE:mbk> ${MBK_WORKSPACE})
