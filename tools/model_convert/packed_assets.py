#!/usr/bin/python3
"""Extracts one file from an emscripten file-packager bundle (MediaPipe's *_packed_assets.data).

The loader script beside the bundle holds the table: loadPackage({"files": [{"filename": ..., "start": S,
"end": E}, ...], "remote_package_size": N}). The offsets are read from it, never assumed.

Usage: packed_assets.py LOADER.js DATA FILENAME_SUFFIX OUT
"""
import json
import os
import re
import sys

from errors import ConversionError

TABLE = re.compile(r"loadPackage\((\{.*?\})\);")


def find_entry(loader_text, suffix):
    """(start, end, package size) of the one file whose name ends with `suffix`."""
    m = TABLE.search(loader_text)
    if not m:
        raise ConversionError("no loadPackage({...}) table in the loader script")
    try:
        table = json.loads(m.group(1))
    except json.JSONDecodeError as e:
        raise ConversionError(f"the loadPackage table is not JSON: {e}") from None
    hits = [f for f in table.get("files", []) if str(f.get("filename", "")).endswith(suffix)]
    if len(hits) != 1:
        names = [f.get("filename") for f in table.get("files", [])]
        raise ConversionError(f"{len(hits)} files named *{suffix} in the table (files: {names})")
    f = hits[0]
    start, end, size = f.get("start"), f.get("end"), table.get("remote_package_size")
    if not all(isinstance(v, int) for v in (start, end, size)) or not 0 <= start < end <= size:
        raise ConversionError(f"bad table entry for {f.get('filename')}: start {start}, end {end}, package {size}")
    return start, end, size


def extract(loader_path, data_path, suffix, out_path):
    with open(loader_path, encoding="utf-8") as f:
        start, end, size = find_entry(f.read(), suffix)
    actual = os.path.getsize(data_path)
    if actual != size:
        raise ConversionError(f"{data_path} is {actual} bytes, the table says {size}")
    with open(data_path, "rb") as f:
        f.seek(start)
        blob = f.read(end - start)
    with open(out_path, "wb") as f:
        f.write(blob)
    return start, end


def main(argv):
    if len(argv) != 4:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    try:
        start, end = extract(*argv)
    except (ConversionError, OSError) as e:
        print(f"packed_assets: {e}", file=sys.stderr)
        return 1
    print(f"packed_assets: {argv[3]}: bytes {start}..{end} of {argv[1]}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
