# The rviz display on the running demo, headless (test/rviz/screenshot_test.sh): rviz under Xvfb
# with config/mb_kinematics.rviz; the screenshot goes to the test results folder. Serial: rviz's
# software rendering takes both cores, and the node's rate tests must not share them.
add_test(NAME rviz_screenshot
  COMMAND ${CATKIN_DEVEL_PREFIX}/env.sh ${PROJECT_SOURCE_DIR}/test/rviz/screenshot_test.sh
    ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME})
set_tests_properties(rviz_screenshot PROPERTIES RUN_SERIAL TRUE TIMEOUT 150)
