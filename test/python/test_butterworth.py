"""The Butterworth estimator (`--estimator butterworth:FC`, estimation/butterworth_estimator.h)
against scipy.signal.butter/filtfilt: the same zero-lag filter (Winter's two-pass correction, odd
reflection padding, steady-state starts), then 5-point differences of the filtered series."""
import csv
import os

import numpy as np
import pytest

import mb_kinematics
from conftest import mbk, source

signal = pytest.importorskip("scipy.signal")

C = (2 ** 0.5 - 1) ** 0.25  # Winter's correction for two passes


def scipy_estimates(x, rate, cutoff):
    """scipy's filtfilt at cutoff / C with the estimator's padding, then 5-point central
    differences; the interior samples (2 from each end) only."""
    b, a = signal.butter(2, cutoff / C / (rate / 2))
    pad = min(len(x) - 1, max(9, int(np.ceil(12 / (1 - np.sqrt(a[2]))))))
    y = signal.filtfilt(b, a, x, padtype="odd", padlen=pad)
    h = 1 / rate
    first = (y[:-4] - 8 * y[1:-3] + 8 * y[3:-1] - y[4:]) / (12 * h)
    second = (-y[:-4] + 16 * y[1:-3] - 30 * y[2:-2] + 16 * y[3:-1] - y[4:]) / (12 * h * h)
    return y, first, second


def noisy_sines(rate, seconds, nq, seed, noise=1e-3):
    t = np.arange(1, int(rate * seconds) + 1) / rate
    rng = np.random.default_rng(seed)
    f = rng.uniform(0.3, 3, nq)
    x = 0.4 * np.sin(2 * np.pi * np.outer(t, f)) + rng.normal(0, noise, (len(t), nq))
    return t, x, f


@pytest.mark.parametrize("rate,cutoff", [(100, 6), (1000, 6), (120, 10)])
def test_equals_scipy_filtfilt_then_differences(rate, cutoff):
    model = mb_kinematics.load(source("config/ten_body.yaml"))
    t, x, _ = noisy_sines(rate, 5, model.nq, 1)
    s = model.states(model.recording(t, x), estimator="butterworth:%g" % cutoff)
    for c in range(model.nq):
        _, first, second = scipy_estimates(x[:, c], rate, cutoff)
        # Interior samples; the differences' rounding grows as 1 / h^2.
        assert np.max(np.abs(s["velocity"][2:-2, c] - first)) <= 1e-10 * np.max(np.abs(first))
        assert np.max(np.abs(s["acceleration"][2:-2, c] - second)) <= 1e-8 * np.max(
            np.abs(second))
    assert s["velocity_se"].shape == x.shape and np.all(s["acceleration_se"] > 0)


def test_clean_sine_plus_noise_against_analytic_derivatives():
    """The two passes scale each sine by their gain at its frequency; away from the ends the
    estimates are the analytic derivatives of the scaled sines, to the noise's share."""
    model = mb_kinematics.load(source("config/ten_body.yaml"))
    rate, cutoff = 1000, 6
    t, x, f = noisy_sines(rate, 5, model.nq, 2, noise=1e-4)
    s = model.states(model.recording(t, x), estimator="butterworth:%g" % cutoff)
    ratio = np.tan(np.pi * f / rate) / np.tan(np.pi * cutoff / (C * rate))
    gain = 1 / (1 + ratio ** 4)
    w = 2 * np.pi * f
    inside = slice(500, -500)
    velocity = 0.4 * gain * w * np.cos(np.outer(t, w))
    acceleration = -0.4 * gain * w ** 2 * np.sin(np.outer(t, w))
    for estimate, exact in ((s["velocity"], velocity), (s["acceleration"], acceleration)):
        err = np.abs(estimate[inside] - exact[inside]).max(axis=0) / np.abs(exact).max(axis=0)
        assert err.max() < (5e-3 if exact is velocity else 5e-2), err


def test_mbk_bag_writes_error_bars(tmp_path):
    model = source("config/ten_body.yaml")
    nq = mb_kinematics.load(model).nq
    t, x, _ = noisy_sines(100, 4, nq, 3)
    names = mb_kinematics.load(model).coordinate_names
    path = tmp_path / "walk.csv"
    with open(path, "w") as out:
        out.write("time," + ",".join(names) + "\n")
        for i in range(len(t)):
            out.write("%.6f," % t[i] + ",".join("%.17g" % v for v in x[i]) + "\n")
    for name in ("butterworth:6", "butterworth:auto"):
        csv_path = tmp_path / ("out_%s.csv" % name.replace(":", "_"))
        mbk("bag", str(path), "--model", model, "--estimator", name, "--csv", str(csv_path))
        with open(str(csv_path)) as f:
            header = next(csv.reader(f))
        assert "alpha_se_x" in header and "acceleration_se_z" in header
        errors = str(csv_path)[:-4] + ".errors.csv"
        assert os.path.isfile(errors)
        rows = list(csv.DictReader(open(errors)))
        assert len(rows) == nq and all(0.5e-3 < float(r["noise"]) < 2e-3 for r in rows)
