#!/usr/bin/python3
"""The elastic flattened Brazilian disk of data/brazilian_disk_elastic.toml, solved by DOLFINx.

The peer run of issue 14: meshes the disk with Gmsh as rockdd does, imports it into DOLFINx,
solves plane-stress P1 elasticity with PETSc KSP preonly + Cholesky (MUMPS) and prints the
wall time of each phase.

  bench/peers/dolfinx_brazilian.py [--element-size 5e-4] [--scene data/brazilian_disk_elastic.toml]
                                   [--json FILE] [--view] [--mumps-ordering N]

Needs Debian's python3-dolfinx and python3-gmsh (apt-get install -y python3-dolfinx python3-gmsh);
run it on one MPI rank with OMP_NUM_THREADS=1 for a one-thread comparison.

The geometry, the material, the loads and the restraints come from the scene. The disk is drawn
as rockdd's add_disk (engine/mesh/builtin_shapes.cpp) draws it: the same Gmsh geo-kernel
points, curves and loop in the same order, the centre embedded, each point's size and
Mesh.MeshSizeMax set to element_size, default algorithm. With the same Gmsh (Debian's 4.8.4,
which rockdd links to) the triangles are the same; the count is printed to check.

The problem, as in rockdd: E, nu, thickness t, plane stress, P1 triangles. Pressure p on each
flat along the inward normal, as the consistent P1 load (p l t / 2 to each end of an edge, which
is what rockdd applies). Restraints: the centre node fixed in x and y, the top node
(0, R cos alpha) fixed in x. Both codes eliminate these dofs: rockdd drops them from the system,
DOLFINx keeps their rows and columns with a 1 on the diagonal (3 extra equations).

Timers (seconds of wall time, time.perf_counter):
  meshing        Gmsh: geometry + generate(2)
  import         gmshio.model_to_mesh (topology, geometry, partitioning on one rank)
  setup          function space, forms (FFCx JIT, loaded from ~/.cache/fenics after the first
                 run; `jit` says how long the forms took), locating the restrained nodes
  pattern        fem.petsc.create_matrix: the sparsity pattern and the allocation
  assembly       assemble_matrix into that matrix + assemble_vector + lifting and set_bc
  analysis       MUMPS analysis (PETSc event MatCholFctrSym, inside KSPSetUp)
  factorization  MUMPS numeric factorization (PETSc event MatCholFctrNum, inside KSPSetUp)
  ksp_setup      the wall time of KSPSetUp (analysis + factorization + PETSc's own work)
  solve          KSPSolve (forward and backward substitution)
  total          from the start of meshing to the end of the solve
The centre's sigma_xx (the area-weighted mean over the triangles around the centre node, as
rockdd's nodal stress) and the mean uy of the top flat's nodes (rockdd's probe "top") check that both codes solve the same problem.
"""

import argparse
import ctypes
import json
import math
import os
import sys
import time
import tomllib

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.normpath(os.path.join(here, "..", ".."))



def blas_kernels():
    """The kernel set OpenBLAS runs in this process (what MUMPS's BLAS calls use), or "?"."""
    for name in ("libopenblas.so.0", "libblas.so.3"):
        try:
            lib = ctypes.CDLL(name)
            lib.openblas_get_corename.restype = ctypes.c_char_p
            return lib.openblas_get_corename().decode()
        except (OSError, AttributeError):
            continue
    return "?"

def scene_problem(path, element_size):
    """The numbers of the disk scene that this script reproduces."""
    with open(path, "rb") as f:
        scene = tomllib.load(f)
    mesh = scene["mesh"]
    if mesh.get("shape") != "disk":
        sys.exit(f"{path}: expected mesh.shape = \"disk\"")
    if scene["scene"].get("plane", "stress") != "stress":
        sys.exit(f"{path}: expected plane = \"stress\"")
    (material,) = scene["material"]
    pressures = {load["on"]: load["pressure"] for load in scene["load"] if "pressure" in load}
    fixes = {b["on"]: b["fix"] for b in scene["boundary"]}
    expected = {"center": ["x", "y"], "top": ["x"]}
    if fixes != expected or set(pressures) != {"top_flat", "bottom_flat"}:
        sys.exit(f"{path}: this script reproduces only restraints {expected} and a pressure on "
                 f"top_flat and bottom_flat, got {fixes} and {pressures}")
    return {
        "radius": mesh["radius"],
        "origin": mesh.get("origin", [0.0, 0.0]),
        "alpha_deg": mesh["flat_half_angle_deg"],
        "element_size": element_size if element_size else mesh["element_size"],
        "young": material["young"],
        "poisson": material["poisson"],
        "thickness": scene["scene"].get("thickness", 1.0),
        "pressure": pressures,
    }


def draw_disk(gmsh, p):
    """rockdd's add_disk, statement for statement (alpha > 0)."""
    geo = gmsh.model.geo
    r, size = p["radius"], p["element_size"]
    alpha = math.radians(p["alpha_deg"])
    cx, cy = p["origin"]
    half_width, flat_y = r * math.sin(alpha), r * math.cos(alpha)

    def point(x, y):
        return geo.addPoint(cx + x, cy + y, 0.0, size)

    center = point(0.0, 0.0)
    right, left = point(r, 0.0), point(-r, 0.0)
    top, bottom = point(0.0, flat_y), point(0.0, -flat_y)
    loop, rim, top_flat, bottom_flat = [], [], [], []

    def arc(a, b):
        rim.append(geo.addCircleArc(a, center, b))
        loop.append(rim[-1])

    def flat(a, b, named):
        named.append(geo.addLine(a, b))
        loop.append(named[-1])

    bottom_right, top_right = point(half_width, -flat_y), point(half_width, flat_y)
    top_left, bottom_left = point(-half_width, flat_y), point(-half_width, -flat_y)
    flat(bottom, bottom_right, bottom_flat)
    arc(bottom_right, right)
    arc(right, top_right)
    flat(top_right, top, top_flat)
    flat(top, top_left, top_flat)
    arc(top_left, left)
    arc(left, bottom_left)
    flat(bottom_left, bottom, bottom_flat)
    surface = geo.addPlaneSurface([geo.addCurveLoop(loop)])
    geo.synchronize()
    gmsh.model.mesh.embed(0, [center], 2, surface)
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    tags = {"body": 1, "top_flat": 2, "bottom_flat": 3}
    gmsh.model.addPhysicalGroup(2, [surface], tags["body"])
    gmsh.model.addPhysicalGroup(1, top_flat, tags["top_flat"])
    gmsh.model.addPhysicalGroup(1, bottom_flat, tags["bottom_flat"])
    return tags, (cx, cy), (cx, cy + flat_y)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default=os.path.join(root, "data", "brazilian_disk_elastic.toml"))
    ap.add_argument("--element-size", type=float, default=None,
                    help="mesh size cap in m (default: the scene's mesh.element_size)")
    ap.add_argument("--json", help="also write the timers and results to this JSON file")
    ap.add_argument("--mumps-ordering", type=int, default=None,
                    help="MUMPS ICNTL(7), the fill-reducing ordering (0 AMD, 2 AMF, 3 SCOTCH, "
                    "4 PORD, 5 METIS, 6 QAMD, 7 automatic; default: PETSc's default, automatic)")
    ap.add_argument("--view", action="store_true",
                    help="print PETSc's KSPView after the solve (MUMPS's settings and statistics)")
    args = ap.parse_args()
    p = scene_problem(args.scene, args.element_size)

    t_process = time.perf_counter()
    import gmsh
    import numpy as np
    import ufl
    from mpi4py import MPI
    from petsc4py import PETSc
    import dolfinx
    from dolfinx import fem, mesh as dmesh
    import dolfinx.fem.petsc
    from dolfinx.io import gmshio
    t_imports = time.perf_counter() - t_process
    comm = MPI.COMM_WORLD
    if comm.size != 1:
        sys.exit("run on one MPI rank: the timers and the centre check are serial")

    timers = {}
    clock = time.perf_counter
    t_start = clock()

    # Meshing.
    t = clock()
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.Verbosity", 1)
    gmsh.model.add("disk")
    tags, center_xy, top_xy = draw_disk(gmsh, p)
    gmsh.model.mesh.generate(2)
    timers["meshing"] = clock() - t

    # Import.
    t = clock()
    domain, cell_tags, facet_tags = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=2)
    timers["import"] = clock() - t
    gmsh.finalize()

    # Function space, forms, restraints.
    t = clock()
    V = fem.VectorFunctionSpace(domain, ("Lagrange", 1))
    E, nu, th = p["young"], p["poisson"], p["thickness"]
    mu = E / (2.0 * (1.0 + nu))
    lam = 2.0 * mu * nu / (1.0 - nu)  # plane stress: 2 lambda mu / (lambda + 2 mu)
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)

    def eps(w):
        return ufl.sym(ufl.grad(w))

    def sigma(w):
        return 2.0 * mu * eps(w) + lam * ufl.tr(eps(w)) * ufl.Identity(2)

    n = ufl.FacetNormal(domain)
    ds = ufl.Measure("ds", domain=domain, subdomain_data=facet_tags)
    a_ufl = th * ufl.inner(sigma(u), eps(v)) * ufl.dx
    L_ufl = sum(-p["pressure"][name] * th * ufl.dot(n, v) * ds(tags[name])
                for name in ("top_flat", "bottom_flat"))
    t_jit = clock()
    a, L = fem.form(a_ufl), fem.form(L_ufl)
    jit = clock() - t_jit

    tdim = domain.topology.dim
    domain.topology.create_connectivity(0, tdim)

    def vertex_at(xy):
        found = dmesh.locate_entities(
            domain, 0, lambda x: np.isclose(x[0], xy[0], rtol=0, atol=1e-12)
            & np.isclose(x[1], xy[1], rtol=0, atol=1e-12))
        if len(found) != 1:
            sys.exit(f"expected one mesh node at {xy}, found {len(found)}")
        return found

    center_v, top_v = vertex_at(center_xy), vertex_at(top_xy)
    zero2 = np.zeros(2, dtype=PETSc.ScalarType)
    bcs = [fem.dirichletbc(zero2, fem.locate_dofs_topological(V, 0, center_v), V),
           fem.dirichletbc(PETSc.ScalarType(0.0),
                           fem.locate_dofs_topological(V.sub(0), 0, top_v), V.sub(0))]
    timers["setup"] = clock() - t
    timers["jit"] = jit

    # Sparsity pattern, then assembly.
    t = clock()
    A = fem.petsc.create_matrix(a)
    b = fem.petsc.create_vector(L)
    timers["pattern"] = clock() - t
    t = clock()
    A.zeroEntries()
    fem.petsc.assemble_matrix(A, a, bcs=bcs)
    A.assemble()
    with b.localForm() as b_local:
        b_local.set(0.0)
    fem.petsc.assemble_vector(b, L)
    fem.petsc.apply_lifting(b, [a], bcs=[bcs])
    b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    fem.petsc.set_bc(b, bcs)
    timers["assembly"] = clock() - t
    A.setOption(PETSc.Mat.Option.SYMMETRIC, True)
    A.setOption(PETSc.Mat.Option.SPD, True)

    # KSP preonly + Cholesky by MUMPS.
    ksp = PETSc.KSP().create(comm)
    ksp.setOperators(A)
    ksp.setType("preonly")
    pc = ksp.getPC()
    pc.setType("cholesky")
    pc.setFactorSolverType("mumps")
    if args.mumps_ordering is not None:  # read by PETSc when MUMPS is initialized, in KSPSetUp
        PETSc.Options()["mat_mumps_icntl_7"] = args.mumps_ordering
    PETSc.Log.begin()
    t = clock()
    ksp.setUp()
    timers["ksp_setup"] = clock() - t
    timers["analysis"] = PETSc.Log.Event("MatCholFctrSym").getPerfInfo()["time"]
    timers["factorization"] = PETSc.Log.Event("MatCholFctrNum").getPerfInfo()["time"]
    uh = fem.Function(V)
    t = clock()
    ksp.solve(b, uh.vector)
    timers["solve"] = clock() - t
    uh.x.scatter_forward()
    timers["total"] = clock() - t_start
    reason = ksp.getConvergedReason()
    if reason < 0:
        sys.exit(f"KSP failed: converged reason {reason}")

    # Checks: the centre's nodal sigma_xx and the mean uy of the top flat.
    x_dofs = V.tabulate_dof_coordinates()[:, :2]
    cell_dofs = V.dofmap.cell_dofs
    u_arr = uh.x.array.reshape(-1, 2)
    D = E / (1.0 - nu * nu) * np.array([[1.0, nu, 0.0], [nu, 1.0, 0.0], [0.0, 0.0, (1.0 - nu) / 2]])
    s_sum, w_sum = np.zeros(3), 0.0
    for c in domain.topology.connectivity(0, tdim).links(center_v[0]):
        d = cell_dofs(c)
        (x1, y1), (x2, y2), (x3, y3) = x_dofs[d]
        area2 = (x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1)
        dN = np.array([[y2 - y3, y3 - y1, y1 - y2], [x3 - x2, x1 - x3, x2 - x1]]) / area2
        grad = u_arr[d].T @ dN.T  # grad[i, j] = d u_i / d x_j
        strain = np.array([grad[0, 0], grad[1, 1], grad[0, 1] + grad[1, 0]])
        s_sum += abs(area2) / 2 * (D @ strain)
        w_sum += abs(area2) / 2
    sxx_center = s_sum[0] / w_sum
    top_flat_dofs = fem.locate_dofs_topological(V, tdim - 1, facet_tags.find(tags["top_flat"]))
    uy_top_flat = float(np.mean(u_arr[top_flat_dofs, 1]))  # rockdd's probe "top": a plain mean

    factor = pc.getFactorMatrix()
    info = {
        "element_size": p["element_size"],
        "triangles": domain.topology.index_map(tdim).size_local,
        "nodes": domain.topology.index_map(0).size_local,
        "equations": V.dofmap.index_map.size_local * V.dofmap.index_map_bs,
        "sxx_center": sxx_center,
        "uy_top_flat": uy_top_flat,
        "timers": timers,
        "python_imports": t_imports,
        "dolfinx": dolfinx.__version__,
        "petsc": ".".join(str(x) for x in PETSc.Sys.getVersion()),
        "factor_solver": pc.getFactorSolverType(),
        "mumps_ordering_used": factor.getMumpsInfog(7),  # 0 AMD, 2 AMF, 3 SCOTCH, 4 PORD, 5 METIS
        "mumps_factor_entries": factor.getMumpsInfog(29),
        "mumps_flops": factor.getMumpsRinfog(3),
        "blas_kernels": blas_kernels(),
    }
    print(f"DOLFINx {info['dolfinx']}, PETSc {info['petsc']}, factor: {info['factor_solver']} "
          f"Cholesky; {info['triangles']} triangles, {info['nodes']} nodes, "
          f"{info['equations']} equations, element_size {p['element_size']:g} m; MUMPS ordering "
          f"{info['mumps_ordering_used']} (INFOG(7)), {info['mumps_factor_entries']:,} entries in "
          f"the factor, {info['mumps_flops']:.3g} flops")
    for key in ("meshing", "import", "setup", "jit", "pattern", "assembly", "analysis",
                "factorization", "ksp_setup", "solve", "total"):
        print(f"  {key:14s} {timers[key]:9.4f} s")
    print(f"  sigma_xx at the centre: {sxx_center:.9e} Pa; mean uy of the top flat's nodes: "
          f"{uy_top_flat:.9e} m")
    if args.view:
        ksp.view()
    if args.json:
        with open(args.json, "w") as f:
            json.dump(info, f, indent=2)


if __name__ == "__main__":
    main()
