# Runs a cantilever scene through rockdd's Python module and prints the tip's vertical
# displacement; then stops a compression run after three steps and runs a small ensemble.
#   PYTHONPATH=~/.local/lib/python3/dist-packages python3 example.py data/cantilever_model_1.toml
import sys

import numpy as np

import rockdd

scene = rockdd.Scene.from_file(sys.argv[1])
sim = rockdd.Simulation(scene)
outcome = sim.run(threads=1)  # no out_dir: no files, the summary comes anyway
if not outcome.ok:
    sys.exit(f"run failed: {outcome.reason}")
X, u = sim.positions(), sim.displacements()  # (nodes, 2), read-only views, no copies
tip = np.argmin(np.hypot(X[:, 0] - 0.04, X[:, 1] - 0.005))  # the middle of the free end
print(f"tip uy = {u[tip, 1]:.17g}")
print(f"{outcome.summary['steps']} step(s), max stress "
      f"{np.abs(sim.stresses()).max() / 1e6:.1f} MPa", file=sys.stderr)

# A TOML string with overrides, a step callback that stops the run, and a bad key.
text = """
[scene]
name = "small-compression"
analysis = "quasi-static"
[time]
dt = 0.00625
end = 0.1
[mesh]
shape = "rectangle"
size = [0.075, 0.15]
divisions = [10, 20]
[[material]]
body = "body"
density = 2700.0
young = 50e9
poisson = 0.2
cohesion = 100e6
friction_angle = 20.0
tensile_strength = 7e6
homogeneity = 1.5
heterogeneous = ["young", "tensile_strength", "cohesion"]
[[boundary]]
on = "bottom"
fix = ["x", "y"]
[[boundary]]
on = "top"
velocity_y = -2e-5
[[probe]]
name = "top"
on = "top"
fields = ["fy"]
"""
compression = rockdd.Scene.from_string(text, ["material.0.seed=3"])
sim = rockdd.Simulation(compression)
outcome = sim.run(on_step=lambda step: step.step < 3)  # False stops the run, ok
print(f"stopped after {outcome.summary['steps']} steps, damaged elements: "
      f"{np.count_nonzero(sim.damage())}", file=sys.stderr)
try:
    rockdd.Scene.from_string(text, ["material.0.young=-1"])
except rockdd.BadInput as e:  # a ValueError; the message names the key and what was expected
    print(f"refused: {e}", file=sys.stderr)

# Two realizations (seeds 3 and 4), one after the other in this process: mc.csv's table.
table = rockdd.run_ensemble(compression, 2, first_seed=3, threads=1)
print(f"seeds {list(table['seed'])}: {table['status']}, steps {table['steps']}", file=sys.stderr)
