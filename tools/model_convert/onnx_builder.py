"""The ONNX graph under construction: TFLite tensors mapped to ONNX values, nodes, initializers."""
import numpy as np
import onnx
from onnx import helper, numpy_helper

from errors import ConversionError

# Opset 11: Resize with coordinate_transformation_mode (half_pixel) and Pad with its pads as an input.
# Clip stays in the attribute form OpenCV 4.6 reads (see onnx_ops.RELU6_RANGE).
ONNX_OPSET = 11


class GraphBuilder:
    def __init__(self, model, consts):
        self.model, self.consts = model, consts
        self.nodes, self.initializers, self.values = [], [], {}
        self._count = 0

    def _fresh(self, prefix):
        self._count += 1
        return f"{prefix}_{self._count}"

    def shape(self, index):
        return list(self.model.tensors[index].shape)

    def const(self, index, what):
        if index < 0 or index not in self.consts:
            raise ConversionError(f"{what}: tensor '{self.model.tensors[index].name}' must be a constant")
        return self.consts[index]

    def value(self, index):
        if index not in self.values:
            t = self.model.tensors[index]
            raise ConversionError(f"tensor '{t.name}' is used before any op computes it (or is a constant "
                                  f"where an activation is expected)")
        return self.values[index]

    def value_or_const(self, index):
        """An activation's value, or a constant as an initializer laid out for NCHW broadcasting."""
        if index in self.values:
            return self.values[index]
        c = np.asarray(self.const(index, "operand"), np.float32)
        if 0 < c.ndim < 4:
            c = c.reshape((1,) * (4 - c.ndim) + c.shape)
        if c.ndim == 4:
            c = c.transpose(0, 3, 1, 2)
        return self.initializer(c)

    def initializer(self, array):
        name = self._fresh("const")
        self.initializers.append(numpy_helper.from_array(np.ascontiguousarray(array), name))
        return name

    def node(self, op_type, inputs, name=None, **attrs):
        out = name or self._fresh(op_type.lower())
        self.nodes.append(helper.make_node(op_type, inputs, [out], name=out, **attrs))
        return out

    def set_output(self, index, value_name):
        self.values[index] = value_name

    def rename(self, old, new):
        for n in self.nodes:
            for seq in (n.input, n.output):
                for k, v in enumerate(seq):
                    if v == old:
                        seq[k] = new
            if n.name == old:
                n.name = new

    def to_model(self, inputs, outputs, doc):
        graph = helper.make_graph(self.nodes, "converted", inputs, outputs, self.initializers)
        m = helper.make_model(graph, opset_imports=[helper.make_opsetid("", ONNX_OPSET)],
                              producer_name="gesture-pilot tflite2onnx", doc_string=doc)
        return m


def value_info(name, shape):
    return helper.make_tensor_value_info(name, onnx.TensorProto.FLOAT, shape)
