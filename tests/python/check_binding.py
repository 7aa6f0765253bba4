#!/usr/bin/python3
"""The Python module `rockdd` against the command line and the C++ API; one case per run.

    check_binding.py CASE --rockdd BUILD/bin/rockdd --source SOURCE_DIR --work DIR

with the module on PYTHONPATH. Exits non-zero, with the reason, when the case fails."""
import argparse
import ctypes
import csv
import math
import os
import shutil
import subprocess
import sys

import numpy as np

import rockdd

CASES = {}


def case(function):
    CASES[function.__name__] = function
    return function


def expect(condition, message):
    if not condition:
        raise AssertionError(message)


def blas_kernels_of_this_process():
    """The kernel set OpenBLAS runs in this process, the one the module's runs use."""
    openblas = ctypes.CDLL("libopenblas.so.0")
    openblas.openblas_get_corename.restype = ctypes.c_char_p
    return openblas.openblas_get_corename().decode()


def cli(args, work):
    """`rockdd ARGS` in `work`; its output when it succeeds. The command line runs the kernel
    set of this process's OpenBLAS: where OpenBLAS falls back to Prescott, `rockdd` would
    otherwise start itself again with Haswell's (docs/scene.md, "Environment"), whose
    factorizations round differently, and these cases compare one engine, bit for bit."""
    env = dict(os.environ, OPENBLAS_CORETYPE=blas_kernels_of_this_process())
    done = subprocess.run([ARGS.rockdd] + args, cwd=work, capture_output=True, text=True,
                          env=env)
    expect(done.returncode == 0, f"rockdd {' '.join(args)} exited {done.returncode}:\n"
                                 f"{done.stdout}{done.stderr}")
    return done.stdout + done.stderr


@case
def displacements_equal_the_command_lines_vtu(work):
    """The cantilever's displacement field through the module equals the last VTU frame of
    `rockdd run` on the same scene. Tolerance: none (bitwise): both run the same engine on one
    thread, and the VTU stores Float64 raw; a difference would be a different computation."""
    sys.path.insert(0, os.path.join(ARGS.source, "tools"))
    from rockdd_results import last_frame  # noqa: E402

    scene_file = os.path.join(ARGS.source, "data", "cantilever_model_1.toml")
    cli(["run", scene_file, "--threads", "1", "--set", "output.every=1", "--out", "cli",
         "--quiet"], work)
    mesh, _ = last_frame(os.path.join(work, "cli", "cantilever-model-1"))

    sim = rockdd.Simulation(rockdd.Scene.from_file(scene_file))
    outcome = sim.run(threads=1)
    expect(outcome.ok, f"the run failed: {outcome.reason}")
    u = sim.displacements()
    expect(u.shape == (sim.num_nodes, 2), f"displacements shape {u.shape}")
    expect(not u.flags.writeable and not u.flags.owndata, "displacements not a read-only view")
    vtu_u = mesh["point_data"]["displacement"]
    expect(vtu_u.shape == (sim.num_nodes, 3), f"VTU displacement shape {vtu_u.shape}")
    difference = np.max(np.abs(vtu_u[:, :2] - u))
    print(f"max |u_vtu - u_python| = {difference:.3g} m of max |u| = {np.max(np.abs(u)):.6g} m")
    expect(difference == 0.0, "the module's displacements differ from the VTU frame's")
    expect(np.array_equal(mesh["cell_data"]["stress"], sim.stresses()),
           "the module's stresses differ from the VTU frame's")
    expect(np.array_equal(mesh["triangles"], sim.connectivity()), "connectivity differs")
    summary = outcome.summary
    expect(isinstance(summary, dict) and summary["status"] == "ok", f"summary {summary}")


@case
def fields_are_read_only_views_that_keep_the_simulation_alive(work):
    """Every field is a view (no copy) of the engine's array, read-only, whose base keeps the
    Simulation alive after the last name for it is gone."""
    scene = rockdd.Scene.from_file(os.path.join(ARGS.source, "data", "cantilever_model_1.toml"))
    sim = rockdd.Simulation(scene)
    sim.run(threads=1)
    fields = {"positions": (sim.num_nodes, 2), "displacements": (sim.num_nodes, 2),
              "stresses": (sim.num_elements, 3), "damage": (sim.num_elements,),
              "element_blocks": (sim.num_elements,), "connectivity": (sim.num_elements, 3)}
    views = {}
    for name, shape in fields.items():
        a = getattr(sim, name)()
        expect(a.shape == shape, f"{name}: shape {a.shape}, expected {shape}")
        expect(not a.flags.writeable, f"{name} is writeable")
        expect(not a.flags.owndata, f"{name} owns its data: a copy")
        # Two takes share the engine's memory.
        expect(np.shares_memory(a, getattr(sim, name)()), f"{name}: two takes share no memory")
        try:
            a[0] = 0
            raise AssertionError(f"{name}: a write went through")
        except ValueError:
            pass
        views[name] = a
    expect(views["element_blocks"].dtype == np.int32 and views["connectivity"].dtype == np.int32,
           "integer fields are not int32")
    expect(views["connectivity"].max() < sim.num_nodes, "connectivity beyond the nodes")
    expected = views["displacements"].copy()
    del sim, scene
    import gc
    gc.collect()
    # The view holds the Simulation: its memory is still the run's.
    expect(np.array_equal(views["displacements"], expected), "a view outlived its Simulation")
    print("six read-only views, alive after the Simulation's last name went")


@case
def bad_scene_raises_bad_input_with_the_readers_message(work):
    with open(os.path.join(ARGS.source, "data", "cantilever_model_1.toml")) as f:
        text = f.read().replace("young = 10e9", "young = -1")
    try:
        rockdd.Scene.from_string(text, name="bad_cantilever.toml")
        raise AssertionError("a negative Young's modulus was accepted")
    except rockdd.BadInput as e:
        message = str(e)
        print(f"BadInput: {message}")
        for part in ("bad_cantilever.toml", "young", "-1"):
            expect(part in message, f"the message lacks '{part}': {message}")
        expect(isinstance(e, ValueError) and isinstance(e, rockdd.Error), "BadInput's bases")
    try:
        rockdd.Scene.from_file("/nonexistent/scene.toml")
        raise AssertionError("a missing file was accepted")
    except rockdd.BadInput as e:
        expect("/nonexistent/scene.toml" in str(e), f"the message lacks the file: {e}")
    # An override of an unknown key names it.
    try:
        rockdd.Scene.from_file(os.path.join(ARGS.source, "data", "cantilever_model_1.toml"),
                               ["mesh.no_such_key=1"])
        raise AssertionError("an unknown key was accepted")
    except rockdd.BadInput as e:
        expect("no_such_key" in str(e), f"the message lacks the key: {e}")


@case
def step_callback_stops_the_run(work):
    scene = rockdd.Scene.from_file(os.path.join(ARGS.source, "data", "uniaxial_compression.toml"),
                                   ["mesh.divisions=[10, 20]"])
    sim = rockdd.Simulation(scene)
    seen = []

    def on_step(step):
        seen.append((step.step, step.time, sim.displacements().copy()))
        return step.step < 3  # False after the third step stops the run

    outcome = sim.run(threads=1, on_step=on_step)
    expect(outcome.ok, f"a stopped run is ok, got {outcome.reason}")
    expect([s[0] for s in seen] == [1, 2, 3], f"steps seen: {[s[0] for s in seen]}")
    expect(outcome.summary.get("stopped_by_caller") is True, f"summary {outcome.summary}")
    expect(outcome.summary["steps"] == 3, f"summary steps {outcome.summary['steps']}")
    expect(not np.array_equal(seen[0][2], seen[2][2]), "the callback saw no field change")
    # An exception in the callback stops the run and comes out of run().
    sim2 = rockdd.Simulation(scene)

    def failing(step):
        raise KeyError("from the callback")

    try:
        sim2.run(threads=1, on_step=failing)
        raise AssertionError("the callback's exception was lost")
    except KeyError:
        pass
    # A Simulation runs once.
    try:
        sim.run()
        raise AssertionError("a second run was accepted")
    except rockdd.Error:
        pass
    print(f"stopped after steps {[s[0] for s in seen]}")


@case
def ensemble_table_equals_rockdd_mc(work):
    """Three seeds of the coarse compression specimen, to its first 0.05 s, through the module
    and through `rockdd mc`: every column but wall time equal, bitwise."""
    scene_file = os.path.join(ARGS.source, "data", "uniaxial_compression.toml")
    overrides = ["mesh.divisions=[10, 20]", "time.end=0.05"]
    sets = [a for o in overrides for a in ("--set", o)]
    cli(["mc", scene_file, "--realizations", "3", "--first-seed", "7", "--threads", "1",
         "--jobs", "1", "--out", "mc", "--quiet"] + sets, work)
    with open(os.path.join(work, "mc", "uniaxial-compression", "mc.csv")) as f:
        rows = list(csv.DictReader(f))
    table = rockdd.run_ensemble(rockdd.Scene.from_file(scene_file, overrides), 3, first_seed=7,
                                out_dir=os.path.join(work, "module"), threads=1)
    expect(list(table) == list(rows[0]), f"columns {list(table)} against mc.csv's {list(rows[0])}")
    expect(table["seed"].dtype == np.uint64 and list(table["seed"]) == [7, 8, 9],
           f"seeds {table['seed']}")
    compared = 0
    for column in table:
        for i, row in enumerate(rows):
            got = table[column][i]
            if column in ("status", "reason"):
                expect(got == row[column], f"{column} of seed {row['seed']}: {got!r}")
            elif column != "wall_seconds":
                want = float(row[column]) if row[column] else math.nan
                same = (math.isnan(want) and math.isnan(got)) or float(got) == want
                expect(same, f"{column} of seed {row['seed']}: {got!r} against mc.csv {want!r}")
                compared += 1
    expect(table["status"] == ["ok"] * 3, f"status {table['status']}")
    expect(not math.isnan(table["peaks.top.fy"][0]), "no peak force with an out_dir")
    print(f"{compared} numbers of 3 realizations equal to mc.csv's")


def main():
    global ARGS
    parser = argparse.ArgumentParser()
    parser.add_argument("case", choices=sorted(CASES))
    parser.add_argument("--rockdd", required=True, type=os.path.abspath)
    parser.add_argument("--source", required=True, type=os.path.abspath)
    parser.add_argument("--work", required=True)
    ARGS = parser.parse_args()
    work = os.path.abspath(os.path.join(ARGS.work, ARGS.case))
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    try:
        CASES[ARGS.case](work)
    except AssertionError as e:
        print(f"FAILED: {e}", file=sys.stderr)
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
