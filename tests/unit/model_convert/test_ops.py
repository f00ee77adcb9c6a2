#!/usr/bin/python3
"""Each converted op: the numpy reference against known answers, then the ONNX conversion run through
cv2.dnn against the reference on small random graphs; what the converter must refuse, refused by name."""
import os
import subprocess
import sys
import tempfile
import unittest

import cv2
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
CONVERTER = os.path.join(HERE, "..", "..", "..", "tools", "model_convert")
sys.path[:0] = [CONVERTER, HERE]

import tflite_reference as ref  # noqa: E402
from errors import ConversionError  # noqa: E402
from sparsity import densify  # noqa: E402
from tflite2onnx import convert  # noqa: E402
from tflite_builder import Graph  # noqa: E402
from tflite_schema import Sparsity, read_model  # noqa: E402

# cv2.dnn (float32) against the float64 reference on values of order 1: float32 rounding over a few
# hundred products, far below any layout or padding mistake (those give errors of order 1).
TOLERANCE = 1e-4
RNG = np.random.default_rng(29)


def run_cv2(onnx_model, x_nhwc, outputs):
    net = cv2.dnn.readNetFromONNX(np.frombuffer(onnx_model.SerializeToString(), np.uint8))
    net.setInput(np.ascontiguousarray(x_nhwc.transpose(0, 3, 1, 2)))
    return net.forward(outputs)


def single_op_graph(op, in_shape, out_shape, consts=(), stored=np.float16, **options):
    """input -> op(input, *consts) -> output; consts are float weights or int32 operands."""
    g = Graph()
    x = g.tensor("input", in_shape)
    ins = [x] + [g.const(f"c{k}", c, stored) for k, c in enumerate(consts)]
    y = g.tensor("output", out_shape)
    g.op(op, ins, [y], **options)
    g.inputs, g.outputs = [x], [y]
    return g


class ReferenceKnownAnswers(unittest.TestCase):
    """The judge is checked first, on answers worked out by hand from TFLite's op definitions."""

    def test_same_padding_puts_the_odd_pixel_after(self):
        # 4 wide, kernel 3, stride 2: output 2, total pad (2-1)*2+3-4 = 1 -> (0, 1)
        self.assertEqual(ref.same_padding(4, 3, 2), (0, 1))
        self.assertEqual(ref.same_padding(5, 3, 1), (1, 1))
        self.assertEqual(ref.same_padding(4, 2, 2), (0, 0))

    def test_conv_same_stride_2_on_a_ramp(self):
        x = np.arange(16, dtype=np.float64).reshape(1, 4, 4, 1)
        w = np.ones((1, 3, 3, 1))
        y = ref.conv_2d(x, w, None, dict(padding="SAME", stride_h=2, stride_w=2, activation="NONE"))
        # padding (0, 1): output (0,0) sums rows 0..2, cols 0..2; (1,1) rows 2..3, cols 2..3 and the pad.
        # Padding before instead (1, 0) would give 0+1+4+5 = 10 at (0,0).
        self.assertEqual(y[0, 0, 0, 0], 0 + 1 + 2 + 4 + 5 + 6 + 8 + 9 + 10)
        self.assertEqual(y[0, 1, 1, 0], 10 + 11 + 14 + 15)

    def test_depthwise_channel_multiplier_order(self):
        # 2 channels, multiplier 2: output channel c*2+m reads input channel c
        x = np.array([1.0, 10.0]).reshape(1, 1, 1, 2)
        w = np.array([1.0, 2.0, 3.0, 4.0]).reshape(1, 1, 1, 4)
        y = ref.depthwise_conv_2d(x, w, None, dict(padding="VALID", stride_h=1, stride_w=1, depth_multiplier=2,
                                                    activation="NONE"))
        np.testing.assert_array_equal(y.ravel(), [1, 2, 30, 40])

    def test_resize_half_pixel_doubling(self):
        # [0, 4] doubled: sources -0.25, 0.25, 0.75, 1.25 -> clamped 0, 1, 3, 4
        x = np.array([0.0, 4.0]).reshape(1, 1, 2, 1)
        y = ref.resize_bilinear(x, [1, 4], False, True)
        np.testing.assert_allclose(y.ravel(), [0, 1, 3, 4])

    def test_depth_to_space_order(self):
        # 1x1 pixel, 4 channels [a b c d], block 2 -> [[a b], [c d]]
        y = ref.depth_to_space(np.arange(4.0).reshape(1, 1, 1, 4), 2)
        np.testing.assert_array_equal(y[0, :, :, 0], [[0, 1], [2, 3]])

    def test_max_pool_same_ignores_padding(self):
        x = -np.ones((1, 3, 3, 1))
        y = ref.max_pool_2d(x, dict(padding="SAME", stride_h=2, stride_w=2, filter_h=2, filter_w=2,
                                    activation="NONE"))
        np.testing.assert_array_equal(y.ravel(), [-1, -1, -1, -1])

    def test_densify_csr_on_the_last_dimension(self):
        # 2x3, row 0 has (0,2), row 1 has (1): values 5 7 9
        sp = Sparsity([0, 1], [], [("DENSE", 2), ("CSR", np.array([0, 2, 3]), np.array([0, 2, 1]))])
        d = densify([2, 3], np.array([5.0, 7.0, 9.0]), sp, "t")
        np.testing.assert_array_equal(d, [[5, 0, 7], [0, 9, 0]])

    def test_densify_refuses_inconsistent_segments(self):
        sp = Sparsity([0, 1], [], [("DENSE", 2), ("CSR", np.array([0, 2]), np.array([0, 2]))])
        with self.assertRaisesRegex(ConversionError, "segments"):
            densify([2, 3], np.array([5.0, 7.0]), sp, "t")


class OpConversion(unittest.TestCase):
    """Each op through flatbuffer -> reader -> converter -> cv2.dnn, against the reference."""

    def check(self, g, in_shape):
        model = read_model(g.build())
        x = RNG.uniform(-1, 1, in_shape).astype(np.float32)
        want = ref.run(model, {"input": x})["output"]
        got = run_cv2(convert(model), x, ["output"])[0]
        self.assertEqual(got.shape, want.shape)
        diff = np.abs(got - want).max()
        self.assertLess(diff, TOLERANCE, f"max |cv2.dnn - reference| = {diff}")
        self.assertGreater(np.abs(want).max(), 0.05, "a known answer of zeros would prove nothing")
        return want

    def test_conv_2d_same_even_size_stride_2_relu6(self):
        w, b = RNG.normal(0, 1, (5, 3, 3, 4)), RNG.normal(0, 1, 5)
        self.check(single_op_graph("CONV_2D", [1, 8, 8, 4], [1, 4, 4, 5], [w, b], padding="SAME", stride=2,
                                   activation="RELU6"), [1, 8, 8, 4])

    def test_conv_2d_valid_1x1(self):
        w, b = RNG.normal(0, 1, (6, 1, 1, 3)), RNG.normal(0, 1, 6)
        self.check(single_op_graph("CONV_2D", [1, 5, 7, 3], [1, 5, 7, 6], [w, b], padding="VALID"), [1, 5, 7, 3])

    def test_conv_2d_dilated(self):
        w, b = RNG.normal(0, 1, (2, 3, 3, 2)), RNG.normal(0, 1, 2)
        self.check(single_op_graph("CONV_2D", [1, 9, 9, 2], [1, 9, 9, 2], [w, b], padding="SAME", dilation=2),
                   [1, 9, 9, 2])

    def test_conv_2d_with_sparse_weights_behind_densify(self):
        w = RNG.normal(0, 1, (4, 1, 1, 6)) * (RNG.uniform(size=(4, 1, 1, 6)) < 0.5)
        rows, idx, vals = [0], [], []
        for r in w.reshape(4, 6):
            nz = np.nonzero(r)[0]
            idx += list(nz)
            vals += list(r[nz])
            rows.append(len(idx))
        g = Graph()
        x = g.tensor("input", [1, 3, 3, 6])
        sparse = g.tensor("w_sparse", [4, 1, 1, 6], np.float16, np.asarray(vals, np.float16),
                          sparsity=([0, 1, 2, 3], [("DENSE", 4), ("DENSE", 1), ("DENSE", 1), ("CSR", rows, idx)]))
        dense16, dense32 = g.tensor("w16", [4, 1, 1, 6], np.float16), g.tensor("w", [4, 1, 1, 6])
        g.op("DENSIFY", [sparse], [dense16])
        g.op("DEQUANTIZE", [dense16], [dense32])
        bias = g.const("b", np.zeros(4))
        y = g.tensor("output", [1, 3, 3, 4])
        g.op("CONV_2D", [x, dense32, bias], [y], padding="VALID")
        g.inputs, g.outputs = [x], [y]
        model = read_model(g.build())
        consts = ref.fold_constants(model)[0]
        np.testing.assert_array_equal(consts[dense32], w.astype(np.float16).astype(np.float32))
        self.check(g, [1, 3, 3, 6])

    def test_depthwise_conv_2d_same_stride_2_multiplier_1(self):
        w, b = RNG.normal(0, 1, (1, 3, 3, 4)), RNG.normal(0, 1, 4)
        self.check(single_op_graph("DEPTHWISE_CONV_2D", [1, 6, 6, 4], [1, 3, 3, 4], [w, b], padding="SAME",
                                   stride=2, activation="RELU6"), [1, 6, 6, 4])

    def test_depthwise_conv_2d_multiplier_2(self):
        w, b = RNG.normal(0, 1, (1, 5, 5, 6)), RNG.normal(0, 1, 6)
        self.check(single_op_graph("DEPTHWISE_CONV_2D", [1, 7, 7, 3], [1, 7, 7, 6], [w, b], padding="SAME",
                                   depth_multiplier=2), [1, 7, 7, 3])

    def test_max_pool_2d(self):
        self.check(single_op_graph("MAX_POOL_2D", [1, 6, 6, 3], [1, 3, 3, 3], padding="VALID", stride=2, filter=2),
                   [1, 6, 6, 3])

    def test_add_relu6_with_a_per_channel_constant(self):
        self.check(single_op_graph("ADD", [1, 4, 4, 3], [1, 4, 4, 3], [RNG.normal(0, 3, 3)], activation="RELU6"),
                   [1, 4, 4, 3])

    def test_add_two_activations(self):
        g = Graph()
        x = g.tensor("input", [1, 4, 4, 2])
        h = g.tensor("h", [1, 4, 4, 2])
        y = g.tensor("output", [1, 4, 4, 2])
        g.op("LOGISTIC", [x], [h])
        g.op("ADD", [x, h], [y])
        g.inputs, g.outputs = [x], [y]
        self.check(g, [1, 4, 4, 2])

    def test_logistic(self):
        self.check(single_op_graph("LOGISTIC", [1, 3, 3, 2], [1, 3, 3, 2]), [1, 3, 3, 2])

    def test_pad_spatial_and_channels(self):
        paddings = np.array([[0, 0], [1, 2], [0, 1], [0, 3]], np.int32)
        self.check(single_op_graph("PAD", [1, 3, 4, 2], [1, 6, 5, 5], [paddings]), [1, 3, 4, 2])

    def test_reshape_out_of_4d_keeps_nhwc_order(self):
        shape = np.array([1, 12, 3], np.int32)
        self.check(single_op_graph("RESHAPE", [1, 2, 2, 9], [1, 12, 3], [shape]), [1, 2, 2, 9])

    def test_resize_bilinear_half_pixel(self):
        size = np.array([8, 6], np.int32)
        self.check(single_op_graph("RESIZE_BILINEAR", [1, 4, 3, 2], [1, 8, 6, 2], [size], half_pixel_centers=True),
                   [1, 4, 3, 2])

    def concat_graph(self, shape, axis, reshape_to=None):
        """concat(x, logistic(x)) on `axis`, after a RESHAPE to `reshape_to` when given (the detector's way)."""
        g = Graph()
        x = g.tensor("input", shape)
        a = x
        if reshape_to:
            a = g.tensor("r", reshape_to)
            g.op("RESHAPE", [x, g.const("s", np.asarray(reshape_to, np.int32))], [a])
        cur = reshape_to or shape
        h = g.tensor("h", cur)
        g.op("LOGISTIC", [a], [h])
        out = list(cur)
        out[axis] *= 2
        y = g.tensor("output", out)
        g.op("CONCATENATION", [a, h], [y], axis=axis)
        g.inputs, g.outputs = [x], [y]
        return g

    def test_concatenation_on_channels(self):
        self.check(self.concat_graph([1, 3, 3, 4], 3), [1, 3, 3, 4])

    def test_concatenation_after_reshape_to_3d(self):
        self.check(self.concat_graph([1, 2, 2, 6], 1, [1, 8, 3]), [1, 2, 2, 6])

    def test_concatenation_with_a_constant_refused(self):
        # cv::dnn 4.6 computes concat(input, constant) wrong (half the channels garbage): refused, not converted
        g = single_op_graph("CONCATENATION", [1, 3, 3, 4], [1, 3, 3, 6], [RNG.normal(0, 1, (1, 3, 3, 2))], axis=3)
        with self.assertRaisesRegex(ConversionError, "CONCATENATION"):
            convert(read_model(g.build()))

    def test_depth_to_space(self):
        self.check(single_op_graph("DEPTH_TO_SPACE", [1, 2, 3, 8], [1, 4, 6, 2], block_size=2), [1, 2, 3, 8])


class Refusals(unittest.TestCase):
    def convert_cli(self, data):
        with tempfile.TemporaryDirectory() as d:
            src, dst = os.path.join(d, "m.tflite"), os.path.join(d, "m.onnx")
            with open(src, "wb") as f:
                f.write(data)
            r = subprocess.run([sys.executable, os.path.join(CONVERTER, "tflite2onnx.py"), src, dst],
                               capture_output=True, text=True)
            return r, os.path.exists(dst)

    def test_unknown_op_refused_with_its_name(self):
        data = single_op_graph("TANH", [1, 2, 2, 1], [1, 2, 2, 1]).build()
        with self.assertRaisesRegex(ConversionError, "TANH"):
            convert(read_model(data))
        r, written = self.convert_cli(data)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("TANH", r.stderr)
        self.assertFalse(written)

    def test_unknown_tensor_type_refused_with_its_name(self):
        g = single_op_graph("LOGISTIC", [1, 2, 2, 1], [1, 2, 2, 1])
        g.tensors[1]["type_code"] = 6                    # BOOL
        with self.assertRaisesRegex(ConversionError, "BOOL"):
            read_model(g.build())

    def test_truncated_file_refused(self):
        w = RNG.normal(0, 1, (4, 3, 3, 4))
        data = single_op_graph("CONV_2D", [1, 4, 4, 4], [1, 4, 4, 4], [w, np.zeros(4)], padding="SAME").build()
        read_model(data)                                 # whole: reads
        for cut in (len(data) // 3, len(data) // 2, len(data) - 16, 6):
            with self.assertRaisesRegex(ConversionError, "truncated|not a TFLite"):
                read_model(data[:cut])
        r, written = self.convert_cli(data[:len(data) // 2])
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("truncated", r.stderr)
        self.assertFalse(written)

    def test_activation_dequantize_refused(self):
        g = Graph()
        x = g.tensor("input", [1, 2, 2, 1], np.float16)
        y = g.tensor("output", [1, 2, 2, 1])
        g.op("DEQUANTIZE", [x], [y])
        g.inputs, g.outputs = [x], [y]
        with self.assertRaisesRegex(ConversionError, "DEQUANTIZE"):
            convert(read_model(g.build()))


if __name__ == "__main__":
    unittest.main()
