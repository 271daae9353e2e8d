"""Opens a gpudem-mpi particles.xmf and every mesh-wall .xmf of an output folder with
ParaView's XDMF readers (pvpython / python3-paraview) and checks each sees every snapshot, one
point and one vertex cell per particle and every particle field, and for a mesh one point per
vertex, one cell per triangle and the per-triangle fields. Usage: /usr/bin/python3
paraview_open.py OUTPUT_DIR. Exits non-zero on any mismatch."""
import glob
import os
import sys
import xml.etree.ElementTree as ET

from paraview import servermanager
from paraview.simple import XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT

FIELDS = {"radius", "velocity", "angular_velocity", "force", "material", "id"}
MESH_FIELDS = {"force", "pressure"}


def first_grids(xmf):
    return ET.parse(xmf).getroot().find("Domain/Grid").findall("Grid")


def expected_grids(xmf):
    """(time, points, cells) of every snapshot listed in the document."""
    listed = []
    for g in first_grids(xmf):
        cells = int(g.find("Topology").get("NumberOfElements"))
        rows = g.find("Geometry/DataItem").get("Dimensions").split()[0]
        listed.append((float(g.find("Time").get("Value")), int(rows), cells))
    return listed


def is_mesh(xmf):
    grids = first_grids(xmf)
    return bool(grids) and grids[0].find("Topology").get("TopologyType") == "Triangle"


def arrays_of(data, mesh):
    fields = data.GetCellData() if mesh else data.GetPointData()
    return {fields.GetArrayName(i) for i in range(fields.GetNumberOfArrays())}


def check(name, reader, grids, mesh):
    times = list(reader.TimestepValues)
    if len(times) != len(grids):
        return f"{name}: {len(times)} time steps, expected {len(grids)}"
    expected_fields = MESH_FIELDS if mesh else FIELDS
    for time, points, cells in (grids[0], grids[-1]):
        reader.UpdatePipeline(time)
        data = servermanager.Fetch(reader)
        if data.GetNumberOfPoints() != points or data.GetNumberOfCells() != cells:
            return (f"{name} at t={time}: {data.GetNumberOfPoints()} points, "
                    f"{data.GetNumberOfCells()} cells, expected {points} and {cells}")
        arrays = arrays_of(data, mesh)
        if cells > 0 and arrays != expected_fields:  # an empty snapshot has no arrays to show
            return (f"{name} at t={time}: arrays {sorted(arrays)}, "
                    f"expected {sorted(expected_fields)}")
    return None


def open_document(xmf):
    """Error lines of every reader on one document."""
    grids, mesh = expected_grids(xmf), is_mesh(xmf)
    readers = [("Xdmf3ReaderS", Xdmf3ReaderS(FileName=[xmf])),
               ("Xdmf3ReaderT", Xdmf3ReaderT(FileName=[xmf])),
               ("XDMFReader", XDMFReader(FileNames=[xmf]))]
    errors = [e for e in (check(f"{os.path.basename(xmf)} {n}", r, grids, mesh)
                          for n, r in readers) if e]
    if not errors:
        print(f"ParaView opened {xmf}: {len(grids)} snapshots with every reader")
    return errors


def main():
    documents = [os.path.join(sys.argv[1], "particles.xmf")]
    documents += [x for x in sorted(glob.glob(os.path.join(sys.argv[1], "*.xmf"))) if is_mesh(x)]
    errors = [e for xmf in documents for e in open_document(xmf)]
    for e in errors:
        print("error:", e)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
