#!/usr/bin/python3
"""The converted BlazePose models (models/pose/, made by deploy/setup) through cv2.dnn against the numpy
reference interpreter of their .tflite originals, on a real photo. Fails (not skips) without them."""
import os
import sys
import unittest

import cv2
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools", "model_convert"))

import tflite_reference as ref  # noqa: E402
from errors import ConversionError  # noqa: E402
from tflite_schema import read_model  # noqa: E402

MODELS = os.path.join(ROOT, "models", "pose")
IMAGE = os.path.join(ROOT, "data", "people", "000000000785.jpg")   # one skier, whole body in view
# Measured 1.5e-4 (lite), 1.7e-4 (full) crop pixels, 3.5e-4 on the detector's raw outputs (values up to
# ~680): float32 against float64 over ~100 layers. A layout or padding mistake is off by pixels.
LANDMARK_TOLERANCE_PX = 1e-3
DETECTOR_TOLERANCE = 2e-3
# The photo's person is clear: the pose flag must say so (guards against a model that runs but is wrong
# in both implementations, e.g. a misread weight layout).
MIN_POSE_FLAG = 0.9


def model_path(name, ext):
    path = os.path.join(MODELS, f"{name}.{ext}")
    if not os.path.isfile(path):
        raise AssertionError(f"{path} missing: run deploy/setup (deploy/models converts the pose models)")
    return path


def rgb_square(size, lo, hi):
    """The photo's centred square crop, resized, RGB scaled to [lo, hi], NHWC float32."""
    bgr = cv2.imread(IMAGE)
    if bgr is None:
        raise AssertionError(f"{IMAGE} unreadable")
    h, w = bgr.shape[:2]
    s = min(h, w)
    crop = bgr[(h - s) // 2:(h - s) // 2 + s, (w - s) // 2:(w - s) // 2 + s]
    rgb = cv2.cvtColor(cv2.resize(crop, (size, size), interpolation=cv2.INTER_AREA), cv2.COLOR_BGR2RGB)
    return (rgb.astype(np.float32) / 255.0 * (hi - lo) + lo)[None]


def compare(name, size, lo, hi):
    onnx_path, tflite_path = model_path(name, "onnx"), model_path(name, "tflite")
    net = cv2.dnn.readNetFromONNX(onnx_path)
    outs = list(net.getUnconnectedOutLayersNames())
    x = rgb_square(size, lo, hi)
    net.setInput(np.ascontiguousarray(x.transpose(0, 3, 1, 2)))
    got = dict(zip(outs, net.forward(outs)))
    with open(tflite_path, "rb") as f:
        want = ref.run(read_model(f.read()), {"input_1": x}, outs)
    return got, want


class ConvertedModels(unittest.TestCase):
    def check_landmarks(self, name):
        got, want = compare(name, 256, 0.0, 1.0)
        self.assertEqual(sorted(got), ["Identity", "Identity_1"])     # segmentation and heatmaps pruned
        self.assertEqual(got["Identity"].shape, (1, 195))
        self.assertEqual(got["Identity_1"].shape, (1, 1))
        diff = np.abs(got["Identity"] - want["Identity"]).max()
        print(f"{name}: max |cv2.dnn - reference| = {diff:.2e} crop px", file=sys.stderr)
        self.assertLess(diff, LANDMARK_TOLERANCE_PX)
        self.assertLess(abs(got["Identity_1"] - want["Identity_1"]).max(), 1e-4)
        self.assertGreater(float(got["Identity_1"]), MIN_POSE_FLAG)
        xy = got["Identity"].reshape(39, 5)[:33, :2]
        self.assertTrue(np.all((xy > 0) & (xy < 256)), "a whole body in view: every landmark inside the crop")

    def test_landmark_lite(self):
        self.check_landmarks("pose_landmark_lite")

    def test_landmark_full(self):
        self.check_landmarks("pose_landmark_full")

    def test_detector(self):
        got, want = compare("pose_detection", 224, -1.0, 1.0)
        self.assertEqual(got["Identity"].shape, (1, 2254, 12))
        self.assertEqual(got["Identity_1"].shape, (1, 2254, 1))
        for k, tol in (("Identity", DETECTOR_TOLERANCE), ("Identity_1", DETECTOR_TOLERANCE)):
            diff = np.abs(got[k] - want[k]).max()
            print(f"pose_detection {k}: max |cv2.dnn - reference| = {diff:.2e}", file=sys.stderr)
            self.assertLess(diff, tol)
        best = 1 / (1 + np.exp(-got["Identity_1"].max()))
        self.assertGreater(best, 0.5, "the skier is detected by some anchor")

    def test_truncated_real_model_refused(self):
        with open(model_path("pose_landmark_lite", "tflite"), "rb") as f:
            data = f.read()
        for cut in (len(data) // 2, len(data) - 100):
            with self.assertRaisesRegex(ConversionError, "truncated"):
                read_model(data[:cut])


if __name__ == "__main__":
    unittest.main()
