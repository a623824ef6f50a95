#!/usr/bin/python3
"""test/mocap/euler_spikes.py against doc/recorded_data.md's table "Angular velocity spikes of the
right hand": every figure of the table is what the script computes on the shipped recordings,
and the conclusion holds on 131_01: the right wrist's and thumb's samples over 20 rad/s are the
same samples in the Euler-rate and the rotation-group estimates (the spikes are in the recorded
orientations). The control: a smooth motion whose Euler angles switch to the equivalent
representation (a, b, c) -> (a + pi, pi - b, c + pi) mid-way spikes in the Euler-rate estimate
only, so the comparison does tell an artifact from the motion."""
import os
import re
import sys
import unittest

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import euler_spikes  # noqa: E402

DOC = os.path.join(HERE, "..", "..", "doc", "recorded_data.md")
THRESHOLD = 20.0  # rad/s, as the table's


def table_rows():
    """(recording, joints, euler cell, rotation-group cell) of the table's rows."""
    with open(DOC) as f:
        text = f.read()
    section = text[text.index("### Angular velocity spikes"):]
    rows = []
    for line in section.splitlines()[1:]:
        if line.startswith("#"):
            break
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 3 and re.match(r"\d+_\d+ ", cells[0]):
            recording, joints = cells[0].split(" ", 1)
            rows.append((recording, joints.split(", "), cells[1], cells[2]))
    return rows


def figures(cell):
    """The maxima (one per joint, before "rad/s") and the share over 20 rad/s (before "%") as
    printed: (text, value) pairs."""
    maxima = re.findall(r"[\d.]+", cell[:cell.index("rad/s")])
    share = re.search(r"([\d.]+) %", cell).group(1)
    return maxima, share


def as_printed(value, text):
    """`value` rounded to the decimals of `text`."""
    decimals = len(text.split(".")[1]) if "." in text else 0
    return round(value, decimals) == float(text)


class RecordingCache:
    files = {}

    @classmethod
    def speeds(cls, recording, joint):
        if recording not in cls.files:
            cls.files[recording] = euler_spikes.parse(os.path.join(HERE, recording + ".bvh"))
        segs, data, dt = cls.files[recording]
        euler, rotation, _ = euler_spikes.speeds(segs, data, dt, joint)
        return euler, rotation


class EulerSpikesTest(unittest.TestCase):
    def test_every_figure_of_the_table_is_reproduced(self):
        rows = table_rows()
        self.assertEqual(len(rows), 5, rows)
        for recording, joints, euler_cell, rotation_cell in rows:
            for column, cell in ((0, euler_cell), (1, rotation_cell)):
                maxima, share = figures(cell)
                self.assertEqual(len(maxima), len(joints), cell)
                for joint, text in zip(joints, maxima):
                    w = RecordingCache.speeds(recording, joint)[column]
                    where = "%s %s column %d" % (recording, joint, column)
                    self.assertTrue(as_printed(w.max(), text), "%s: max %.3f, table %s" %
                                    (where, w.max(), text))
                    self.assertTrue(as_printed(100 * np.mean(w > THRESHOLD), share),
                                    "%s: %.3f %%, table %s" %
                                    (where, 100 * np.mean(w > THRESHOLD), share))

    def test_the_right_hands_spikes_are_in_the_recorded_orientations(self):
        for joint in ("RightWrist", "RThumb"):
            euler, rotation = RecordingCache.speeds("131_01", joint)
            spikes = np.flatnonzero(euler > THRESHOLD)
            self.assertGreater(len(spikes), 0, joint)
            np.testing.assert_array_equal(np.flatnonzero(rotation > THRESHOLD), spikes,
                                          err_msg=joint)

    def test_a_representation_flip_spikes_in_the_euler_rates_only(self):
        dt = 1 / 120.0
        t = np.arange(240) * dt
        angles = np.degrees(np.stack([0.3 * np.sin(t), 0.5 + 0.2 * t, 0.5 * np.cos(t)], axis=1))
        flipped = angles.copy()
        flipped[120:] = angles[120:] * [1, -1, 1] + [180, 180, 180]  # (a+180, 180-b, c+180)
        segs = [{"name": "J", "parent": -1, "ch": ["Zrotation", "Xrotation", "Yrotation"],
                 "col": 0}]
        for f in range(len(t)):  # the same orientations
            np.testing.assert_allclose(euler_spikes.local(segs[0], flipped[f]),
                                       euler_spikes.local(segs[0], angles[f]), atol=1e-12)
        euler, rotation, _ = euler_spikes.speeds(segs, flipped, dt, "J")
        smooth, _, _ = euler_spikes.speeds(segs, angles, dt, "J")
        self.assertLess(smooth.max(), 2.0)
        self.assertGreater(euler.max(), 100.0)  # the flip, read as motion
        self.assertLess(rotation.max(), 2.0)  # what the motion is
        np.testing.assert_allclose(rotation, smooth, rtol=1e-3)


if __name__ == "__main__":
    unittest.main()
