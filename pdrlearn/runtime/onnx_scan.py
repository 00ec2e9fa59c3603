"""Whether an ONNX graph keeps tensor data outside its file (decision E263), read from the protobuf wire format with
the standard library only (the runtime never imports the ``onnx`` package).

``pdrlearn export`` writes every graph whole (``SerializeToString``), so a bundle graph that names external data
(a ``TensorProto`` with ``external_data`` entries or ``data_location`` EXTERNAL) did not come from it: its data would
be read from a file the bundle's checksums do not cover. :func:`external_tensor` walks the messages that can hold a
tensor (onnx.proto3 field numbers, cited per schema below) and skips every other field by its length.
"""

from __future__ import annotations

# onnx.proto3 field numbers: message -> {field: message it holds}
_SCHEMAS = {
    "model": {7: "graph", 20: "training", 25: "function"},  # ModelProto.graph, training_info, functions
    "training": {1: "graph", 2: "graph"},  # TrainingInfoProto.initialization, algorithm
    "function": {7: "node"},  # FunctionProto.node
    "graph": {1: "node", 5: "tensor", 15: "sparse"},  # GraphProto.node, initializer, sparse_initializer
    "node": {5: "attribute"},  # NodeProto.attribute
    "attribute": {5: "tensor", 6: "graph", 10: "tensor", 11: "graph", 22: "sparse", 23: "sparse"},  # t g tensors ...
    "sparse": {1: "tensor", 2: "tensor"},  # SparseTensorProto.values, indices
    "tensor": {},
}
_TENSOR_NAME, _EXTERNAL_DATA, _DATA_LOCATION = 8, 13, 14  # TensorProto.name, external_data, data_location
_EXTERNAL = 1  # TensorProto.DataLocation.EXTERNAL
_MAX_DEPTH = 64  # subgraphs nest a few levels; deeper is not a graph pdrlearn writes


class NotOnnx(ValueError):
    """The bytes are not a protobuf message this walker can read (a truncated or foreign file)."""


def _varint(buf: memoryview, i: int) -> tuple[int, int]:
    value = shift = 0
    while True:
        if i >= len(buf) or shift > 63:
            raise NotOnnx("a truncated or overlong varint")
        b = buf[i]
        i += 1
        value |= (b & 0x7F) << shift
        if b < 0x80:
            return value, i
        shift += 7


def _fields(buf: memoryview):
    """``(field, wire type, value)`` of one message: an int (varint) or a memoryview (length-delimited)."""
    i = 0
    while i < len(buf):
        key, i = _varint(buf, i)
        field, wire = key >> 3, key & 7
        if wire == 0:
            value, i = _varint(buf, i)
        elif wire == 1:
            value, i = None, i + 8
        elif wire == 5:
            value, i = None, i + 4
        elif wire == 2:
            n, i = _varint(buf, i)
            value, i = buf[i:i + n], i + n
        else:
            raise NotOnnx(f"wire type {wire} (a protobuf group), which ONNX does not use")
        if i > len(buf):
            raise NotOnnx("a field runs past the end of its message")
        yield field, wire, value


def _walk(buf: memoryview, kind: str, depth: int) -> str | None:
    if depth > _MAX_DEPTH:
        raise NotOnnx(f"messages nested more than {_MAX_DEPTH} deep")
    schema = _SCHEMAS[kind]
    name, external = "", False
    for field, wire, value in _fields(buf):
        if kind == "tensor":
            if field == _TENSOR_NAME and wire == 2:
                name = bytes(value).decode("utf-8", "replace")
            elif (field == _EXTERNAL_DATA and wire == 2) or (field == _DATA_LOCATION and value == _EXTERNAL):
                external = True
        elif field in schema and wire == 2:
            found = _walk(value, schema[field], depth + 1)
            if found is not None:
                return found
    return (name or "(unnamed tensor)") if external else None


def external_tensor(data: bytes) -> str | None:
    """The name of the first tensor of the ONNX model ``data`` whose data is external, None when every tensor is in
    the file. Raises :class:`NotOnnx` for bytes that are not a readable protobuf message."""
    return _walk(memoryview(data), "model", 0)
