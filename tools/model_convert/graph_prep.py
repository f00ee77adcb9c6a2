"""Prepares a TFLite graph for conversion: keeps only what the wanted outputs need, folds constants.

MediaPipe's models store every weight as float16 behind a DEQUANTIZE op, some of them sparse behind a
DENSIFY op: both run on constants only, so they become float32 constants here and leave the graph.
"""
import numpy as np

from errors import ConversionError
from sparsity import densify
from tflite_schema import Model


def keep_outputs(model: Model, names):
    """The model reduced to the outputs named (in that order) and the operators they depend on."""
    by_name = {model.tensors[i].name: i for i in model.outputs}
    missing = [n for n in names if n not in by_name]
    if missing:
        raise ConversionError(f"output(s) {missing} not in the model (outputs: {sorted(by_name)})")
    outputs = [by_name[n] for n in names]
    needed, ops = set(outputs), []
    for op in reversed(model.operators):
        if any(o in needed for o in op.outputs):
            ops.append(op)
            needed.update(i for i in op.inputs if i >= 0)
    return Model(model.tensors, list(reversed(ops)), model.inputs, outputs)


def fold_constants(model: Model):
    """Every constant as float32 (INT32 shape operands kept): {tensor index: array}, and the ops left."""
    consts = {}
    for t in model.tensors:
        if t.data is None:
            continue
        if t.sparsity is not None:
            consts[t.index] = None            # stored sparse: only a DENSIFY may read it
        elif t.type_name in ("FLOAT32", "FLOAT16"):
            consts[t.index] = t.data.astype(np.float32)
        else:
            consts[t.index] = t.data
    ops = []
    for op in model.operators:
        if op.op in ("DEQUANTIZE", "DENSIFY"):
            src = model.tensors[op.inputs[0]]
            if src.index not in consts:
                raise ConversionError(f"{op.op} of the activation '{src.name}': only constant inputs are supported")
            if op.op == "DENSIFY":
                if src.sparsity is None:
                    raise ConversionError(f"DENSIFY of '{src.name}', which is not stored sparse")
                value = densify(src.shape, src.data, src.sparsity, src.name)
            else:
                if src.type_name != "FLOAT16":
                    raise ConversionError(f"DEQUANTIZE of '{src.name}' ({src.type_name}): only FLOAT16 is supported")
                value = consts[src.index] if consts[src.index] is not None else None
                if value is None:
                    raise ConversionError(f"DEQUANTIZE of the sparse '{src.name}' before a DENSIFY")
            consts[op.outputs[0]] = value.astype(np.float32)
        else:
            ops.append(op)
    for op in ops:
        for i in op.inputs:
            if i >= 0 and i in consts and consts[i] is None:
                raise ConversionError(f"{op.op} reads the sparse tensor '{model.tensors[i].name}' without a DENSIFY")
    return consts, ops
