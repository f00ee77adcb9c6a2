"""One function per TFLite op: emits the ONNX nodes that compute it, activations in NCHW.

Every 4-D activation lives in ONNX as NCHW (what cv::dnn::blobFromImage gives); weights are laid out
for it (conv OHWI -> OIHW, depthwise [1,kh,kw,C*M] -> [C*M,1,kh,kw] with group C). Everything else
(paddings, axes, resize sizes) is rewritten from TFLite's NHWC at conversion time, so the graph holds
no layout transposes except around a RESHAPE out of 4-D, whose row-major order is NHWC's.
"""
import numpy as np

from errors import ConversionError
from tflite_reference import same_padding

NHWC_TO_NCHW = (0, 3, 1, 2)
NCHW_TO_NHWC = (0, 2, 3, 1)
# RELU6 as Clip with min/max attributes: OpenCV 4.6's importer asserts on opset 11's input form.
RELU6_RANGE = (0.0, 6.0)


def fused_activation(g, x, activation):
    if activation in (None, "NONE"):
        return x
    if activation == "RELU":
        return g.node("Relu", [x])
    if activation == "RELU6":
        return g.node("Clip", [x], min=RELU6_RANGE[0], max=RELU6_RANGE[1])
    raise ConversionError(f"fused activation {activation} is not supported")


def _conv_pads(g, op, kh, kw):
    x = g.shape(op.inputs[0])
    o = op.options
    if o["padding"] == "VALID":
        return [0, 0, 0, 0]
    (t, b) = same_padding(x[1], kh, o["stride_h"], o["dilation_h"])
    (l, r) = same_padding(x[2], kw, o["stride_w"], o["dilation_w"])
    return [t, l, b, r]


def conv_2d(g, op):
    w = g.const(op.inputs[1], "CONV_2D weights")
    o = op.options
    ins = [g.value(op.inputs[0]), g.initializer(w.transpose(NHWC_TO_NCHW))]
    if len(op.inputs) > 2 and op.inputs[2] >= 0:
        ins.append(g.initializer(g.const(op.inputs[2], "CONV_2D bias")))
    y = g.node("Conv", ins, kernel_shape=[w.shape[1], w.shape[2]], strides=[o["stride_h"], o["stride_w"]],
               dilations=[o["dilation_h"], o["dilation_w"]], pads=_conv_pads(g, op, w.shape[1], w.shape[2]))
    return fused_activation(g, y, o["activation"])


def depthwise_conv_2d(g, op):
    w = g.const(op.inputs[1], "DEPTHWISE_CONV_2D weights")
    o = op.options
    channels = g.shape(op.inputs[0])[3]
    if w.shape[0] != 1 or w.shape[3] % channels:
        raise ConversionError(f"DEPTHWISE_CONV_2D weights {list(w.shape)} for {channels} input channels")
    ins = [g.value(op.inputs[0]), g.initializer(w.transpose(3, 0, 1, 2))]
    if len(op.inputs) > 2 and op.inputs[2] >= 0:
        ins.append(g.initializer(g.const(op.inputs[2], "DEPTHWISE_CONV_2D bias")))
    y = g.node("Conv", ins, kernel_shape=[w.shape[1], w.shape[2]], strides=[o["stride_h"], o["stride_w"]],
               dilations=[o["dilation_h"], o["dilation_w"]], group=channels,
               pads=_conv_pads(g, op, w.shape[1], w.shape[2]))
    return fused_activation(g, y, o["activation"])


def max_pool_2d(g, op):
    o = op.options
    kh, kw = o["filter_h"], o["filter_w"]
    x = g.shape(op.inputs[0])
    pads = [0, 0, 0, 0]
    if o["padding"] == "SAME":
        (t, b), (l, r) = same_padding(x[1], kh, o["stride_h"]), same_padding(x[2], kw, o["stride_w"])
        pads = [t, l, b, r]
    y = g.node("MaxPool", [g.value(op.inputs[0])], kernel_shape=[kh, kw], strides=[o["stride_h"], o["stride_w"]],
               pads=pads)
    return fused_activation(g, y, o["activation"])


def add(g, op):
    ins = [g.value_or_const(i) for i in op.inputs]
    return fused_activation(g, g.node("Add", ins), op.options["activation"])


def logistic(g, op):
    return g.node("Sigmoid", [g.value(op.inputs[0])])


def pad(g, op):
    p = np.asarray(g.const(op.inputs[1], "PAD paddings"), np.int64)
    rank = len(g.shape(op.inputs[0]))
    if p.shape != (rank, 2):
        raise ConversionError(f"PAD paddings of shape {list(p.shape)} for a rank-{rank} input")
    if rank == 4:
        p = p[list(NHWC_TO_NCHW)]
    pads = np.concatenate([p[:, 0], p[:, 1]]).astype(np.int64)
    return g.node("Pad", [g.value(op.inputs[0]), g.initializer(pads)], mode="constant")


def reshape(g, op):
    x = g.value(op.inputs[0])
    if len(g.shape(op.inputs[0])) == 4:
        x = g.node("Transpose", [x], perm=list(NCHW_TO_NHWC))
    out_shape = g.shape(op.outputs[0])
    y = g.node("Reshape", [x, g.initializer(np.asarray(out_shape, np.int64))])
    if len(out_shape) == 4:
        y = g.node("Transpose", [y], perm=list(NHWC_TO_NCHW))
    return y


def resize_bilinear(g, op):
    o = op.options
    if o["align_corners"]:
        mode = "align_corners"
    elif o["half_pixel_centers"]:
        mode = "half_pixel"
    else:
        mode = "asymmetric"
    n, h, w, c = g.shape(op.inputs[0])
    oh, ow = [int(s) for s in g.const(op.inputs[1], "RESIZE_BILINEAR size")]
    scales = np.asarray([1.0, 1.0, oh / h, ow / w], np.float32)
    return g.node("Resize", [g.value(op.inputs[0]), g.initializer(np.zeros(0, np.float32)), g.initializer(scales)],
                  mode="linear", coordinate_transformation_mode=mode)


def concatenation(g, op):
    rank = len(g.shape(op.outputs[0]))
    axis = op.options["axis"] % rank
    if rank == 4:
        axis = NHWC_TO_NCHW.index(axis)
    for i in op.inputs:
        if i in g.consts:   # cv::dnn 4.6 fills such a Concat with garbage (tests/unit/model_convert)
            raise ConversionError(f"CONCATENATION of the constant '{g.model.tensors[i].name}': not supported")
    y = g.node("Concat", [g.value(i) for i in op.inputs], axis=axis)
    return fused_activation(g, y, op.options["activation"])


def depth_to_space(g, op):
    return g.node("DepthToSpace", [g.value(op.inputs[0])], blocksize=op.options["block_size"], mode="DCR")


CONVERTERS = {"CONV_2D": conv_2d, "DEPTHWISE_CONV_2D": depthwise_conv_2d, "MAX_POOL_2D": max_pool_2d,
              "ADD": add, "LOGISTIC": logistic, "PAD": pad, "RESHAPE": reshape,
              "RESIZE_BILINEAR": resize_bilinear, "CONCATENATION": concatenation,
              "DEPTH_TO_SPACE": depth_to_space}
