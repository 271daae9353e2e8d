"""Opens a gpudem-mpi particles.xmf with ParaView's XDMF readers (pvpython / python3-paraview)
and checks each sees every snapshot, one point and one vertex cell per particle, and every
field. Usage: /usr/bin/python3 paraview_open.py OUTPUT_DIR. Exits non-zero on any mismatch."""
import os
import sys
import xml.etree.ElementTree as ET

from paraview import servermanager
from paraview.simple import XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT

FIELDS = {"radius", "velocity", "angular_velocity", "force", "material", "id"}


def expected_grids(xmf):
    """(time, particle count) of every snapshot listed in the document."""
    grids = ET.parse(xmf).getroot().find("Domain/Grid").findall("Grid")
    return [(float(g.find("Time").get("Value")),
             int(g.find("Topology").get("NumberOfElements"))) for g in grids]


def check(name, reader, grids):
    times = list(reader.TimestepValues)
    if len(times) != len(grids):
        return f"{name}: {len(times)} time steps, expected {len(grids)}"
    for time, count in (grids[0], grids[-1]):
        reader.UpdatePipeline(time)
        data = servermanager.Fetch(reader)
        arrays = {data.GetPointData().GetArrayName(i)
                  for i in range(data.GetPointData().GetNumberOfArrays())}
        if data.GetNumberOfPoints() != count or data.GetNumberOfCells() != count:
            return (f"{name} at t={time}: {data.GetNumberOfPoints()} points, "
                    f"{data.GetNumberOfCells()} cells, expected {count}")
        if count > 0 and arrays != FIELDS:  # an empty snapshot has no arrays to show
            return f"{name} at t={time}: arrays {sorted(arrays)}, expected {sorted(FIELDS)}"
    return None


def main():
    xmf = os.path.join(sys.argv[1], "particles.xmf")
    grids = expected_grids(xmf)
    readers = [("Xdmf3ReaderS", Xdmf3ReaderS(FileName=[xmf])),
               ("Xdmf3ReaderT", Xdmf3ReaderT(FileName=[xmf])),
               ("XDMFReader", XDMFReader(FileNames=[xmf]))]
    errors = [e for e in (check(n, r, grids) for n, r in readers) if e]
    for e in errors:
        print("error:", e)
    if not errors:
        print(f"ParaView opened {xmf}: {len(grids)} snapshots with every reader")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
