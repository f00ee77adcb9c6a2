#!/usr/bin/python3
"""Converts a TFLite float model (MediaPipe's BlazePose detector and landmark models) to ONNX for
OpenCV 4.6's cv::dnn. See README.md for the ops it converts and what it refuses.

Usage: tflite2onnx.py MODEL.tflite OUT.onnx [--outputs NAME,NAME...] [--json]
"""
import argparse
import json
import os
import sys
import time

import onnx

from errors import ConversionError
from graph_prep import fold_constants, keep_outputs
from onnx_builder import GraphBuilder, value_info
from onnx_ops import CONVERTERS, NCHW_TO_NHWC, NHWC_TO_NCHW
from tflite_schema import read_model


def _nchw(shape):
    return [shape[i] for i in NHWC_TO_NCHW] if len(shape) == 4 else list(shape)


def convert(model, output_names=None, doc=""):
    """The onnx.ModelProto computing `model`'s outputs (those named, in that order, when given)."""
    if output_names:
        model = keep_outputs(model, output_names)
    unknown = sorted({op.op for op in model.operators} - set(CONVERTERS) - {"DEQUANTIZE", "DENSIFY"})
    if unknown:
        raise ConversionError(f"op(s) not supported by the converter: {', '.join(unknown)}")
    consts, ops = fold_constants(model)
    g = GraphBuilder(model, consts)
    inputs = []
    for i in model.inputs:
        t = model.tensors[i]
        if t.type_name != "FLOAT32":
            raise ConversionError(f"input '{t.name}' is {t.type_name}; only FLOAT32 inputs are supported")
        g.set_output(i, t.name)
        inputs.append(value_info(t.name, _nchw(t.shape)))
    for op in ops:
        for o in op.outputs:
            t = model.tensors[o]
            if t.type_name != "FLOAT32":
                raise ConversionError(f"{op.op} output '{t.name}' is {t.type_name}; only FLOAT32 activations "
                                      f"are supported")
        g.set_output(op.outputs[0], CONVERTERS[op.op](g, op))
    outputs = []
    for i in model.outputs:
        t = model.tensors[i]
        if len(t.shape) == 4:          # graph outputs keep TFLite's NHWC layout and shape
            g.node("Transpose", [g.value(i)], name=t.name, perm=list(NCHW_TO_NHWC))
        else:
            g.rename(g.value(i), t.name)
        outputs.append(value_info(t.name, list(t.shape)))
    return g.to_model(inputs, outputs, doc)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("tflite")
    p.add_argument("onnx")
    p.add_argument("--outputs", help="comma-separated output names to keep (default: all)")
    p.add_argument("--doc", default="", help="doc_string stored in the ONNX model (provenance)")
    p.add_argument("--json", action="store_true", help="print one JSON object (time, sizes) on stdout")
    a = p.parse_args(argv)
    t0 = time.perf_counter()
    try:
        with open(a.tflite, "rb") as f:
            model = read_model(f.read())
        proto = convert(model, a.outputs.split(",") if a.outputs else None, a.doc)
    except (ConversionError, OSError) as e:
        print(f"tflite2onnx: {a.tflite}: {e}", file=sys.stderr)
        return 1
    tmp = a.onnx + ".tmp"
    onnx.save(proto, tmp)
    os.replace(tmp, a.onnx)
    seconds = time.perf_counter() - t0
    summary = {"tflite": a.tflite, "onnx": a.onnx, "seconds": round(seconds, 3),
               "tflite_bytes": os.path.getsize(a.tflite), "onnx_bytes": os.path.getsize(a.onnx),
               "nodes": len(proto.graph.node), "outputs": [o.name for o in proto.graph.output]}
    if a.json:
        print(json.dumps(summary))
    else:
        print(f"tflite2onnx: {a.onnx}: {summary['nodes']} nodes, {summary['onnx_bytes']} bytes, {seconds:.2f} s",
              file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
