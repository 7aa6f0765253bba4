#!/usr/bin/python3
"""A VTU frame of rockdd read back with VTK, as ParaView reads it.

    vtu_readback_check.py --rockdd BUILD/bin/rockdd --source SOURCE --work DIR

Runs data/brazilian_disk_crack.toml for two steps twice: with the default zlib-compressed
frames and with output.compress = false, every field on (strain too). Reads each last frame
with vtkXMLUnstructuredGridReader and checks: the arrays and their component names (stress
xx, yy, xy; principal s1, s3; strain xx, yy, gamma_xy; vectors x, y, z); that VTK's values
equal tools/rockdd_results.read_vtu's bit for bit, and the compressed frame's the raw one's;
that the principal stresses are those of the stress tensor (s1 >= s3, their sum its trace,
their product its determinant). Prints the two frames' sizes. Exit 0 when every check holds,
1 otherwise, 77 (skipped) without VTK's Python module.
"""

import argparse
import os
import shutil
import subprocess
import sys

import numpy as np

try:
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
except ImportError:  # CTest reads 77 as skipped (SKIP_RETURN_CODE)
    print("skipped: VTK's Python module is not installed (Debian python3-vtk9)")
    sys.exit(77)

FAILURES = []


def expect(condition, message):
    if not condition:
        FAILURES.append(message)
        print(f"FAIL: {message}", file=sys.stderr)


def read_with_vtk(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if reader.GetErrorCode() or grid.GetNumberOfCells() == 0:
        raise SystemExit(f"VTK could not read {path}")
    arrays = {}
    for data in (grid.GetPointData(), grid.GetCellData()):
        for i in range(data.GetNumberOfArrays()):
            a = data.GetArray(i)
            names = [a.GetComponentName(c) for c in range(a.GetNumberOfComponents())]
            arrays[a.GetName()] = (vtk_to_numpy(a).reshape(a.GetNumberOfTuples(), -1), names)
    cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 3)
    return vtk_to_numpy(grid.GetPoints().GetData()), cells, arrays


def run(rockdd, scene, work, name, compress):
    out = os.path.join(work, name)
    shutil.rmtree(out, ignore_errors=True)
    args = [rockdd, "run", scene, "--quiet", "--threads", "1", "--out", out,
            "--set", "time.end=2e-5", "--set", "output.every=1",
            "--set", 'output.fields=["displacement","velocity","stress","principal","damage",'
                     '"block","material","strain"]',
            "--set", f"output.compress={'true' if compress else 'false'}"]
    subprocess.run(args, check=True)
    return os.path.join(out, "brazilian-disk-crack", "frames", "frame_00002.vtu")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--rockdd", required=True)
    p.add_argument("--source", required=True)
    p.add_argument("--work", required=True)
    a = p.parse_args()
    sys.path.insert(0, os.path.join(a.source, "tools"))
    import rockdd_results

    scene = os.path.join(a.source, "data", "brazilian_disk_crack.toml")
    os.makedirs(a.work, exist_ok=True)
    compressed = run(a.rockdd, scene, a.work, "compressed", True)
    raw = run(a.rockdd, scene, a.work, "raw", False)
    with open(compressed, "rb") as f:
        head = f.read(400)
    expect(b'compressor="vtkZLibDataCompressor"' in head, "the default frame is not compressed")
    with open(raw, "rb") as f:
        expect(b"compressor" not in f.read(400), "output.compress = false still compressed")
    sizes = {path: os.path.getsize(path) for path in (compressed, raw)}
    print(f"frame of 2 steps, every field: {sizes[raw]} bytes raw, {sizes[compressed]} bytes "
          f"zlib-compressed ({sizes[compressed] / sizes[raw]:.2f})")
    expect(sizes[compressed] < 0.8 * sizes[raw], "compression saved less than 20 %")

    expected_names = {"displacement": ["x", "y", "z"], "velocity": ["x", "y", "z"],
                      "stress": ["xx", "yy", "xy"], "principal": ["s1", "s3"],
                      "strain": ["xx", "yy", "gamma_xy"], "damage": [None],
                      "block": [None], "material": [None]}
    frames = {}
    for path in (compressed, raw):
        points, cells, arrays = read_with_vtk(path)
        frames[path] = (points, cells, arrays)
        expect(sorted(arrays) == sorted(expected_names), f"{path}: arrays {sorted(arrays)}")
        for name, names in expected_names.items():
            if name in arrays:
                expect(arrays[name][1] == names,
                       f"{path}: {name} components {arrays[name][1]}, expected {names}")
        # VTK's values against rockdd_results' reader, which reads the same bytes its own way.
        ours = rockdd_results.read_vtu(path)
        expect(np.array_equal(ours["triangles"], cells), f"{path}: connectivity differs")
        expect(np.array_equal(ours["points"], points), f"{path}: points differ")
        for name, (values, _) in arrays.items():
            mine = ours["point_data"].get(name, ours["cell_data"].get(name))
            expect(mine is not None and np.array_equal(np.asarray(mine).reshape(values.shape), values),
                   f"{path}: {name} differs between VTK and rockdd_results")
        expect(ours["component_names"].get("principal") == ["s1", "s3"],
               f"{path}: rockdd_results reads principal's components as "
               f"{ours['component_names'].get('principal')}")
        stress, principal = arrays["stress"][0], arrays["principal"][0]
        expect(np.abs(stress).max() > 1e5, f"{path}: no stress to speak of")
        s1, s3 = principal[:, 0], principal[:, 1]
        scale = np.abs(stress).max()
        expect(np.all(s1 >= s3), f"{path}: s1 < s3 somewhere")
        expect(np.allclose(s1 + s3, stress[:, 0] + stress[:, 1], rtol=0, atol=1e-9 * scale),
               f"{path}: s1 + s3 is not the trace")
        det = stress[:, 0] * stress[:, 1] - stress[:, 2] ** 2
        expect(np.allclose(s1 * s3, det, rtol=0, atol=1e-9 * scale ** 2),
               f"{path}: s1 s3 is not the determinant")
        displacement = arrays["displacement"][0]
        expect(np.abs(displacement).max() > 0, f"{path}: no displacement")
        expect(np.all(displacement[:, 2] == 0) and np.all(points[:, 2] == 0), f"{path}: z not 0")
    # The compressed frame holds the raw frame's values, bit for bit.
    (pc, cc, ac), (pr, cr, ar) = frames[compressed], frames[raw]
    expect(np.array_equal(pc, pr) and np.array_equal(cc, cr), "points or cells differ")
    for name in ac:
        expect(np.array_equal(ac[name][0], ar[name][0]), f"{name}: compressed differs from raw")
    if FAILURES:
        print(f"{len(FAILURES)} check(s) failed", file=sys.stderr)
        return 1
    print(f"ok: {len(ac)} arrays, {len(cc)} cells read back by VTK with their component names")
    return 0


if __name__ == "__main__":
    sys.exit(main())
