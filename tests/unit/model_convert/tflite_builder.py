"""Writes small .tflite flatbuffers for the converter's tests (the writer twin of tflite_schema.py).

A graph is tensors (name, shape, type code, constant data or None) and operators (op code, inputs,
outputs, options); slots as in TensorFlow Lite's schema.fbs.
"""
import flatbuffers
import numpy as np

OP_CODES = {"ADD": 0, "CONCATENATION": 2, "CONV_2D": 3, "DEPTHWISE_CONV_2D": 4, "DEPTH_TO_SPACE": 5,
            "DEQUANTIZE": 6, "LOGISTIC": 14, "MAX_POOL_2D": 17, "RESHAPE": 22, "RESIZE_BILINEAR": 23,
            "TANH": 28, "PAD": 34, "DENSIFY": 124}
TYPE_CODES = {np.dtype(np.float32): 0, np.dtype(np.float16): 1, np.dtype(np.int32): 2}
PADDING = {"SAME": 0, "VALID": 1}
ACTIVATION = {"NONE": 0, "RELU": 1, "RELU6": 3}
# builtin_options union type per op (1-based index in schema.fbs's BuiltinOptions union; the reader
# goes by the op, so these only keep the files well-formed).
OPTION_TYPES = {"CONV_2D": 1, "DEPTHWISE_CONV_2D": 2, "MAX_POOL_2D": 5, "CONCATENATION": 10, "ADD": 11,
                "RESIZE_BILINEAR": 15, "RESHAPE": 17, "DEPTH_TO_SPACE": 94}


class Graph:
    def __init__(self):
        self.tensors, self.ops, self.inputs, self.outputs = [], [], [], []

    def tensor(self, name, shape, dtype=np.float32, data=None, sparsity=None, type_code=None):
        self.tensors.append(dict(name=name, shape=list(shape), dtype=np.dtype(dtype), data=data,
                                 sparsity=sparsity, type_code=type_code))
        return len(self.tensors) - 1

    def const(self, name, array, stored=np.float16):
        """A float constant stored as float16 behind a DEQUANTIZE (as MediaPipe stores weights)."""
        array = np.asarray(array)
        if array.dtype == np.int32 or stored is None:
            return self.tensor(name, array.shape, array.dtype, array)
        raw = self.tensor(name + "_f16", array.shape, stored, array.astype(stored))
        out = self.tensor(name, array.shape)
        self.op("DEQUANTIZE", [raw], [out])
        return out

    def op(self, name, inputs, outputs, **options):
        self.ops.append((name, list(inputs), list(outputs), options))

    def build(self):
        return _write(self)


def _ints(b, values, dtype=np.int32):
    return b.CreateNumpyVector(np.asarray(values, dtype))


def _table_vector(b, offsets):
    b.StartVector(4, len(offsets), 4)
    for o in reversed(offsets):
        b.PrependUOffsetTRelative(o)
    return b.EndVector()


def _options(b, name, o):
    act = ACTIVATION[o.get("activation", "NONE")]
    if name in ("CONV_2D", "DEPTHWISE_CONV_2D"):
        dw = name == "DEPTHWISE_CONV_2D"
        b.StartObject(7)
        b.PrependInt8Slot(0, PADDING[o["padding"]], 0)
        b.PrependInt32Slot(1, o.get("stride", 1), 0)
        b.PrependInt32Slot(2, o.get("stride", 1), 0)
        if dw:
            b.PrependInt32Slot(3, o.get("depth_multiplier", 1), 0)
        b.PrependInt8Slot(4 if dw else 3, act, 0)
        b.PrependInt32Slot(5 if dw else 4, o.get("dilation", 1), 1)
        b.PrependInt32Slot(6 if dw else 5, o.get("dilation", 1), 1)
        return b.EndObject()
    if name == "MAX_POOL_2D":
        b.StartObject(6)
        b.PrependInt8Slot(0, PADDING[o["padding"]], 0)
        b.PrependInt32Slot(1, o["stride"], 0)
        b.PrependInt32Slot(2, o["stride"], 0)
        b.PrependInt32Slot(3, o["filter"], 0)
        b.PrependInt32Slot(4, o["filter"], 0)
        return b.EndObject()
    if name == "ADD":
        b.StartObject(1)
        b.PrependInt8Slot(0, act, 0)
        return b.EndObject()
    if name == "CONCATENATION":
        b.StartObject(2)
        b.PrependInt32Slot(0, o["axis"], 0)
        b.PrependInt8Slot(1, act, 0)
        return b.EndObject()
    if name == "RESIZE_BILINEAR":
        b.StartObject(4)
        b.PrependBoolSlot(2, o.get("align_corners", False), False)
        b.PrependBoolSlot(3, o.get("half_pixel_centers", False), False)
        return b.EndObject()
    if name == "RESHAPE":
        b.StartObject(1)
        return b.EndObject()
    if name == "DEPTH_TO_SPACE":
        b.StartObject(1)
        b.PrependInt32Slot(0, o["block_size"], 0)
        return b.EndObject()
    return None


def _sparsity(b, sp):
    """sp: (traversal_order, [("DENSE", size) | ("CSR", segments, indices)]) with int32 index vectors."""
    order, dims = sp
    metas = []
    for d in dims:
        if d[0] == "CSR":
            vecs = []
            for values in (d[1], d[2]):
                v = _ints(b, values)
                b.StartObject(1)
                b.PrependUOffsetTRelativeSlot(0, v, 0)
                vecs.append(b.EndObject())
        b.StartObject(6)
        if d[0] == "DENSE":
            b.PrependInt32Slot(1, d[1], 0)
        else:
            b.PrependInt8Slot(0, 1, 0)
            b.PrependUint8Slot(2, 1, 0)
            b.PrependUOffsetTRelativeSlot(3, vecs[0], 0)
            b.PrependUint8Slot(4, 1, 0)
            b.PrependUOffsetTRelativeSlot(5, vecs[1], 0)
        metas.append(b.EndObject())
    order_v, metas_v = _ints(b, order), _table_vector(b, metas)
    b.StartObject(3)
    b.PrependUOffsetTRelativeSlot(0, order_v, 0)
    b.PrependUOffsetTRelativeSlot(2, metas_v, 0)
    return b.EndObject()


def _write(g):
    b = flatbuffers.Builder(1024)
    buffers = []
    b.StartObject(1)
    buffers.append(b.EndObject())                         # buffer 0: the empty sentinel
    tensors = []
    for t in g.tensors:
        buf_index = 0
        if t["data"] is not None:
            data = b.CreateNumpyVector(np.frombuffer(np.ascontiguousarray(t["data"]).tobytes(), np.uint8))
            b.StartObject(1)
            b.PrependUOffsetTRelativeSlot(0, data, 0)
            buffers.append(b.EndObject())
            buf_index = len(buffers) - 1
        name, shape = b.CreateString(t["name"]), _ints(b, t["shape"])
        sp = _sparsity(b, t["sparsity"]) if t["sparsity"] else None
        b.StartObject(7)
        b.PrependUOffsetTRelativeSlot(0, shape, 0)
        type_code = t["type_code"] if t["type_code"] is not None else TYPE_CODES[t["dtype"]]
        b.PrependInt8Slot(1, type_code, 0)
        b.PrependUint32Slot(2, buf_index, 0)
        b.PrependUOffsetTRelativeSlot(3, name, 0)
        if sp:
            b.PrependUOffsetTRelativeSlot(6, sp, 0)
        tensors.append(b.EndObject())
    names = sorted({op[0] for op in g.ops}, key=lambda n: OP_CODES[n])
    codes = []
    for n in names:
        b.StartObject(4)
        b.PrependInt8Slot(0, min(OP_CODES[n], 127), 0)
        b.PrependInt32Slot(3, OP_CODES[n], 0)
        codes.append(b.EndObject())
    ops = []
    for name, ins, outs, options in g.ops:
        opt = _options(b, name, options)
        ins_v, outs_v = _ints(b, ins), _ints(b, outs)
        b.StartObject(5)
        b.PrependUint32Slot(0, names.index(name), 0)
        b.PrependUOffsetTRelativeSlot(1, ins_v, 0)
        b.PrependUOffsetTRelativeSlot(2, outs_v, 0)
        if opt is not None:
            b.PrependUint8Slot(3, OPTION_TYPES[name], 0)
            b.PrependUOffsetTRelativeSlot(4, opt, 0)
        ops.append(b.EndObject())
    tensors_v, ops_v = _table_vector(b, tensors), _table_vector(b, ops)
    in_v, out_v = _ints(b, g.inputs), _ints(b, g.outputs)
    b.StartObject(5)
    b.PrependUOffsetTRelativeSlot(0, tensors_v, 0)
    b.PrependUOffsetTRelativeSlot(1, in_v, 0)
    b.PrependUOffsetTRelativeSlot(2, out_v, 0)
    b.PrependUOffsetTRelativeSlot(3, ops_v, 0)
    subgraph = b.EndObject()
    codes_v, sub_v, bufs_v = _table_vector(b, codes), _table_vector(b, [subgraph]), _table_vector(b, buffers)
    b.StartObject(5)
    b.PrependUint32Slot(0, 3, 0)
    b.PrependUOffsetTRelativeSlot(1, codes_v, 0)
    b.PrependUOffsetTRelativeSlot(2, sub_v, 0)
    b.PrependUOffsetTRelativeSlot(4, bufs_v, 0)
    b.Finish(b.EndObject(), file_identifier=b"TFL3")
    return bytes(b.Output())
