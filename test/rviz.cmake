# The rviz display on the running demo, headless (test/rviz/screenshot_test.sh): rviz under Xvfb
# with config/mb_kinematics.rviz; the screenshot goes to the test results folder. Serial: rviz's
# software rendering takes both cores, and the node's rate tests must not share them.
add_test(NAME rviz_screenshot
  COMMAND ${CATKIN_DEVEL_PREFIX}/env.sh ${PROJECT_SOURCE_DIR}/test/rviz/screenshot_test.sh
    ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME})
set_tests_properties(rviz_screenshot PROPERTIES RUN_SERIAL TRUE TIMEOUT 150)
# The same on launch/bvh.launch and config/bvh.rviz: the real walk test/mocap/131_01.bvh.
add_test(NAME rviz_screenshot_bvh
  COMMAND ${CATKIN_DEVEL_PREFIX}/env.sh ${PROJECT_SOURCE_DIR}/test/rviz/screenshot_test.sh
    ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME}/bvh)
set_tests_properties(rviz_screenshot_bvh PROPERTIES RUN_SERIAL TRUE TIMEOUT 150 ENVIRONMENT
  "LAUNCH=bvh.launch;RVIZ_CONFIG=${PROJECT_SOURCE_DIR}/config/bvh.rviz;DEMO_ARGS=bvh:=${PROJECT_SOURCE_DIR}/test/mocap/131_01.bvh scale:=0.056444")
