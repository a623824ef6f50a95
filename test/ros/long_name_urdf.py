#!/usr/bin/env python3
"""Prints a URDF whose moving link has a name of LENGTH characters (default 30,000): hostile.test
gives it to a node with ~publish_markers (a name that long once overflowed the stack in the
markers' body filter)."""
import sys

length = int(sys.argv[1]) if len(sys.argv) > 1 else 30000
name = "long" + "n" * (length - 4)
print(f"""<robot name="long_name">
  <link name="base"/>
  <link name="{name}">
    <inertial><origin xyz="0.5 0 0"/><mass value="1"/>
      <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="turn" type="continuous">
    <parent link="base"/><child link="{name}"/><axis xyz="0 0 1"/>
  </joint>
</robot>""")
