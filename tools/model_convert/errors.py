"""The one error the converter raises: a model it refuses, with the reason (op, tensor or file named)."""


class ConversionError(Exception):
    pass
