"""Densifies a TFLite sparse tensor (TACO-style SparsityParameters: DENSE and SPARSE_CSR dimensions).

Walks the dimensions in traversal order: a DENSE dimension enumerates every index, a CSR dimension the
indices listed for the current position of the dimensions before it (segments[p]..segments[p+1]).
Values are stored in that walk's order. Block sparsity (block_map) is refused: these models have none.
"""
import numpy as np

from errors import ConversionError


def densify(shape, values, sparsity, name=""):
    """The dense array of `shape` holding `values` where `sparsity` says, zeros elsewhere."""
    order = sparsity.traversal_order
    if sparsity.block_map:
        raise ConversionError(f"tensor '{name}': block-sparse weights (block_map {sparsity.block_map}) are not supported")
    if sorted(order) != list(range(len(shape))) or len(sparsity.dims) != len(shape):
        raise ConversionError(f"tensor '{name}': traversal order {order} does not match shape {list(shape)}")
    # positions: for each entry so far, (index tuple in traversal order, position in the flattened walk)
    coords = np.zeros((1, 0), np.int64)
    positions = np.zeros(1, np.int64)
    for level, dim in enumerate(sparsity.dims):
        size = shape[order[level]]
        if dim[0] == "DENSE":
            if dim[1] != size:
                raise ConversionError(f"tensor '{name}': dense dimension {level} has size {dim[1]}, shape says {size}")
            idx = np.tile(np.arange(size), len(positions))
            parent = np.repeat(np.arange(len(positions)), size)
            positions = positions[parent] * size + idx
        else:
            segments, indices = dim[1], dim[2]
            if len(segments) != len(positions) + 1 or segments[-1] != len(indices) or np.any(np.diff(segments) < 0):
                raise ConversionError(f"tensor '{name}': CSR dimension {level} has {len(segments)} segments "
                                      f"ending at {segments[-1] if len(segments) else None} for {len(positions)} rows "
                                      f"and {len(indices)} indices")
            if len(indices) and (indices.min() < 0 or indices.max() >= size):
                raise ConversionError(f"tensor '{name}': CSR dimension {level} has an index outside 0..{size - 1}")
            counts = np.diff(segments)
            parent = np.repeat(np.arange(len(positions)), counts)
            idx = indices
            positions = np.arange(len(indices))
        coords = np.concatenate([coords[parent], idx[:, None]], axis=1)
    if len(values) != len(coords):
        raise ConversionError(f"tensor '{name}': {len(values)} stored values for {len(coords)} sparse positions")
    dense = np.zeros(shape, dtype=values.dtype)
    dims = np.empty_like(coords)
    dims[:, order] = coords
    dense[tuple(dims.T)] = values
    return dense
