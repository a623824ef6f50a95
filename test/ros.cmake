# The node's tests (test/ros/): a unit test of the input layer (no ROS master) and rostest
# integration tests (each .test starts its own master and the nodes it needs).
find_package(rostest REQUIRED)

catkin_add_gtest(joint_state_input_test test/ros/joint_state_input_test.cc)
add_dependencies(joint_state_input_test mb_kinematics_msgs_generate_messages_cpp)
target_link_libraries(joint_state_input_test mbk_ros mbk_engine mbk_io mbk_core gtest_main)
target_compile_definitions(joint_state_input_test PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

# The input side's models, with and without ~base_odometry (no ROS master needed).
catkin_add_gtest(node_input_test test/ros/node_input_test.cc)
add_dependencies(node_input_test mb_kinematics_msgs_generate_messages_cpp)
target_link_libraries(node_input_test mbk_ros mbk_test_models mbk_io mbk_core gtest_main)

# No allocation per sample in the node's output fill functions (no ROS master needed).
catkin_add_gtest(output_allocation_test test/ros/output_allocation_test.cc)
add_dependencies(output_allocation_test mb_kinematics_msgs_generate_messages_cpp)
target_link_libraries(output_allocation_test mbk_ros mbk_test_models mbk_analysis mbk_io mbk_core
  gtest_main)
target_compile_definitions(output_allocation_test PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

# /tf's rotations against mbk::joint_quaternion, bit for bit (no master).
catkin_add_gtest(tf_fill_test test/ros/tf_fill_test.cc)
add_dependencies(tf_fill_test mb_kinematics_msgs_generate_messages_cpp)
target_link_libraries(tf_fill_test mbk_ros mbk_test_models mbk_core gtest_main)

# /tf's and body_kinematics' kept bytes against ros::serialization's, bit for bit (no master).
catkin_add_gtest(reused_serialization_test test/ros/reused_serialization_test.cc)
add_dependencies(reused_serialization_test mb_kinematics_msgs_generate_messages_cpp)
target_link_libraries(reused_serialization_test mbk_ros mbk_test_models mbk_core gtest_main)

# body_kinematics' system field against the core, with and without inertias (no master).
catkin_add_gtest(system_fields_test test/ros/system_fields_test.cc)
add_dependencies(system_fields_test mb_kinematics_msgs_generate_messages_cpp)
target_link_libraries(system_fields_test mbk_ros mbk_test_models mbk_analysis mbk_io mbk_core
  gtest_main)

# bvh_player's schedule and messages (no master needed).
catkin_add_gtest(frame_player_test test/ros/frame_player_test.cc)
target_link_libraries(frame_player_test mbk_ros gtest_main)

# The heap's freed pages back to the system after the model is read (no master needed).
catkin_add_gtest(heap_trim_test test/ros/heap_trim_test.cc)
target_link_libraries(heap_trim_test gtest_main)

# The picture shared by the rviz display and ~publish_markers (no master needed).
catkin_add_gtest(kinematics_markers_test test/ros/kinematics_markers_test.cc)
target_link_libraries(kinematics_markers_test mbk_markers mbk_io gtest_main)
target_compile_definitions(kinematics_markers_test PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
# Its limits: far bodies, long names, many bodies (ROS-free).
catkin_add_gtest(glyph_limits_test test/viz/glyph_limits_test.cc)
target_link_libraries(glyph_limits_test mbk_viz gtest_main)

# Its auto lengths on two robots of test/robots/ (ROS-free).
catkin_add_gtest(auto_lengths_test test/viz/auto_lengths_test.cc)
target_link_libraries(auto_lengths_test mbk_viz mbk_io mbk_core gtest_main)
target_compile_definitions(auto_lengths_test PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

# The rviz display's legend: its colors named (no master needed).
catkin_add_gtest(legend_test test/viz/legend_test.cc)
target_link_libraries(legend_test mbk_viz gtest_main)

# The integration tests' shared helpers (test/ros/ros_test_support.h), compiled once: in the
# header, their subscriptions' templates were compiled again in each of the tests below.
add_library(mbk_ros_test_support STATIC EXCLUDE_FROM_ALL test/ros/ros_test_support.cc)
add_dependencies(mbk_ros_test_support mb_kinematics_msgs_generate_messages_cpp)
target_link_libraries(mbk_ros_test_support mbk_io mbk_core ${catkin_LIBRARIES} ${GTEST_LIBRARIES})
target_compile_definitions(mbk_ros_test_support PRIVATE GTEST_HAS_PTHREAD=1
  MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}" MBK_NODE_PATH="$<TARGET_FILE:mb_kinematics_node>")
foreach(name node pairing rsp_compare markers hostile frame_prefix system base_odometry reload
    two_robots missing deep_partials)
  add_rostest_gtest(${name}_test test/ros/${name}.test test/ros/${name}_test.cc)
  add_dependencies(${name}_test mb_kinematics_node mb_kinematics_msgs_generate_messages_cpp)
  target_link_libraries(${name}_test mbk_ros_test_support mbk_ros mbk_io mbk_core
    ${catkin_LIBRARIES})
  target_compile_definitions(${name}_test PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    MBK_NODE_PATH="$<TARGET_FILE:mb_kinematics_node>")
endforeach()
add_dependencies(two_robots_test demo_publisher)  # launch/two_robots.launch runs it
# launch/bvh.launch on the real recording test/mocap/131_01.bvh.
add_rostest_gtest(bvh_launch_test test/ros/bvh_launch.test test/ros/bvh_launch_test.cc)
add_dependencies(bvh_launch_test mb_kinematics_node bvh_player mbk)
target_link_libraries(bvh_launch_test mbk_io mbk_core ${catkin_LIBRARIES})
add_rostest(test/ros/hz.test DEPENDENCIES mb_kinematics_node demo_publisher)
add_rostest(test/ros/nodelet.test DEPENDENCIES mbk_nodelet demo_publisher)
add_rostest(test/ros/deep_partials_nodelet.test DEPENDENCIES mbk_nodelet deep_partials_test)
add_rostest(test/ros/launch_description.test DEPENDENCIES mb_kinematics_node rsp_compare_test)
# Beside robot_state_publisher: the duplicate-/tf warning, and publish_tf:=false.
add_rostest(test/ros/tf_duplicate.test DEPENDENCIES mb_kinematics_node demo_publisher)
add_rostest(test/ros/tf_duplicate.test ARGS publish_tf:=false
  DEPENDENCIES mb_kinematics_node demo_publisher)

# The real-robot conformance set (test/robots/): the node against robot_state_publisher.
add_executable(real_robots_test EXCLUDE_FROM_ALL test/ros/real_robots_test.cc)
add_dependencies(tests real_robots_test)
add_dependencies(real_robots_test mb_kinematics_node mbk mbk_bag
  mb_kinematics_msgs_generate_messages_cpp)
target_include_directories(real_robots_test SYSTEM PRIVATE ${GTEST_INCLUDE_DIRS})
target_link_libraries(real_robots_test mbk_ros_test_support mbk_ros mbk_io mbk_core
  ${catkin_LIBRARIES} ${GTEST_LIBRARIES})
target_compile_definitions(real_robots_test PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
  MBK_NODE_PATH="$<TARGET_FILE:mb_kinematics_node>" MBK_MBK_PATH="$<TARGET_FILE:mbk>")
foreach(robot panda anymal_c solo12 romeo_small pr2 baxter)
  add_rostest(test/ros/real_robots.test ARGS robot:=${robot} DEPENDENCIES real_robots_test)
endforeach()
# The humanoid with a floating base from ~base_odometry.
add_rostest(test/ros/real_robots.test ARGS robot:=romeo_small odometry:=true
  DEPENDENCIES real_robots_test)
add_rostest_gtest(nodelet_load_test test/ros/nodelet_load.test test/ros/nodelet_load_test.cc)
add_dependencies(nodelet_load_test mbk_nodelet demo_publisher)
target_link_libraries(nodelet_load_test ${catkin_LIBRARIES})

# mbk bag on bags written by the test (no master needed).
catkin_add_gtest(bag_test test/offline/bag_test.cc)
add_dependencies(bag_test mbk mbk_bag mb_kinematics_msgs_generate_messages_cpp)
target_link_libraries(bag_test mbk_bag_cli mbk_offline mbk_analysis mbk_io mbk_core gtest_main)
target_compile_definitions(bag_test PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
  MBK_MBK_PATH="$<TARGET_FILE:mbk>")

# mbk bag's temporary files: created exclusively, never through a link, removed on signals.
catkin_add_gtest(output_file_test test/offline/output_file_test.cc)
add_dependencies(output_file_test mbk mbk_bag mb_kinematics_msgs_generate_messages_cpp)
target_link_libraries(output_file_test mbk_offline mbk_io mbk_core gtest_main)
target_compile_definitions(output_file_test PRIVATE MBK_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
  MBK_MBK_PATH="$<TARGET_FILE:mbk>")

# Their own files at -O1, with the node's tests' precompiled header (test/test_build.cmake).
mbk_test_compile(mbk_ros_test_headers joint_state_input_test node_input_test
  output_allocation_test reused_serialization_test system_fields_test frame_player_test
  heap_trim_test
  kinematics_markers_test glyph_limits_test legend_test node_test pairing_test rsp_compare_test
  markers_test hostile_test frame_prefix_test system_test base_odometry_test reload_test
  two_robots_test missing_test deep_partials_test bvh_launch_test real_robots_test
  nodelet_load_test bag_test output_file_test auto_lengths_test mbk_ros_test_support)

# scripts/node_load.sh end to end on its own master (port 11523), the node and transport_floor
# (MBK_WORKSPACE: test/tests.cmake).
add_test(NAME node_load_smoke COMMAND ${PROJECT_SOURCE_DIR}/test/ros/node_load_smoke.sh)
set_tests_properties(node_load_smoke PROPERTIES ENVIRONMENT MBK_WS=${MBK_WORKSPACE} TIMEOUT 120)

# mb_kinematics.launch gui:=true on Xvfb: joint_state_publisher_gui starts and drives the node.
add_test(NAME gui_launch
  COMMAND ${CATKIN_DEVEL_PREFIX}/env.sh ${PROJECT_SOURCE_DIR}/test/ros/gui_launch_test.sh)
set_tests_properties(gui_launch PROPERTIES TIMEOUT 90)

# The launch files one after another on one master: each start sets the node's parameters from
# its own arguments (publish_tf:=false's ~outputs does not linger), and says whether /tf is on.
add_test(NAME relaunch
  COMMAND ${CATKIN_DEVEL_PREFIX}/env.sh /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/ros/relaunch_test.py)
set_tests_properties(relaunch PROPERTIES TIMEOUT 150)

# A xacro model, and a xacro robot_description: both refusals name xacro and its command.
add_test(NAME xacro_launch
  COMMAND ${CATKIN_DEVEL_PREFIX}/env.sh /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/ros/xacro_launch_test.py)
set_tests_properties(xacro_launch PROPERTIES TIMEOUT 120)
