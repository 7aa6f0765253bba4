"""Reading rockdd run folders (summary.json, history.csv, VTU frames) and the fracture
measures that tests, tools/convergence and tools/plot share.

Every reader raises ResultError with the file named, never a traceback a user must decode.
"""

import csv
import json
import math
import os
import re
import xml.etree.ElementTree as ET
import zlib

import numpy as np


class ResultError(Exception):
    """A problem with a run folder's files, reported without a traceback."""


VTU_TYPES = {"Float64": "<f8", "Float32": "<f4", "Int64": "<i8", "Int32": "<i4", "Int16": "<i2",
             "Int8": "i1", "UInt64": "<u8", "UInt32": "<u4", "UInt16": "<u2", "UInt8": "u1"}


def read_vtu(path):
    """A triangle-mesh VTU with appended binary data, raw or zlib-compressed (as rockdd writes
    it), as numpy arrays: {"points": (N, 3), "triangles": (M, 3), "point_data": {name: array},
    "cell_data": {...}, "component_names": {name: [names]}}."""
    if not os.path.isfile(path):
        raise ResultError(f"no such file: {path}")
    with open(path, "rb") as f:
        raw = f.read()
    tag = raw.find(b"<AppendedData")
    marker = raw.find(b"_", raw.find(b">", tag) + 1) if tag >= 0 else -1
    if marker < 0:
        raise ResultError(f"{path}: not a VTU file with appended binary data")
    # The XML part parses on its own once the binary section is cut off and the tags closed.
    try:
        root = ET.fromstring(raw[:tag].decode("utf-8") + "</VTKFile>")
    except (ET.ParseError, UnicodeDecodeError) as e:
        raise ResultError(f"{path}: bad XML header ({e})") from None
    if root.get("byte_order", "LittleEndian") != "LittleEndian":
        raise ResultError(f"{path}: only little-endian VTU files are read")
    header = {"UInt64": "<u8", "UInt32": "<u4"}.get(root.get("header_type", "UInt32"))
    piece = root.find("UnstructuredGrid/Piece")
    if header is None or piece is None:
        raise ResultError(f"{path}: not an UnstructuredGrid VTU file")
    compressor = root.get("compressor")
    if compressor not in (None, "vtkZLibDataCompressor"):
        raise ResultError(f"{path}: data compressed with {compressor}; only zlib is read")
    base = marker + 1
    size = np.dtype(header).itemsize

    def block_bytes(start, name, where):
        """The (uncompressed) bytes of the appended block at `start`."""
        if start + size > len(raw):
            raise ResultError(f"{path}: {where} array '{name}' lies past the end of the file")
        if compressor is None:
            nbytes = int(np.frombuffer(raw, dtype=header, count=1, offset=start)[0])
            if start + size + nbytes > len(raw):
                raise ResultError(f"{path}: {where} array '{name}' is truncated")
            return raw[start + size:start + size + nbytes]
        # vtkZLibDataCompressor: [blocks, block size, last block size (0: full), compressed
        # size of each block], then the blocks, each compressed on its own.
        blocks = int(np.frombuffer(raw, dtype=header, count=1, offset=start)[0])
        if start + (3 + blocks) * size > len(raw):
            raise ResultError(f"{path}: {where} array '{name}' is truncated")
        head = np.frombuffer(raw, dtype=header, count=3 + blocks, offset=start).astype(np.int64)
        at, parts = start + (3 + blocks) * size, []
        for b in range(blocks):
            packed = raw[at:at + int(head[3 + b])]
            if len(packed) != int(head[3 + b]):
                raise ResultError(f"{path}: {where} array '{name}' is truncated")
            try:
                parts.append(zlib.decompress(packed))
            except zlib.error as e:
                raise ResultError(f"{path}: {where} array '{name}': bad zlib data ({e})") from None
            at += int(head[3 + b])
        data = b"".join(parts)
        expected = (blocks - 1) * int(head[1]) + (int(head[2]) or int(head[1])) if blocks else 0
        if len(data) != expected:
            raise ResultError(f"{path}: {where} array '{name}' holds {len(data)} bytes, its "
                              f"header says {expected}")
        return data

    def array(element, count, where):
        name = element.get("Name", "Points")
        dtype = VTU_TYPES.get(element.get("type"))
        if element.get("format") != "appended" or dtype is None:
            raise ResultError(f"{path}: {where} array '{name}' is not appended binary data of a known type")
        try:
            start = base + int(element.get("offset"))
            components = int(element.get("NumberOfComponents", "1"))
        except (TypeError, ValueError):
            raise ResultError(f"{path}: {where} array '{name}' has a bad offset or component count") from None
        data = block_bytes(start, name, where)
        itemsize = np.dtype(dtype).itemsize
        if len(data) % itemsize:
            raise ResultError(f"{path}: {where} array '{name}' is truncated")
        values = np.frombuffer(data, dtype=dtype)
        if count is not None and values.size != count * components:
            raise ResultError(f"{path}: {where} array '{name}' has {values.size} values, "
                            f"expected {count} x {components}")
        return values.reshape(-1, components) if components > 1 else values

    try:
        num_points, num_cells = int(piece.get("NumberOfPoints")), int(piece.get("NumberOfCells"))
    except (TypeError, ValueError):
        raise ResultError(f"{path}: Piece without NumberOfPoints/NumberOfCells") from None
    points = piece.find("Points/DataArray")
    if points is None:
        raise ResultError(f"{path}: no Points array")
    cells = {a.get("Name"): a for a in piece.findall("Cells/DataArray")}
    if "connectivity" not in cells:
        raise ResultError(f"{path}: no cell connectivity array")
    if "types" in cells and np.any(array(cells["types"], num_cells, "cell") != 5):
        raise ResultError(f"{path}: only triangle meshes are drawn (VTK cell type 5)")
    triangles = array(cells["connectivity"], None, "cell").astype(np.int64)
    if triangles.size != 3 * num_cells or \
            (triangles.size and not 0 <= triangles.min() <= triangles.max() < num_points):
        raise ResultError(f"{path}: connectivity is not {num_cells} triangles of {num_points} points")
    return {
        "points": array(points, num_points, "point").reshape(num_points, -1),
        "triangles": triangles.reshape(num_cells, 3),
        "point_data": {a.get("Name"): array(a, num_points, "point")
                       for a in piece.findall("PointData/DataArray")},
        "cell_data": {a.get("Name"): array(a, num_cells, "cell")
                      for a in piece.findall("CellData/DataArray")},
        "component_names": {a.get("Name"): [a.get(f"ComponentName{i}")
                                            for i in range(int(a.get("NumberOfComponents", "1")))]
                            for a in piece.findall("*/DataArray")
                            if a.get("ComponentName0") is not None},
    }


def list_frames(outdir):
    """[(step, time or None, path)] of a run folder's frames, sorted by step.

    frames.pvd is trusted over a listing of frames/: a rerun overwrites the pvd but leaves the
    frames of an earlier, longer run behind."""
    if not os.path.isdir(outdir):
        raise ResultError(f"no such run folder: {outdir}")
    pvds = [p for p in (os.path.join(outdir, "frames.pvd"), os.path.join(outdir, "frames", "frames.pvd"))
            if os.path.isfile(p)]
    number = re.compile(r"(\d+)\.vtu")
    frames = {}
    if pvds:
        try:
            datasets = ET.parse(pvds[0]).getroot().iter("DataSet")
            for d in datasets:
                name = d.get("file", "")
                m = number.search(os.path.basename(name))
                if not m:
                    raise ResultError(f"{pvds[0]}: cannot tell the step of '{name}'")
                frames[int(m.group(1))] = (float(d.get("timestep", "nan")),
                                           os.path.join(os.path.dirname(pvds[0]), name))
        except (ET.ParseError, ValueError) as e:
            raise ResultError(f"{pvds[0]}: bad frame collection ({e})") from None
    else:
        folder = os.path.join(outdir, "frames")
        if os.path.isdir(folder):
            for name in os.listdir(folder):
                if m := re.fullmatch(r"frame_(\d+)\.vtu", name):
                    frames[int(m.group(1))] = (None, os.path.join(folder, name))
    if not frames:
        raise ResultError(f"no VTU frames in {outdir} (frames.pvd or frames/frame_NNNNN.vtu)")
    return [(step, time, path) for step, (time, path) in sorted(frames.items())]




def read_summary(outdir):
    """summary.json of a run folder as a dict."""
    path = os.path.join(outdir, "summary.json")
    try:
        with open(path) as f:
            return json.load(f)
    except OSError:
        raise ResultError(f"no such file: {path}") from None
    except json.JSONDecodeError as e:
        raise ResultError(f"{path}: not JSON ({e})") from None


def read_history(outdir):
    """history.csv of a run folder as {column: numpy array}."""
    path = os.path.join(outdir, "history.csv")
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError:
        raise ResultError(f"no such file: {path}") from None
    if len(rows) < 2:
        raise ResultError(f"{path}: no rows")
    try:
        values = np.array([[float(x) for x in r] for r in rows[1:]])
    except ValueError as e:
        raise ResultError(f"{path}: not numeric ({e})") from None
    return {name: values[:, i] for i, name in enumerate(rows[0])}


def last_frame(outdir):
    """The last VTU frame of a run folder (read_vtu's dictionary) and its step."""
    step, _, path = list_frames(outdir)[-1]
    return read_vtu(path), step


def reference_geometry(mesh):
    """Reference (t = 0) point coordinates (N, 2) and element centroids (M, 2) of a frame."""
    points = mesh["points"][:, :2]
    displacement = mesh["point_data"].get("displacement")
    if displacement is not None:
        points = points - np.asarray(displacement).reshape(len(points), -1)[:, :2]
    return points, points[mesh["triangles"]].mean(axis=1)


def damaged_fraction_near_line(mesh, origin, direction, half_width):
    """Of the elements with damage > 0, the fraction whose reference centroid lies within
    half_width of the line through origin along direction; and how many are damaged."""
    damage = np.asarray(mesh["cell_data"]["damage"])
    _, centroid = reference_geometry(mesh)
    d = np.asarray(direction, float) / np.hypot(*direction)
    offset = centroid - np.asarray(origin, float)
    distance = np.abs(offset[:, 0] * d[1] - offset[:, 1] * d[0])
    damaged = damage > 0
    count = int(damaged.sum())
    return (float((distance[damaged] <= half_width).sum()) / count if count else 0.0), count


def block_sizes(mesh):
    """Element counts of the blocks of a frame, largest first."""
    block = np.asarray(mesh["cell_data"]["block"]).astype(np.int64)
    return sorted(np.bincount(block - block.min()).tolist(), reverse=True)


def large_blocks(mesh, fraction=0.01):
    """How many blocks hold more than `fraction` of the elements."""
    sizes = block_sizes(mesh)
    total = sum(sizes)
    return sum(1 for s in sizes if s > fraction * total)


def through_going_fracture(mesh):
    """Whether the crack faces of a frame form a connected chain that touches two opposite
    sides of the specimen (left and right, or bottom and top, of its reference bounding box,
    within 1 % of its size): a fracture that runs from one side to the other, not one that
    cuts off a corner. Returns that, with the chain's element-edge count."""
    points, _ = reference_geometry(mesh)
    tris = mesh["triangles"]
    block = np.asarray(mesh["cell_data"]["block"]).astype(np.int64)
    # Crack faces: edges whose two triangles lie in different blocks, found on merged points.
    scale = max(np.ptp(points[:, 0]), np.ptp(points[:, 1]), 1e-300)
    keys = np.round(points / (scale * 1e-9)).astype(np.int64)
    merged = {}
    ids = np.array([merged.setdefault((int(k[0]), int(k[1])), len(merged)) for k in keys])
    owners = {}
    for t, (a, b, c) in enumerate(ids[tris]):
        for e in ((a, b), (b, c), (c, a)):
            owners.setdefault((min(e), max(e)), []).append(t)
    outer_nodes = set()
    crack = []
    for e, ts in owners.items():
        if len(ts) == 1:
            outer_nodes.update(e)
        elif len(ts) == 2 and block[ts[0]] != block[ts[1]]:
            crack.append(e)
    parent = {}

    def find(x):
        while parent.setdefault(x, x) != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for a, b in crack:
        parent[find(a)] = find(b)
    lo, hi = points.min(axis=0), points.max(axis=0)
    position = np.zeros((len(merged), 2))
    position[ids] = points
    best = (False, 0)
    components = {}
    for a, b in crack:
        components.setdefault(find(a), []).append((a, b))
    for edges in components.values():
        touching = sorted({n for e in edges for n in e if n in outer_nodes})
        p = position[touching].reshape(-1, 2)
        near = 0.01 * scale
        through = bool(len(p)) and any(
            (p[:, axis] <= low + near).any() and (p[:, axis] >= high - near).any()
            for axis, low, high in ((0, lo[0], hi[0]), (1, lo[1], hi[1])))
        if (through, len(edges)) > best:
            best = (through, len(edges))
    return best
