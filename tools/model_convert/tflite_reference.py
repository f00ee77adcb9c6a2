"""Runs a TFLite graph in numpy, NHWC, with TensorFlow Lite's float semantics for every op converted.

The judge of the converter: written from TFLite's op definitions (SAME padding split with the extra
pixel after, half-pixel bilinear resize clamped at the borders as TFLite's kernel does, DEPTH_TO_SPACE's
channel order), independent of ONNX and OpenCV. Float64 inside, so its own rounding is far below the
tolerances the tests state. Slow but plain: a whole landmark model takes seconds.
"""
import numpy as np

from errors import ConversionError
from graph_prep import fold_constants, keep_outputs


def same_padding(size, kernel, stride, dilation=1):
    """TFLite's SAME: output ceil(size/stride), total padding split with the odd pixel at the end."""
    out = -(-size // stride)
    total = max((out - 1) * stride + (kernel - 1) * dilation + 1 - size, 0)
    return total // 2, total - total // 2


def _pads(x_shape, kh, kw, opts):
    if opts["padding"] == "VALID":
        return (0, 0), (0, 0)
    return (same_padding(x_shape[1], kh, opts["stride_h"], opts.get("dilation_h", 1)),
            same_padding(x_shape[2], kw, opts["stride_w"], opts.get("dilation_w", 1)))


def _windows(x, kh, kw, opts, fill):
    """x padded as the op pads it, and each output pixel's kh x kw window: [N, OH, OW, kh, kw, C]."""
    (pt, pb), (pl, pr) = _pads(x.shape, kh, kw, opts)
    x = np.pad(x, ((0, 0), (pt, pb), (pl, pr), (0, 0)), constant_values=fill)
    sh, sw = opts["stride_h"], opts["stride_w"]
    dh, dw = opts.get("dilation_h", 1), opts.get("dilation_w", 1)
    oh = (x.shape[1] - (kh - 1) * dh - 1) // sh + 1
    ow = (x.shape[2] - (kw - 1) * dw - 1) // sw + 1
    rows = []
    for i in range(kh):
        cols = []
        for j in range(kw):
            cols.append(x[:, i * dh:i * dh + (oh - 1) * sh + 1:sh, j * dw:j * dw + (ow - 1) * sw + 1:sw, :])
        rows.append(np.stack(cols, axis=3))
    return np.stack(rows, axis=3)


def activation(x, name):
    if name in (None, "NONE"):
        return x
    if name == "RELU":
        return np.maximum(x, 0)
    if name == "RELU6":
        return np.clip(x, 0, 6)
    raise ConversionError(f"fused activation {name} is not supported")


def conv_2d(x, w, b, opts):
    """w: [O, kh, kw, I] (OHWI)."""
    win = _windows(x, w.shape[1], w.shape[2], opts, 0.0)
    y = np.tensordot(win, w, axes=([3, 4, 5], [1, 2, 3]))
    return activation(y + (0 if b is None else b), opts["activation"])


def depthwise_conv_2d(x, w, b, opts):
    """w: [1, kh, kw, C*M]; output channel c*M + m reads input channel c."""
    m = opts["depth_multiplier"] or w.shape[3] // x.shape[3]
    win = _windows(np.repeat(x, m, axis=3), w.shape[1], w.shape[2], opts, 0.0)
    y = np.einsum("nhwijc,ijc->nhwc", win, w[0])
    return activation(y + (0 if b is None else b), opts["activation"])


def max_pool_2d(x, opts):
    win = _windows(x, opts["filter_h"], opts["filter_w"], opts, -np.inf)
    return activation(win.max(axis=(3, 4)), opts["activation"])


def resize_bilinear(x, size, align_corners, half_pixel):
    """TFLite's kernel: source coordinate (d + 0.5) * in/out - 0.5, neighbours clamped to the image."""
    def axis(n_in, n_out):
        if align_corners and n_out > 1:
            scale = (n_in - 1) / (n_out - 1)
        else:
            scale = n_in / n_out
        d = np.arange(n_out, dtype=np.float64)
        src = (d + 0.5) * scale - 0.5 if half_pixel else d * scale
        lo = np.maximum(np.floor(src), 0).astype(int)
        hi = np.minimum(np.ceil(src), n_in - 1).astype(int)
        return lo, hi, src - lo
    y0, y1, fy = axis(x.shape[1], size[0])
    x0, x1, fx = axis(x.shape[2], size[1])
    fy, fx = fy[None, :, None, None], fx[None, None, :, None]
    top = x[:, y0][:, :, x0] * (1 - fx) + x[:, y0][:, :, x1] * fx
    bottom = x[:, y1][:, :, x0] * (1 - fx) + x[:, y1][:, :, x1] * fx
    return top * (1 - fy) + bottom * fy


def depth_to_space(x, bs):
    n, h, w, c = x.shape
    y = x.reshape(n, h, w, bs, bs, c // (bs * bs)).transpose(0, 1, 3, 2, 4, 5)
    return y.reshape(n, h * bs, w * bs, c // (bs * bs))


def run_op(op, args):
    """One operator on numpy inputs (None for omitted optional ones); its first output."""
    o = op.options
    if op.op == "CONV_2D":
        return conv_2d(args[0], args[1], args[2] if len(args) > 2 else None, o)
    if op.op == "DEPTHWISE_CONV_2D":
        return depthwise_conv_2d(args[0], args[1], args[2] if len(args) > 2 else None, o)
    if op.op == "MAX_POOL_2D":
        return max_pool_2d(args[0], o)
    if op.op == "ADD":
        return activation(args[0] + args[1], o["activation"])
    if op.op == "LOGISTIC":
        return 1.0 / (1.0 + np.exp(-args[0]))
    if op.op == "PAD":
        return np.pad(args[0], [tuple(p) for p in args[1]])
    if op.op == "RESHAPE":
        shape = o["new_shape"] if len(args) < 2 or args[1] is None else args[1]
        return args[0].reshape([int(s) for s in shape])
    if op.op == "RESIZE_BILINEAR":
        return resize_bilinear(args[0], [int(s) for s in args[1]], o["align_corners"], o["half_pixel_centers"])
    if op.op == "CONCATENATION":
        return activation(np.concatenate(args, axis=o["axis"]), o["activation"])
    if op.op == "DEPTH_TO_SPACE":
        return depth_to_space(args[0], o["block_size"])
    raise ConversionError(f"op {op.op} has no reference implementation")


def run(model, inputs, output_names=None):
    """{output name: array} for {input name: NHWC array}; output_names prunes like the converter."""
    if output_names:
        model = keep_outputs(model, output_names)
    consts, ops = fold_constants(model)
    values = {i: v.astype(np.float64) if v.dtype == np.float32 else v for i, v in consts.items() if v is not None}
    for i in model.inputs:
        t = model.tensors[i]
        if t.name not in inputs:
            raise ConversionError(f"input '{t.name}' not given")
        values[i] = np.asarray(inputs[t.name], np.float64).reshape(t.shape)
    for op in ops:
        args = [values[i] if i >= 0 else None for i in op.inputs]
        values[op.outputs[0]] = run_op(op, args)
    return {model.tensors[i].name: values[i].astype(np.float32) for i in model.outputs}
