#!/usr/bin/python3
"""Checks the XDMF documents of an output folder (particles and mesh walls) against their HDF5
snapshots.

    check_snapshot.py DIR              check every .xmf in DIR
    check_snapshot.py --self-test DIR  check that broken copies of DIR's documents are caught

A document must be valid XML holding Xdmf/Domain/Grid, a temporal collection of uniform grids
with increasing times. In each grid, every DataItem (Format "HDF", text "file.h5:/dataset") must
name a file relative to the document that exists and a dataset in it whose shape equals
Dimensions and whose dtype matches NumberType and Precision; Time Value must equal the file's
"time" attribute. A Polyvertex grid (particles) has one row per element in every dataset and
attributes centred on nodes. A Triangle grid (a mesh wall) and a Polyline grid (bonds) have
Topology data of NumberOfElements × 3 (Triangle) or × NodesPerElement (Polyline) vertex indices
below the number of Geometry rows, and attributes centred on cells with one row per element.
Exit status 0 when all holds, 1 with one line per problem otherwise, 2 on bad usage.
"""
import argparse
import math
import os
import pathlib
import shutil
import sys
import tempfile
import xml.etree.ElementTree as ET

try:
    import h5py
except ImportError:
    sys.exit("check_snapshot.py needs h5py (Debian: python3-h5py); run it with /usr/bin/python3")

# XDMF NumberType -> numpy dtype kind ("Float" with Precision 4 is the XDMF default).
NUMBER_KINDS = {"Float": "f", "Int": "i", "UInt": "u", "Char": "i", "UChar": "u",
                "Short": "i", "UShort": "u"}
VALUES_PER_NODE = {"Scalar": 1, "Vector": 3}


def check_data_item(item, base_dir, where):
    """Problems of one DataItem, and the shape it declares (None when unreadable)."""
    problems = []
    try:
        dims = tuple(int(d) for d in item.get("Dimensions", "").split())
    except ValueError:
        return [f"{where}: Dimensions '{item.get('Dimensions')}' is not a list of integers"], None
    if not dims:
        return [f"{where}: DataItem has no Dimensions"], None
    if item.get("Format") != "HDF":
        problems.append(f"{where}: Format is '{item.get('Format')}', expected 'HDF'")
    number_type = item.get("NumberType", item.get("DataType", "Float"))
    precision = int(item.get("Precision", "4"))
    if number_type not in NUMBER_KINDS:
        problems.append(f"{where}: unknown NumberType '{number_type}'")
    file_name, _, dataset_path = (item.text or "").strip().partition(":")
    if not dataset_path:
        return problems + [f"{where}: '{item.text}' is not 'file.h5:/dataset'"], dims
    if os.path.isabs(file_name):
        problems.append(f"{where}: file '{file_name}' is absolute; it must be relative")
    path = base_dir / file_name
    if not path.is_file():
        return problems + [f"{where}: file '{path}' does not exist"], dims
    with h5py.File(path, "r") as h5:
        dataset = h5.get(dataset_path)
        if not isinstance(dataset, h5py.Dataset):
            return problems + [f"{where}: no dataset '{dataset_path}' in '{path}'"], dims
        if dataset.shape != dims:
            problems.append(f"{where}: {file_name}:{dataset_path} has shape {dataset.shape}, "
                            f"Dimensions say {dims}")
        kind, size = dataset.dtype.kind, dataset.dtype.itemsize
        if NUMBER_KINDS.get(number_type) != kind or precision != size:
            problems.append(f"{where}: {file_name}:{dataset_path} is {dataset.dtype}, DataItem "
                            f"says {number_type} of {precision} bytes")
    return problems, dims


def time_attribute(item, base_dir):
    """The "time" attribute of the file a DataItem points to, or None."""
    path = base_dir / (item.text or "").strip().partition(":")[0]
    if not path.is_file():
        return None
    with h5py.File(path, "r") as h5:
        return float(h5.attrs["time"]) if "time" in h5.attrs else None


def read_dataset(item, base_dir):
    """The values a DataItem points to (its file and dataset exist: check_data_item passed)."""
    file_name, _, dataset_path = (item.text or "").strip().partition(":")
    with h5py.File(base_dir / file_name, "r") as h5:
        return h5[dataset_path][()]


def check_cell_indices(topology, geometry, base_dir, where):
    """Problems of a Triangle or Polyline topology's vertex indices: each must name a Geometry
    row."""
    vertices = read_dataset(geometry.find("DataItem"), base_dir).shape[0]
    indices = read_dataset(topology.find("DataItem"), base_dir)
    if indices.size and indices.max() >= vertices:
        return [f"{where}/Topology: vertex index {indices.max()} beyond the {vertices} vertices"]
    return []


# Per topology: where attributes are centred and whether the geometry has a row per element.
CENTERS = {"polyvertex": "Node", "triangle": "Cell", "polyline": "Cell"}


def grid_items(grid, topology, geometry, corners, where, problems):
    """(name, element holding a DataItem, values per row, one row per element) to check;
    `corners` is the vertices per cell, 0 for a Polyvertex grid."""
    cells = corners > 0
    items = [(f"{where}/Geometry", geometry, 3, not cells)] if geometry is not None else []
    if cells:
        items.append((f"{where}/Topology", topology, corners, True))
    center = "Cell" if cells else "Node"
    for attribute in grid.findall("Attribute"):
        kind = attribute.get("AttributeType", attribute.get("Type", "Scalar"))
        name = f"{where}/Attribute[{attribute.get('Name')}]"
        if attribute.get("Center") != center:
            problems.append(f"{name}: Center is '{attribute.get('Center')}', expected {center}")
        items.append((name, attribute, VALUES_PER_NODE.get(kind), True))
    return items


def check_items(items, elements, time, base_dir):
    """Problems of the DataItems of a grid's items (grid_items); True when all were readable."""
    problems, readable = [], True
    for name, parent, values_per_row, row_per_element in items:
        item = parent.find("DataItem")
        if item is None:
            problems.append(f"{name}: no DataItem")
            readable = False
            continue
        item_problems, dims = check_data_item(item, base_dir, name)
        problems += item_problems
        readable = readable and not item_problems
        if dims is None:
            continue
        if row_per_element and dims[0] != elements:
            problems.append(f"{name}: {dims[0]} values, Topology NumberOfElements is {elements}")
        per_row = math.prod(dims[1:])
        if values_per_row is not None and per_row != values_per_row:
            problems.append(f"{name}: {per_row} values per row, expected {values_per_row}")
        stored_time = time_attribute(item, base_dir)
        if stored_time is not None and stored_time != time:
            problems.append(f"{name}: Time Value {time!r} differs from the file's time "
                            f"attribute {stored_time!r}")
    return problems, readable


def check_grid(grid, base_dir, where):
    """Problems of one uniform grid, and its time (None when unreadable)."""
    problems = []
    time_element = grid.find("Time")
    try:
        time = float(time_element.get("Value"))
    except (AttributeError, TypeError, ValueError):
        return [f"{where}: no numeric <Time Value>"], None
    topology = grid.find("Topology")
    if topology is None:
        return [f"{where}: no Topology"], time
    topology_type = topology.get("TopologyType", topology.get("Type", ""))
    if topology_type.lower() not in CENTERS:
        problems.append(f"{where}: TopologyType '{topology_type}', expected Polyvertex, "
                        "Triangle or Polyline")
    corners = {"triangle": 3, "polyline": int(topology.get("NodesPerElement", "2"))}.get(
        topology_type.lower(), 0)
    cells = corners > 0
    try:
        elements = int(topology.get("NumberOfElements", topology.get("Dimensions")))
    except (TypeError, ValueError):
        return problems + [f"{where}: Topology has no integer NumberOfElements"], time
    geometry = grid.find("Geometry")
    if geometry is None or geometry.get("GeometryType", geometry.get("Type")) != "XYZ":
        problems.append(f"{where}: no Geometry of GeometryType XYZ")
    items = grid_items(grid, topology, geometry, corners, where, problems)
    item_problems, readable = check_items(items, elements, time, base_dir)
    problems += item_problems
    if cells and readable and geometry is not None:
        problems += check_cell_indices(topology, geometry, base_dir, where)
    return problems, time


def check_document(xmf):
    """Problems of one .xmf document."""
    try:
        root = ET.parse(xmf).getroot()
    except ET.ParseError as error:
        return [f"{xmf}: not valid XML: {error}"]
    collection = root.find("Domain/Grid") if root.tag == "Xdmf" else None
    if collection is None:
        return [f"{xmf}: no Xdmf/Domain/Grid"]
    if (collection.get("GridType"), collection.get("CollectionType")) != ("Collection", "Temporal"):
        return [f"{xmf}: the first grid is not a temporal collection"]
    grids = collection.findall("Grid")
    if not grids:
        return [f"{xmf}: the temporal collection holds no grid"]
    problems, times = [], []
    for index, grid in enumerate(grids):
        where = f"{xmf.name}: Grid[{index}] '{grid.get('Name')}'"
        if grid.get("GridType", "Uniform") != "Uniform":
            problems.append(f"{where}: GridType is not Uniform")
        grid_problems, time = check_grid(grid, xmf.parent, where)
        problems += grid_problems
        if time is not None:
            times.append(time)
    if any(later <= earlier for earlier, later in zip(times, times[1:])):
        problems.append(f"{xmf}: grid times {times} do not increase")
    return problems


def check_folder(folder):
    """Problems of every .xmf in `folder`, and how many documents there were."""
    documents = sorted(pathlib.Path(folder).glob("*.xmf"))
    if not documents:
        return [f"{folder}: no .xmf document"], 0
    return [p for xmf in documents for p in check_document(xmf)], len(documents)


def first_of(root, path):
    element = root.find(path)
    if element is None:
        raise LookupError(f"the document has no {path}")
    return element


def bump_dimension(item):
    dims = item.get("Dimensions").split()
    item.set("Dimensions", " ".join([str(int(dims[0]) + 1)] + dims[1:]))


def set_attribute(path, key, value):
    return lambda root: first_of(root, path).set(key, value)


def edit_text(path, old, new):
    def edit(root):
        item = first_of(root, path)
        item.text = item.text.replace(old, new)
    return edit


GRID = "Domain/Grid/Grid"
ID_ITEM = f"{GRID}/Attribute[@Name='id']/DataItem"
# Each breaks a document in one way check_document must report: any document, then particle
# documents (Polyvertex), mesh documents (Triangle) and bond documents (Polyline).
COMMON_BREAKS = {
    "dimensions differ from the dataset":
        lambda root: bump_dimension(first_of(root, f"{GRID}/Geometry/DataItem")),
    "precision differs from the dataset": lambda root: (
        lambda item: item.set("Precision", "8" if item.get("Precision") == "4" else "4"))(
            first_of(root, f"{GRID}/Geometry/DataItem")),
    "file missing": edit_text(f"{GRID}/Geometry/DataItem", ".h5:", "_gone.h5:"),
    "NumberOfElements differs": lambda root: first_of(root, f"{GRID}/Topology").set(
        "NumberOfElements", str(int(first_of(root, f"{GRID}/Topology")
                                    .get("NumberOfElements")) + 1)),
    "time differs from the file": set_attribute(f"{GRID}/Time", "Value", "-1.0"),
}
PARTICLE_BREAKS = {
    "signedness differs from the dataset": set_attribute(ID_ITEM, "NumberType", "Int"),
    "dataset missing": edit_text(ID_ITEM, ":/id", ":/no_such_dataset"),
    "vector given as scalar": set_attribute(f"{GRID}/Attribute[@Name='velocity']",
                                            "AttributeType", "Scalar"),
}
MESH_BREAKS = {
    "signedness differs from the dataset": set_attribute(f"{GRID}/Topology/DataItem",
                                                         "NumberType", "Int"),
    "dataset missing": edit_text(f"{GRID}/Attribute[@Name='pressure']/DataItem", "/pressure",
                                 "/no_such_dataset"),
    "vector given as scalar": set_attribute(f"{GRID}/Attribute[@Name='force']",
                                            "AttributeType", "Scalar"),
    "cell values centred on nodes": set_attribute(f"{GRID}/Attribute[@Name='pressure']",
                                                  "Center", "Node"),
    "vertex index beyond the geometry": lambda root: (
        edit_text(f"{GRID}/Geometry/DataItem", "/vertices", "/force")(root),
        set_attribute(f"{GRID}/Geometry/DataItem", "Dimensions",
                      first_of(root, f"{GRID}/Topology").get("NumberOfElements") + " 3")(root)),
}

BOND_BREAKS = {
    "signedness differs from the dataset": set_attribute(f"{GRID}/Topology/DataItem",
                                                         "NumberType", "Int"),
    "dataset missing": edit_text(f"{GRID}/Attribute[@Name='normal_force']/DataItem",
                                 "/normal_force", "/no_such_dataset"),
    "cell values centred on nodes": set_attribute(f"{GRID}/Attribute[@Name='strength_used']",
                                                  "Center", "Node"),
    "two corners given as three": set_attribute(f"{GRID}/Topology", "TopologyType", "Triangle"),
}
BREAKS_BY_TOPOLOGY = {"triangle": MESH_BREAKS, "polyline": BOND_BREAKS}


def breaks_for(xmf):
    """The ways to break this document: those of its kind of grid (Polyvertex, Triangle or
    Polyline)."""
    topology = ET.parse(xmf).getroot().find(f"{GRID}/Topology")
    kind = topology.get("TopologyType", "").lower() if topology is not None else ""
    return {**COMMON_BREAKS, **BREAKS_BY_TOPOLOGY.get(kind, PARTICLE_BREAKS)}


def self_test(folder):
    """Breaks copies of the folder's documents in several ways; each must be reported."""
    problems, count = check_folder(folder)
    if problems:
        print("the folder itself fails the check:", *problems, sep="\n  ", file=sys.stderr)
        return 1
    missed = []
    with tempfile.TemporaryDirectory() as scratch:
        for xmf in sorted(pathlib.Path(folder).glob("*.xmf")):
            breaks = breaks_for(xmf)
            breaks["not XML"] = None
            for label, apply in breaks.items():
                copy = pathlib.Path(scratch) / label.replace(" ", "_")
                shutil.copytree(folder, copy)
                broken = copy / xmf.name
                if apply is None:
                    broken.write_text(xmf.read_text()[:-20])
                else:
                    tree = ET.parse(xmf)
                    apply(tree.getroot())
                    tree.write(broken)
                found = check_document(broken)
                print(f"{xmf.name}, {label}: " + (found[0] if found else "NOT CAUGHT"))
                if not found:
                    missed.append(f"{xmf.name}: {label}")
                shutil.rmtree(copy)
    if missed:
        print("broken documents that passed the check:", *missed, sep="\n  ", file=sys.stderr)
        return 1
    print(f"self-test ok: {count} document(s), every break caught")
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", help="output folder holding .xmf and .h5 files")
    parser.add_argument("--self-test", action="store_true",
                        help="check that broken copies of the folder's documents are caught")
    args = parser.parse_args()
    if not pathlib.Path(args.folder).is_dir():
        parser.error(f"'{args.folder}' is not a folder")
    if args.self_test:
        return self_test(args.folder)
    problems, count = check_folder(args.folder)
    if problems:
        print(*problems, sep="\n", file=sys.stderr)
        return 1
    print(f"ok: {count} XDMF document(s) in {args.folder} match their HDF5 snapshots")
    return 0


if __name__ == "__main__":
    sys.exit(main())
