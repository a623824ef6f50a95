"""doc/python.md's memory per output (section Memory) against the arrays Model.kinematics
returns: every output in the table with its bytes per sample (and body), and the human body
model's figures."""
import re

import numpy as np

from conftest import source


def memory_section():
    text = open(source("doc/python.md"), encoding="utf-8").read()
    return text.split("### Memory", 1)[1].split("\n#", 1)[0]


def table(section):
    """output name -> (bytes, per body, times nv) from the table's rows."""
    rows = {}
    for line in section.split("\n"):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 2 or not cells[0].startswith("`"):
            continue
        m = re.match(r"^(\d+)( nv)?( per body)?( each)?$", cells[1])
        assert m, line
        for name in re.findall(r"`(\w+)`", cells[0]):
            rows[name] = (int(m.group(1)), bool(m.group(3)), bool(m.group(2)))
    return rows


def figure(section, words):
    """The number (commas allowed) right after `words` in the section."""
    m = re.search(re.escape(words) + r"\s+([\d,]+)", " ".join(section.split()))
    assert m, words
    return int(m.group(1).replace(",", ""))


def test_table_matches_the_arrays(mbk_kinematics):
    model = mbk_kinematics.load(source("test/robots/panda.urdf"))
    rows = table(memory_section())
    assert set(rows) == set(mbk_kinematics.OUTPUTS)  # every output, no other
    samples, bodies = 3, [1, 2]
    q = np.zeros((samples, model.nq))
    out = model.kinematics(q, q[:, :model.nv], q[:, :model.nv], outputs=list(rows),
                           bodies=bodies)
    for name, (size, per_body, times_nv) in rows.items():
        expected = size * (len(bodies) if per_body else 1) * (model.nv if times_nv else 1)
        assert out[name].nbytes == samples * expected, name
        single = model.kinematics(q, q[:, :model.nv], q[:, :model.nv], outputs=[name],
                                  bodies=bodies, dtype=np.float32)
        assert single[name].nbytes * 2 == out[name].nbytes, name


def test_human_body_figures(mbk_kinematics):
    model = mbk_kinematics.load(source("config/human_body.urdf"))
    section = memory_section()
    q = np.zeros((1, model.nq))
    v = np.zeros((1, model.nv))
    assert "37 bodies, nv = 37" in section and (model.body_count, model.nv) == (37, 37)
    full = sum(a.nbytes for a in model.kinematics(q, v, v).values())
    pose = sum(a.nbytes for a in model.kinematics(q).values())
    assert figure(section, "`acceleration` take") == full
    assert figure(section, "alone (`q` only)") == pose
    partial = model.kinematics(q, v, v, outputs=["partial_omega"])["partial_omega"].nbytes
    assert figure(section, "each partial-velocity output") == partial
    four = sum(a.nbytes for a in model.kinematics(
        q, v, v, outputs=[n for n in mbk_kinematics.OUTPUTS if n.startswith("partial_")]).values())
    assert figure(section, "the four") == four
    assert "(a million samples:\n%.1f GB)" % (full / 1e3) in section or \
        "a million samples: %.1f GB" % (full / 1e3) in " ".join(section.split())
