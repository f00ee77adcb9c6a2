"""Reads a .tflite flatbuffer into plain Python objects (Model, Tensor, Operator).

Only the fields the converter uses, by their slot in TensorFlow Lite's schema.fbs (a table's fields
are numbered in declaration order; a union takes two slots, its type then its value). Sparse weights
are read as they are stored (sparsity.py densifies them). Any read outside the file is a
ConversionError: a truncated or corrupt file is refused, never half-read.
"""
import struct
from dataclasses import dataclass, field
from typing import Dict, List, Optional

import flatbuffers
import numpy as np

from errors import ConversionError

FILE_IDENTIFIER = b"TFL3"

# TensorType enum -> numpy dtype (only the types these graphs can carry; others are refused by name).
TENSOR_TYPES = {0: ("FLOAT32", np.float32), 1: ("FLOAT16", np.float16), 2: ("INT32", np.int32),
                3: ("UINT8", np.uint8), 4: ("INT64", np.int64), 9: ("INT8", np.int8)}
TENSOR_TYPE_NAMES = {5: "STRING", 6: "BOOL", 7: "INT16", 8: "COMPLEX64", 10: "FLOAT64",
                     11: "COMPLEX128", 12: "UINT64", 13: "RESOURCE", 14: "VARIANT", 15: "UINT32",
                     16: "UINT16", 17: "INT4"}

# BuiltinOperator codes this converter knows by name; any other code is refused with its number.
BUILTIN_OPS = {0: "ADD", 1: "AVERAGE_POOL_2D", 2: "CONCATENATION", 3: "CONV_2D",
               4: "DEPTHWISE_CONV_2D", 5: "DEPTH_TO_SPACE", 6: "DEQUANTIZE", 9: "FULLY_CONNECTED",
               14: "LOGISTIC", 17: "MAX_POOL_2D", 18: "MUL", 19: "RELU", 21: "RELU6", 22: "RESHAPE",
               23: "RESIZE_BILINEAR", 28: "TANH", 32: "CUSTOM", 34: "PAD", 54: "PRELU",
               124: "DENSIFY"}
# Codes at or above this are stored only in OperatorCode.builtin_code (schema 3a).
PLACEHOLDER_FOR_GREATER_OP_CODES = 127

ACTIVATIONS = {0: "NONE", 1: "RELU", 2: "RELU_N1_TO_1", 3: "RELU6", 4: "TANH", 5: "SIGN_BIT"}
PADDINGS = {0: "SAME", 1: "VALID"}


@dataclass
class Sparsity:
    """SparsityParameters: per traversed dimension either ("DENSE", size) or ("CSR", segments, indices)."""
    traversal_order: List[int]
    block_map: List[int]
    dims: List[tuple]


@dataclass
class Tensor:
    index: int
    name: str
    shape: List[int]
    type_name: str
    dtype: object
    data: Optional[np.ndarray] = None      # constant contents (flat when sparse), None for activations
    sparsity: Optional[Sparsity] = None


@dataclass
class Operator:
    op: str                                 # BuiltinOperator name, e.g. "CONV_2D"
    inputs: List[int]                       # tensor indices, -1 for an omitted optional input
    outputs: List[int]
    options: Dict[str, object] = field(default_factory=dict)
    custom_code: str = ""


@dataclass
class Model:
    tensors: List[Tensor]
    operators: List[Operator]
    inputs: List[int]
    outputs: List[int]


class _Table:
    """A flatbuffers.Table with typed, slot-numbered accessors and the schema's defaults."""

    def __init__(self, buf, pos):
        self.t = flatbuffers.table.Table(buf, pos)

    def _off(self, slot):
        return self.t.Offset(4 + 2 * slot)

    def scalar(self, slot, flags, default=0):
        o = self._off(slot)
        return self.t.Get(flags, self.t.Pos + o) if o else default

    def int(self, slot, default=0):
        return self.scalar(slot, flatbuffers.number_types.Int32Flags, default)

    def uint(self, slot, default=0):
        return self.scalar(slot, flatbuffers.number_types.Uint32Flags, default)

    def byte(self, slot, default=0):
        return self.scalar(slot, flatbuffers.number_types.Int8Flags, default)

    def ubyte(self, slot, default=0):
        return self.scalar(slot, flatbuffers.number_types.Uint8Flags, default)

    def bool(self, slot, default=False):
        return bool(self.scalar(slot, flatbuffers.number_types.BoolFlags, default))

    def float(self, slot, default=0.0):
        return self.scalar(slot, flatbuffers.number_types.Float32Flags, default)

    def string(self, slot):
        o = self._off(slot)
        return self.t.String(self.t.Pos + o).decode("utf-8", "replace") if o else ""

    def vector(self, slot, dtype):
        """A vector of scalars as a numpy copy (empty when absent)."""
        o = self._off(slot)
        if not o:
            return np.zeros(0, dtype)
        start, n = self.t.Vector(o), self.t.VectorLen(o)
        nbytes = n * np.dtype(dtype).itemsize
        if start + nbytes > len(self.t.Bytes):
            raise ConversionError("vector runs past the end of the file")
        return np.frombuffer(bytes(self.t.Bytes[start:start + nbytes]), dtype=np.dtype(dtype).newbyteorder("<"))

    def table(self, slot):
        o = self._off(slot)
        return _Table(self.t.Bytes, self.t.Indirect(self.t.Pos + o)) if o else None

    def tables(self, slot):
        o = self._off(slot)
        if not o:
            return []
        start, n = self.t.Vector(o), self.t.VectorLen(o)
        return [_Table(self.t.Bytes, self.t.Indirect(start + 4 * i)) for i in range(n)]


def _options(op, t):
    """The builtin options of a converted op as a dict (slots per its *Options table); {} for others."""
    if op == "CONV_2D":
        return None if t is None else dict(padding=PADDINGS.get(t.byte(0)), stride_w=t.int(1), stride_h=t.int(2),
                                           activation=ACTIVATIONS.get(t.byte(3)), dilation_w=t.int(4, 1),
                                           dilation_h=t.int(5, 1))
    if op == "DEPTHWISE_CONV_2D":
        return None if t is None else dict(padding=PADDINGS.get(t.byte(0)), stride_w=t.int(1), stride_h=t.int(2),
                                           depth_multiplier=t.int(3), activation=ACTIVATIONS.get(t.byte(4)),
                                           dilation_w=t.int(5, 1), dilation_h=t.int(6, 1))
    if op == "MAX_POOL_2D":
        return None if t is None else dict(padding=PADDINGS.get(t.byte(0)), stride_w=t.int(1), stride_h=t.int(2),
                                           filter_w=t.int(3), filter_h=t.int(4),
                                           activation=ACTIVATIONS.get(t.byte(5)))
    if op == "ADD":
        return dict(activation=ACTIVATIONS.get(t.byte(0)) if t else "NONE")
    if op == "CONCATENATION":
        return None if t is None else dict(axis=t.int(0), activation=ACTIVATIONS.get(t.byte(1)))
    if op == "RESHAPE":
        return dict(new_shape=[int(v) for v in t.vector(0, np.int32)] if t else None)
    if op == "RESIZE_BILINEAR":
        return dict(align_corners=t.bool(2) if t else False, half_pixel_centers=t.bool(3) if t else False)
    if op == "DEPTH_TO_SPACE":
        return None if t is None else dict(block_size=t.int(0))
    return {}


def _sparsity(t):
    if t is None:
        return None
    dims = []
    for d in t.tables(2):
        fmt = d.byte(0)
        if fmt == 0:
            dims.append(("DENSE", d.int(1)))
        elif fmt == 1:
            vectors = []
            for type_slot, value_slot in ((2, 3), (4, 5)):
                kind = d.ubyte(type_slot)
                dtype = {1: np.int32, 2: np.uint16, 3: np.uint8}.get(kind)
                value = d.table(value_slot)
                if dtype is None or value is None:
                    raise ConversionError(f"sparse dimension index vector of unknown type {kind}")
                vectors.append(value.vector(0, dtype).astype(np.int64))
            dims.append(("CSR", vectors[0], vectors[1]))
        else:
            raise ConversionError(f"sparse dimension format {fmt} unknown (DENSE=0, SPARSE_CSR=1 are known)")
    return Sparsity([int(v) for v in t.vector(0, np.int32)], [int(v) for v in t.vector(1, np.int32)], dims)


def read_model(data: bytes) -> Model:
    """The first subgraph of a .tflite file; ConversionError if it is not one or is cut short."""
    if len(data) < 8 or data[4:8] != FILE_IDENTIFIER:
        raise ConversionError(f"not a TFLite flatbuffer (file identifier {data[4:8]!r}, expected {FILE_IDENTIFIER!r}; "
                              f"{len(data)} bytes)")
    try:
        return _read_model(bytearray(data))
    except (struct.error, IndexError, ValueError, UnicodeDecodeError) as e:
        raise ConversionError(f"truncated or corrupt TFLite file ({len(data)} bytes): {e}") from None


def _read_model(buf) -> Model:
    root = _Table(buf, flatbuffers.encode.Get(flatbuffers.packer.uoffset, buf, 0))
    # Every buffer read now, used or not: a file cut short anywhere in its buffers is refused.
    buffers = [b.vector(0, np.uint8) for b in root.tables(4)]
    codes = []
    for c in root.tables(1):
        code = max(c.byte(0), c.int(3))
        codes.append((code, c.string(1)))
    subgraphs = root.tables(2)
    if not subgraphs:
        raise ConversionError("the model has no subgraph")
    g = subgraphs[0]

    tensors = []
    for i, t in enumerate(g.tables(0)):
        type_code = t.byte(1)
        if type_code not in TENSOR_TYPES:
            raise ConversionError(f"tensor {i} '{t.string(3)}' has tensor type "
                                  f"{TENSOR_TYPE_NAMES.get(type_code, type_code)}, which the converter does not know")
        type_name, dtype = TENSOR_TYPES[type_code]
        tensor = Tensor(i, t.string(3), [int(v) for v in t.vector(0, np.int32)], type_name, dtype)
        tensor.sparsity = _sparsity(t.table(6))
        b = t.uint(2)
        if b >= len(buffers):
            raise ConversionError(f"tensor {i} '{tensor.name}' refers to buffer {b} of {len(buffers)}")
        raw = buffers[b] if b else np.zeros(0, np.uint8)
        if raw.size:
            n = raw.size // np.dtype(dtype).itemsize
            expected = int(np.prod(tensor.shape)) if tensor.sparsity is None else n
            if raw.size != expected * np.dtype(dtype).itemsize:
                raise ConversionError(f"tensor {i} '{tensor.name}': buffer holds {raw.size} bytes, shape "
                                      f"{tensor.shape} of {type_name} needs {expected * np.dtype(dtype).itemsize}")
            flat = raw.view(np.dtype(dtype).newbyteorder("<")).astype(dtype)
            tensor.data = flat if tensor.sparsity else flat.reshape(tensor.shape)
        tensors.append(tensor)

    operators = []
    for k, o in enumerate(g.tables(3)):
        idx = o.uint(0)
        if idx >= len(codes):
            raise ConversionError(f"operator {k} refers to operator code {idx} of {len(codes)}")
        code, custom = codes[idx]
        if code not in BUILTIN_OPS:
            raise ConversionError(f"operator {k}: builtin op code {code} is not one the converter knows")
        name = BUILTIN_OPS[code]
        inputs = [int(v) for v in o.vector(1, np.int32)]
        outputs = [int(v) for v in o.vector(2, np.int32)]
        for v in inputs + outputs:
            if v >= len(tensors) or v < -1:
                raise ConversionError(f"operator {k} ({name}) refers to tensor {v} of {len(tensors)}")
        options = _options(name, o.table(4))
        if options is None:
            raise ConversionError(f"operator {k} ({name}) has no options table")
        operators.append(Operator(name, inputs, outputs, options, custom))
    return Model(tensors, operators, [int(v) for v in g.vector(1, np.int32)], [int(v) for v in g.vector(2, np.int32)])
