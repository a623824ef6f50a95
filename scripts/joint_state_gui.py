#!/usr/bin/env python3
"""joint_state_publisher_gui as `mb_kinematics.launch gui:=true` runs it: the package's own
program, with its sliders given whole numbers. joint_state_publisher_gui 1.15.1 (Debian
bookworm's joint-state-publisher-gui) passes a float to QSlider.setValue, which the PyQt5 of
Python 3.10 and later refuses: `TypeError: setValue(self, a0: int)` at start, and no GUI.
Elsewhere (ROS Noetic) this changes nothing."""
import runpy
import sys

import joint_state_publisher_gui
import roslib.packages
from python_qt_binding.QtWidgets import QSlider


class WholeSlider(QSlider):
    def setValue(self, value):
        super().setValue(int(round(value)))


def main():
    found = roslib.packages.find_node("joint_state_publisher_gui", "joint_state_publisher_gui")
    if not found:
        sys.exit("joint_state_publisher_gui is not installed: apt install joint-state-publisher-gui "
                 "(Debian) or ros-noetic-joint-state-publisher-gui (ROS Noetic)")
    joint_state_publisher_gui.QSlider = WholeSlider
    sys.argv[0] = found[0]
    runpy.run_path(found[0], run_name="__main__")


if __name__ == "__main__":
    main()
