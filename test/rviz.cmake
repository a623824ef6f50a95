# The rviz display on the running demo, headless (test/rviz/screenshot_test.sh): rviz under Xvfb
# with config/mb_kinematics.rviz; the screenshot goes to the test results folder. Each takes two
# of ctest's slots and none runs beside the node's rate tests (test/schedule.cmake).
add_test(NAME rviz_screenshot
  COMMAND ${CATKIN_DEVEL_PREFIX}/env.sh ${PROJECT_SOURCE_DIR}/test/rviz/screenshot_test.sh
    ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME})
set_tests_properties(rviz_screenshot PROPERTIES TIMEOUT 150)

# mbk_rviz_robot_test(NAME ROBOT FRAME TIMEOUT [VAR=VALUE...]): screenshot_test.sh on the demo of
# test/robots/ROBOT.urdf, its Fixed Frame expected to be FRAME, with more of its environment.
function(mbk_rviz_robot_test name robot frame timeout)
  add_test(NAME ${name}
    COMMAND ${CATKIN_DEVEL_PREFIX}/env.sh ${PROJECT_SOURCE_DIR}/test/rviz/screenshot_test.sh
      ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME})
  string(JOIN ";" environment
    "DEMO_ARGS=model:=${PROJECT_SOURCE_DIR}/test/robots/${robot}.urdf" EXPECT_FRAME=${frame} ${ARGN})
  set_tests_properties(${name} PROPERTIES TIMEOUT ${timeout} ENVIRONMENT "${environment}")
endfunction()

# The same on real robots (test/robots/, no meshes): config/mb_kinematics.rviz says Fixed Frame
# `world`, which these robots have not; the display must set it to the model's root link and frame
# the robot, so that the arrows show in the middle of the 3D view (REGION, and CENTER: their
# centroid within 120 px of the view's centre; the 3D view spans x 364..1264, y 62..802 of the
# 1280x900 screen).
mbk_rviz_robot_test(rviz_robot_panda panda panda_link0 60 REGION=520,200,1080,700
  CENTER=814,432,120 SHOT_NAME=rviz_panda TIMEOUT=20)
mbk_rviz_robot_test(rviz_robot_anymal_c anymal_c base 60 REGION=520,200,1080,700
  CENTER=814,432,120 SHOT_NAME=rviz_anymal_c TIMEOUT=20)

# The same on launch/bvh.launch and config/bvh.rviz: the real walk test/mocap/131_01.bvh.
add_test(NAME rviz_screenshot_bvh
  COMMAND ${CATKIN_DEVEL_PREFIX}/env.sh ${PROJECT_SOURCE_DIR}/test/rviz/screenshot_test.sh
    ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME}/bvh)
set_tests_properties(rviz_screenshot_bvh PROPERTIES TIMEOUT 150 ENVIRONMENT
  "LAUNCH=bvh.launch;RVIZ_CONFIG=${PROJECT_SOURCE_DIR}/config/bvh.rviz;DEMO_ARGS=bvh:=${PROJECT_SOURCE_DIR}/test/mocap/131_01.bvh scale:=0.056444")

# Hostile input (test/rviz/hostile_bodies.launch, no node): a robot at UTM coordinates (x 500000,
# y 5000000) with a body name of 30,000 characters: rviz must draw it and still run 5 s later
# (it aborted in Ogre on arrows whose ends a float could not tell apart, and overflowed the
# stack in the body filter's regex). Then 10,000 bodies at 5 Hz: at most Max Bodies drawn, rviz
# under 330 MB and out within 2.5 s of SIGINT (10 runs on the loaded 2-core machine: 0.24-0.25
# GB, out in 0.36-1.09 s; with Max Bodies 500 and the glyphs drawn to the end, 0.39 GB and out in
# 1.55-6.76 s, 8 of 10 runs over 2.5 s: rviz acts on SIGINT at the end of a frame, seconds long
# under software rendering at 500 bodies); that one runs alone.
add_test(NAME rviz_hostile_far
  COMMAND ${CATKIN_DEVEL_PREFIX}/env.sh ${PROJECT_SOURCE_DIR}/test/rviz/screenshot_test.sh
    ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME})
set_tests_properties(rviz_hostile_far PROPERTIES TIMEOUT 90 ENVIRONMENT
  "LAUNCH=hostile_bodies.launch;READY=hostile bodies: publishing;SHOT_NAME=rviz_hostile_far;TIMEOUT=30;HOLD=5")
add_test(NAME rviz_hostile_many
  COMMAND ${CATKIN_DEVEL_PREFIX}/env.sh ${PROJECT_SOURCE_DIR}/test/rviz/screenshot_test.sh
    ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME})
set_tests_properties(rviz_hostile_many PROPERTIES RUN_SERIAL TRUE TIMEOUT 120 ENVIRONMENT
  "LAUNCH=hostile_bodies.launch;DEMO_ARGS=bodies:=10000 rate:=5 name_length:=10;READY=hostile bodies: publishing;SHOT_NAME=rviz_hostile_many;TIMEOUT=40;HOLD=10;MAX_RSS_MB=330;SIGINT_WITHIN=2.5")
# After 20 s of motion (SETTLE), the moving robot still inside the 3D view, not at its edge:
# every arrow color in REGION (the view less 80 px on each side) and centred within 150 px. An
# arm (panda), a humanoid (romeo_small) and the BVH walker (config/bvh.rviz's camera follows
# its root segment). ARGN: the test's environment, one VAR=VALUE each.
function(mbk_rviz_moving_test name)
  add_test(NAME ${name}
    COMMAND ${CATKIN_DEVEL_PREFIX}/env.sh ${PROJECT_SOURCE_DIR}/test/rviz/screenshot_test.sh
      ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME})
  set_tests_properties(${name} PROPERTIES TIMEOUT 90 ENVIRONMENT
    "${ARGN};REGION=444,142,1184,722;CENTER=814,432,150;SHOT_NAME=${name};SETTLE=20;TIMEOUT=40")
endfunction()
mbk_rviz_moving_test(rviz_moving_panda
  "DEMO_ARGS=model:=${PROJECT_SOURCE_DIR}/test/robots/panda.urdf" EXPECT_FRAME=panda_link0)
mbk_rviz_moving_test(rviz_moving_romeo_small
  "DEMO_ARGS=model:=${PROJECT_SOURCE_DIR}/test/robots/romeo_small.urdf" EXPECT_FRAME=base_link)
mbk_rviz_moving_test(rviz_moving_walk LAUNCH=bvh.launch
  RVIZ_CONFIG=${PROJECT_SOURCE_DIR}/config/bvh.rviz
  "DEMO_ARGS=bvh:=${PROJECT_SOURCE_DIR}/test/mocap/131_01.bvh scale:=0.056444")
# A humanoid on a moving base (test/rviz/moving_base.launch: base_odometry, the base walking 10 m
# in 20 s): the shipped config's view follows the base (the display sets the Orbit view's Target
# Frame), so after 20 s the robot is still in the middle of the view.
mbk_rviz_moving_test(rviz_moving_base LAUNCH=moving_base.launch EXPECT_FRAME=odom
  EXPECT_FOLLOW=base_link)
# Arrow lengths on robots of different sizes (doc/rviz.md#arrow-lengths): Solo 12 (0.58 m, the
# box around its joint points and mass centers) and Baxter (2.58 m). After 12 s of motion, over
# 12 screenshots, the longest velocity and acceleration arrows are 0.16 to 0.8 of the robot's size
# on screen (test/rviz/arrow_lengths.py): at most the rule's cap, 2 L = 0.8 s (doc/rviz.md), at
# least 0.4 of L. Measured over 3 runs 0.21 to 0.32 on Solo 12, 0.32 to 0.59 on Baxter; with 0.3 m
# for every robot's longest arrow, Baxter's were 0.10 and 0.14.
foreach(robot solo12:base_link baxter:base)
  string(REPLACE ":" ";" robot ${robot})
  list(GET robot 0 name)
  list(GET robot 1 frame)
  mbk_rviz_robot_test(rviz_arrows_${name} ${name} ${frame} 240 SHOT_NAME=rviz_arrows_${name}
    SETTLE=12 TIMEOUT=40 ARROW_FRACTION=0.16,0.8)
endforeach()

# The display's Legend in a real rviz (test/rviz/legend_reset_test.cc): shown at start and again
# after each of rviz's resets (a change of the Fixed Frame, the Reset button), which clear a
# display's statuses; each row fits the Displays panel whole.
catkin_add_executable_with_gtest(legend_reset_test test/rviz/legend_reset_test.cc)
target_include_directories(legend_reset_test SYSTEM PRIVATE ${rviz_INCLUDE_DIRS})
target_compile_definitions(legend_reset_test PRIVATE QT_NO_KEYWORDS)
target_link_libraries(legend_reset_test ${rviz_LIBRARIES} Qt5::Widgets ${catkin_LIBRARIES})
add_dependencies(legend_reset_test mbk_rviz)
add_test(NAME rviz_legend_reset
  COMMAND ${CATKIN_DEVEL_PREFIX}/env.sh ${PROJECT_SOURCE_DIR}/test/rviz/legend_reset_test.sh
    $<TARGET_FILE:legend_reset_test>)
set_tests_properties(rviz_legend_reset PROPERTIES TIMEOUT 60)
