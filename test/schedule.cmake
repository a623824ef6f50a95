# ctest's schedule (doc/building.md). On a clean clone ctest has no timings of a previous run and
# starts the tests in decreasing COST, then in the order they were added: the long ones are given
# their seconds here (a clean clone's ctest on the idle 2-core machine, doc/building.md), so that
# they start first and none is left running alone at the end. Include it after every test is added.
#
# scripts/test.sh runs `ctest -j6`, six slots on two cores: most tests wait (on a ROS master, on
# messages, on a timer) and take one slot (the 28 rostests and node_load_smoke: 54 CPU seconds in
# 139 s at -j4 on the busy machine); a test that keeps a core busy takes two (PROCESSORS): at most
# three of those at once, most of them short of a core (rviz, python_module: about 0.6). Four
# slots left the cores about 40 % idle: python_batch, fuzz_smoke and doc_pages, which mostly
# wait, held them all at the start, and the tests that take two slots waited behind those that
# take one, the rviz tests to the end (doc/building.md, "Where the time goes").
# rviz under Xvfb renders in software: about 0.6 of a core (rviz_moving_walk: 14.8 CPU seconds in
# its 25 s): two slots, never beside the node's rate tests (hztest at 50 Hz, node_load_smoke's
# every sample counted, /tf's longest gap during a heavy call in deep_partials), rviz tests
# beside each other (three at most, by their slots). rviz_hostile_many runs alone
# (test/rviz.cmake). doc_pages takes one slot: its blocks mostly wait (a launched node's settle
# time), three at once. fuzz_smoke starts with the first: it waits for the harnesses' clang build
# (which scripts/test.sh starts beside the install check and the tests' build), then runs them
# two at a time.

# mbk_tests_matching(REGEX OUT): the names of this directory's tests that match REGEX.
function(mbk_tests_matching regex out)
  get_property(tests DIRECTORY PROPERTY TESTS)
  list(FILTER tests INCLUDE REGEX "${regex}")
  set(${out} ${tests} PARENT_SCOPE)
endfunction()

# mbk_test_cost(REGEX SECONDS)
function(mbk_test_cost regex seconds)
  mbk_tests_matching("${regex}" tests)
  if(tests)
    set_tests_properties(${tests} PROPERTIES COST ${seconds})
  endif()
endfunction()

mbk_test_cost("^python_batch$" 225)
mbk_test_cost("^fuzz_smoke$" 185)  # the harnesses built beside the tests: their runs
mbk_test_cost("^doc_pages$" 147)
mbk_test_cost("^python_module$" 44)
mbk_test_cost("gtest_bag_test$" 32)
mbk_test_cost("rostest_test_ros_hostile\\.test$" 28)
mbk_test_cost("rostest_test_ros_(missing|node|base_odometry)\\.test$|^plot_kinematics$" 24)
mbk_test_cost("^node_load_smoke$" 20)
mbk_test_cost("rostest_test_ros_nodelet\\.test$|^rviz_hostile_far$|^doc_check$|^relaunch$" 17)
mbk_test_cost("gtest_offline_stream_test$|^plot_kinematics_bvh$|^gui_launch$|^xacro_launch$" 14)
mbk_test_cost("rostest_test_ros_deep_partials(_nodelet)?\\.test$|^rviz_robot_|^rviz_screenshot" 12)
mbk_test_cost("gtest_estimator_bound_test$" 12)
mbk_test_cost("^rviz_legend_reset$|rostest_test_ros_(reload|hz)\\.test$|tf_duplicate" 9)
mbk_test_cost("gtest_output_file_test$" 9)
# The long rviz tests (25 to 45 s each) next after the three longest, above their seconds: they
# can run beside doc_pages, which keeps the rate tests waiting anyway, and left last they ran two
# at a time with the cores half idle. Each has 40 s for its arrows to show, of which it needs 12
# or 20 (SETTLE, test/rviz.cmake); the short ones (20 s, none to spare on a busy machine) keep
# their place later, when fuzz_smoke's harnesses have ended.
mbk_test_cost("^rviz_(arrows|moving)_" 60)

# Busy tests: two slots each.
mbk_tests_matching("^fuzz_smoke$|^node_load_smoke$|^memcheck_|^python_module$|^rviz_" busy)
set_tests_properties(${busy} PROPERTIES PROCESSORS 2)

# Each rviz test locks a resource of its own name, which every rate test takes too: no rviz test
# beside a rate test (nor two rate tests together), rviz tests beside each other.
mbk_tests_matching("^rviz_|^doc_pages$" rviz)  # doc_pages starts rviz too
mbk_tests_matching("rostest_test_ros_(hz|nodelet|deep_partials|deep_partials_nodelet)\\.test$"
  rate)
list(APPEND rate node_load_smoke)
foreach(test IN LISTS rviz)
  set_property(TEST ${test} APPEND PROPERTY RESOURCE_LOCK ${test})
  set_property(TEST ${rate} APPEND PROPERTY RESOURCE_LOCK ${test})
endforeach()
