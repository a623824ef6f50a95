# kinematics_benchmark (Google Benchmark): ours against Orocos KDL, and against Pinocchio, DART
# and MuJoCo when CMake finds them. Like the tests, benchmarks and their peers are test dependencies
# (package.xml): without Google Benchmark, no benchmark.
#   Pinocchio 3.x is not in Debian: build it yourself and point CMake at it, e.g.
#   `source scripts/common.sh; mbk_build -DCMAKE_PREFIX_PATH=<its install prefix>`.
#   DART: Debian's libdart-dev and libdart-utils-urdf-dev (scripts/common.sh installs them).
# recursion_instructions: the driver of bench/recursion_instructions.sh and
# bench/euler_instructions.sh (callgrind; no Google Benchmark).
add_executable(recursion_instructions bench/recursion_instructions.cc)
target_link_libraries(recursion_instructions mbk_analysis mbk_io mbk_core)
target_compile_definitions(recursion_instructions PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

find_package(benchmark QUIET)  # orocos_kdl and kdl_parser: found in CMakeLists.txt
if(NOT benchmark_FOUND)
  message(STATUS "kinematics_benchmark: not built (needs Google Benchmark)")
  return()
endif()

add_executable(kinematics_benchmark bench/kinematics_benchmark.cc)
target_include_directories(kinematics_benchmark PRIVATE ${orocos_kdl_INCLUDE_DIRS}
  ${kdl_parser_INCLUDE_DIRS})
target_link_libraries(kinematics_benchmark mbk_analysis mbk_io mbk_core benchmark::benchmark
  ${orocos_kdl_LIBRARIES} ${kdl_parser_LIBRARIES})
target_compile_definitions(kinematics_benchmark PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

find_package(pinocchio QUIET)
# Under MBK_MARCH_NATIVE the peer's Eigen objects are laid out for this CPU (wider alignment):
# the Pinocchio library that builds its models must have been built with -march=native too
# (doc/speed.md), or the benchmark crashes. Say so with MBK_PINOCCHIO_MARCH_NATIVE.
option(MBK_PINOCCHIO_MARCH_NATIVE "The Pinocchio found was built with -march=native" OFF)
if(pinocchio_FOUND AND MBK_MARCH_NATIVE AND NOT MBK_PINOCCHIO_MARCH_NATIVE)
  message(STATUS "kinematics_benchmark: without Pinocchio (MBK_MARCH_NATIVE needs a Pinocchio "
    "built with -march=native; then add -DMBK_PINOCCHIO_MARCH_NATIVE=ON)")
elseif(pinocchio_FOUND)
  message(STATUS "kinematics_benchmark: with Pinocchio ${pinocchio_VERSION}")
  target_sources(kinematics_benchmark PRIVATE bench/pinocchio_peer.cc)
  target_link_libraries(kinematics_benchmark pinocchio::pinocchio)
  target_compile_definitions(kinematics_benchmark PRIVATE MBK_WITH_PINOCCHIO)
else()
  message(STATUS "kinematics_benchmark: without Pinocchio (not found; see bench/bench.cmake)")
endif()

find_package(DART QUIET COMPONENTS utils-urdf)
# DART's CMake config adds -DBOOST_TEST_DYN_LINK to every target of this directory (for
# Boost.Test, which nothing here uses): a build with the tests would compile again everything a
# build without them made (scripts/test.sh after scripts/demo.sh).
remove_definitions(-DBOOST_TEST_DYN_LINK)
if(DART_FOUND AND MBK_MARCH_NATIVE)  # Debian's DART is not built for this CPU (see Pinocchio)
  message(STATUS "kinematics_benchmark: without DART (Debian's is not built with -march=native)")
elseif(DART_FOUND)
  message(STATUS "kinematics_benchmark: with DART ${DART_VERSION}")
  target_sources(kinematics_benchmark PRIVATE bench/dart_peer.cc)
  target_link_libraries(kinematics_benchmark ${DART_LIBRARIES})
  target_compile_definitions(kinematics_benchmark PRIVATE MBK_WITH_DART)
else()
  message(STATUS "kinematics_benchmark: without DART (libdart-dev, libdart-utils-urdf-dev)")
endif()

find_library(MBK_MUJOCO_LIBRARY mujoco)  # as test/tests.cmake
find_path(MBK_MUJOCO_INCLUDE mujoco/mujoco.h)
if(MBK_MUJOCO_LIBRARY AND MBK_MUJOCO_INCLUDE)
  message(STATUS "kinematics_benchmark: with MuJoCo (${MBK_MUJOCO_LIBRARY})")
  target_sources(kinematics_benchmark PRIVATE bench/mujoco_peer.cc)
  target_link_libraries(kinematics_benchmark ${MBK_MUJOCO_LIBRARY})
  target_compile_definitions(kinematics_benchmark PRIVATE MBK_WITH_MUJOCO)
else()
  message(STATUS "kinematics_benchmark: without MuJoCo (libmujoco-dev)")
endif()

# bag_benchmark: the whole `mbk bag` path (read, compute, write) on the human model.
add_executable(bag_benchmark bench/bag_benchmark.cc)
target_link_libraries(bag_benchmark mbk_offline mbk_demo mbk_analysis mbk_io mbk_core benchmark::benchmark)
target_compile_definitions(bag_benchmark PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

# partial_velocities_benchmark: one ~get_partial_velocities request for a deep chain's tip, its
# chain only against the whole tree's arrays.
add_executable(partial_velocities_benchmark bench/partial_velocities_benchmark.cc)
target_link_libraries(partial_velocities_benchmark mbk_analysis mbk_core benchmark::benchmark)

# bvh_load_benchmark: reading a BVH recording and building its model (doc/speed.md#reading-bvh).
add_executable(bvh_load_benchmark bench/bvh_load_benchmark.cc)
target_link_libraries(bvh_load_benchmark mbk_io mbk_core benchmark::benchmark)
target_compile_definitions(bvh_load_benchmark PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

# batch_benchmark: mbk::batch_kinematics (the Python module's C++) into preallocated arrays, and a
# copy of the same bytes (doc/speed.md#python; bench/python_batch.py runs it beside the module).
add_executable(batch_benchmark bench/batch_benchmark.cc)
target_link_libraries(batch_benchmark mbk_engine mbk_io mbk_core benchmark::benchmark)
target_compile_definitions(batch_benchmark PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
