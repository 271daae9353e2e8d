"""Binary STL writing shared by the scripts that make the shipped meshes
(make_orifice_stl.py, make_cylinder_stl.py)."""
import struct


def unit_normal(triangle):
    """The unit normal of (a, b, c) by the right-hand rule, (b - a) x (c - a) / |...|, with
    +0.0 for a zero component (never -0.0, so that a file is the same whatever the signs)."""
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = triangle
    u, v = (bx - ax, by - ay, bz - az), (cx - ax, cy - ay, cz - az)
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    length = (n[0] ** 2 + n[1] ** 2 + n[2] ** 2) ** 0.5
    return tuple(c / length + 0.0 for c in n)


def write_binary_stl(path, title, triangles):
    """`triangles` as a little-endian binary STL: an 80-byte header holding `title`, the count,
    then each triangle's unit normal and corners as 32-bit floats."""
    with open(path, "wb") as f:
        f.write(title.encode().ljust(80, b" "))
        f.write(struct.pack("<I", len(triangles)))
        for tri in triangles:
            f.write(struct.pack("<3f", *unit_normal(tri)))
            for vertex in tri:
                f.write(struct.pack("<3f", *vertex))
            f.write(b"\0\0")
