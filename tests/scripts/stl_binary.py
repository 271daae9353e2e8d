"""Reads a binary STL for the checks of the STL generators (check_orifice_stl.py,
check_cylinder_stl.py), independently of the scripts' own writer."""
import struct
import sys


def read_binary_stl(path):
    """(normal, [corner a, corner b, corner c]) of each triangle; exits naming the file when its
    size does not match its triangle count."""
    with open(path, "rb") as f:
        data = f.read()
    (count,) = struct.unpack_from("<I", data, 80)
    if len(data) != 84 + 50 * count:
        sys.exit(f"{path}: {len(data)} bytes for {count} triangles")
    triangles = []
    for i in range(count):
        values = struct.unpack_from("<12f", data, 84 + 50 * i)
        triangles.append((values[:3], [values[3 + 3 * c:6 + 3 * c] for c in range(3)]))
    return triangles
