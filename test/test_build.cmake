# How the tests' own files compile (doc/building.md#how-the-tests-compile): at -O1, and with a
# precompiled header of what most of them include. Compiling the test files was over half of
# the build's CPU time, a third of it their headers and most of the rest the optimizer at -O3.
# The code under test is the libraries', compiled with the build's flags (-O3 in Release); a
# test file's own code is its checks, which -O1 leaves the same numbers (no -ffast-math: no
# optimization level reorders floating point arithmetic).
#
# Two headers' owners, each an empty file: the ROS-free tests' (GoogleTest, Eigen, the core's
# update and the test models) and the node's tests' (that, roscpp and the messages they
# read). A test file reuses its group's header; GCC checks that the
# flags match (-Winvalid-pch) and otherwise parses the headers itself, so a mismatch costs time,
# never correctness.
set(MBK_TEST_HEADERS <gtest/gtest.h> <algorithm> <cmath> <limits> <map> <random> <sstream>
  <stdexcept> <string> <vector> <Eigen/Dense> mb_kinematics/core/kinematics_double.h
  test/support/test_models.h)
add_library(mbk_test_headers STATIC EXCLUDE_FROM_ALL test/support/precompiled.cc)
target_compile_definitions(mbk_test_headers PRIVATE GTEST_HAS_PTHREAD=1)
target_precompile_headers(mbk_test_headers PRIVATE ${MBK_TEST_HEADERS})
add_library(mbk_ros_test_headers STATIC EXCLUDE_FROM_ALL test/support/precompiled.cc)
target_compile_definitions(mbk_ros_test_headers PRIVATE GTEST_HAS_PTHREAD=1)
target_precompile_headers(mbk_ros_test_headers PRIVATE ${MBK_TEST_HEADERS} <ros/ros.h>
  <mb_kinematics_msgs/BodyKinematicsArray.h> <mb_kinematics_msgs/LowerBodyArray.h>
  <nav_msgs/Odometry.h> <sensor_msgs/JointState.h> <tf2_msgs/TFMessage.h>)
add_dependencies(mbk_ros_test_headers mb_kinematics_msgs_generate_messages_cpp)
foreach(owner mbk_test_headers mbk_ros_test_headers)
  target_compile_options(${owner} PRIVATE -O1)
  # GoogleTest's include folder: /usr/include with libgtest-dev, else the sources catkin builds
  # it from (Debian's googletest package alone, as on a fresh machine).
  target_link_libraries(${owner} GTest::gtest)
endforeach()

# mbk_test_compile(HEADERS TARGET...): the test executables' own files at -O1, each with the
# precompiled HEADERS (mbk_test_headers or mbk_ros_test_headers).
function(mbk_test_compile headers)
  foreach(target ${ARGN})
    target_compile_options(${target} PRIVATE -O1)
    target_precompile_headers(${target} REUSE_FROM ${headers})
  endforeach()
endfunction()
