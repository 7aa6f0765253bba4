// The Python module `rockdd`: the installed C++ API (include/rockdd/rockdd.hpp) through
// pybind11. Fields are read-only NumPy views of the engine's arrays whose base is the
// Simulation, so the Simulation outlives every view taken of it.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdlib>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rockdd/rockdd.hpp"

namespace py = pybind11;
using namespace rockdd::api;

namespace {

/// The Python exception classes, made once at import.
struct Exceptions {
  py::object error, bad_input, run_failed;
};

Exceptions& exceptions() {
  static Exceptions e;
  return e;
}

/// A read-only array of `rows` x `width` values over `data`, kept alive by `owner`.
template <class T>
py::array view(std::span<const T> data, py::ssize_t width, const py::object& owner) {
  const py::ssize_t rows = static_cast<py::ssize_t>(data.size()) / width;
  py::array_t<T> out =
      width == 1 ? py::array_t<T>({rows}, {static_cast<py::ssize_t>(sizeof(T))}, data.data(), owner)
                 : py::array_t<T>({rows, width},
                                  {static_cast<py::ssize_t>(width * sizeof(T)),
                                   static_cast<py::ssize_t>(sizeof(T))},
                                  data.data(), owner);
  // The engine's own memory: a write would change the model behind the engine's back.
  out.attr("setflags")(py::arg("write") = false);
  return out;
}

/// summary_json as a dict.
py::object parse_json(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

/// The settings of a run or an ensemble from keyword arguments; None is no folder.
RunSettings settings_of(const std::optional<std::string>& out_dir, int threads, bool frames) {
  RunSettings s;
  s.out_dir = out_dir.value_or("");
  s.threads = threads;
  s.write_frames = frames;
  return s;
}

/// Runs `sim` with the GIL released; `on_step` (a Python callable or None) gets the GIL back
/// for each step. An exception in the callback stops the run and is raised once it returns.
RunOutcome run_simulation(Simulation& sim, const RunSettings& settings, const py::object& on_step) {
  std::optional<py::error_already_set> raised;
  StepCallback callback;
  if (!on_step.is_none())
    callback = [&](const Step& step) {
      py::gil_scoped_acquire gil;
      try {
        const py::object result = on_step(step);
        // None (no return statement) carries on: only an explicit false value stops.
        return result.is_none() || py::bool_(result);
      } catch (py::error_already_set& e) {
        raised.emplace(std::move(e));
        return false;
      }
    };
  RunOutcome outcome;
  {
    py::gil_scoped_release released;
    outcome = sim.run(settings, callback);
  }
  if (raised) throw std::move(*raised);
  return outcome;
}

/// An ensemble's table as {column: values}, in mc.csv's order: seed (uint64), status (str),
/// the value columns (float64, NaN where mc.csv has an empty cell), reason (str).
py::dict table_dict(const EnsembleTable& table) {
  const std::size_t n = table.rows.size();
  py::array_t<std::uint64_t> seeds(static_cast<py::ssize_t>(n));
  py::list status, reason;
  for (std::size_t r = 0; r < n; ++r) {
    seeds.mutable_at(static_cast<py::ssize_t>(r)) = table.rows[r].seed;
    status.append(table.rows[r].status);
    reason.append(table.rows[r].reason);
  }
  py::dict out;
  out["seed"] = seeds;
  out["status"] = status;
  for (std::size_t c = 0; c < table.columns.size(); ++c) {
    py::array_t<double> values(static_cast<py::ssize_t>(n));
    for (std::size_t r = 0; r < n; ++r) {
      const std::string& cell = table.rows[r].cells[c];
      // mc.csv's cells print doubles to round trip: strtod gives the engine's value back.
      values.mutable_at(static_cast<py::ssize_t>(r)) =
          cell.empty() ? std::nan("") : std::strtod(cell.c_str(), nullptr);
    }
    out[py::str(table.columns[c])] = values;
  }
  out["reason"] = reason;
  return out;
}

}  // namespace

PYBIND11_MODULE(rockdd, m) {
  m.doc() = "rockdd, a FEM/DDA rock-fracture engine: scenes, simulations and ensembles.";
  m.attr("__version__") = version();
  m.def(
      "version", [] { return std::string(version()); }, "The rockdd version string.");

  Exceptions& e = exceptions();
  e.error = py::reinterpret_steal<py::object>(
      PyErr_NewExceptionWithDoc("rockdd.Error", "Any rockdd error.", PyExc_RuntimeError, nullptr));
  // A bad scene is a bad argument: callers that catch ValueError catch it too.
  e.bad_input = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "rockdd.BadInput", "A bad scene or file; the message names the file, key and expectation.",
      py::make_tuple(e.error, py::handle(PyExc_ValueError)).ptr(), nullptr));
  e.run_failed = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "rockdd.RunFailed", "A numerical failure.", e.error.ptr(), nullptr));
  m.attr("Error") = e.error;
  m.attr("BadInput") = e.bad_input;
  m.attr("RunFailed") = e.run_failed;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& error) {
      const Exceptions& x = exceptions();
      const py::object& type = error.kind() == ErrorKind::bad_input    ? x.bad_input
                               : error.kind() == ErrorKind::run_failed ? x.run_failed
                                                                       : x.error;
      PyErr_SetString(type.ptr(), error.what());
    }
  });

  py::class_<Scene>(m, "Scene", "A read and validated scene.")
      .def_static("from_file", &Scene::from_file, py::arg("path"),
                  py::arg("overrides") = std::vector<std::string>{},
                  "Reads a scene file after overrides ('key.path=value', as rockdd run --set).")
      .def_static(
          "from_string",
          [](const std::string& text, const std::vector<std::string>& overrides,
             const std::string& name) { return Scene::from_string(text, overrides, name); },
          py::arg("text"), py::arg("overrides") = std::vector<std::string>{},
          py::arg("name") = "scene.toml",
          "Reads TOML text; name stands for the file in messages and anchors relative paths.")
      .def_property_readonly("name", &Scene::name, "The scene's [scene].name.");

  py::class_<Step>(m, "Step", "What a step callback sees after each committed step.")
      .def_readonly("step", &Step::step)
      .def_readonly("time", &Step::time)
      .def_readonly("dt", &Step::dt)
      .def_readonly("end_time", &Step::end_time)
      .def("__repr__", [](const Step& s) {
        return "Step(step=" + std::to_string(s.step) + ", time=" + std::to_string(s.time) + ")";
      });

  py::class_<RunOutcome>(m, "RunOutcome", "How a run ended, and its summary.")
      .def_readonly("ok", &RunOutcome::ok)
      .def_readonly("reason", &RunOutcome::reason)
      .def_readonly("summary_json", &RunOutcome::summary_json)
      .def_property_readonly(
          "summary", [](const RunOutcome& o) { return parse_json(o.summary_json); },
          "summary.json as a dict.");

  py::class_<Simulation>(m, "Simulation", "One simulation of a scene; it runs once.")
      .def(py::init<const Scene&>(), py::arg("scene"), "Meshes the scene and builds its model.")
      .def(
          "run",
          [](Simulation& sim, const std::optional<std::string>& out_dir, int threads,
             bool write_frames, const py::object& on_step) {
            return run_simulation(sim, settings_of(out_dir, threads, write_frames), on_step);
          },
          py::arg("out_dir") = py::none(), py::arg("threads") = 0, py::arg("write_frames") = false,
          py::arg("on_step") = py::none(),
          "Runs to the end, or until on_step(step) returns False. A numerical failure is an "
          "outcome (ok False), not an exception.")
      .def_property_readonly("num_nodes", &Simulation::num_nodes)
      .def_property_readonly("num_elements", &Simulation::num_elements)
      .def(
          "positions",
          [](const py::object& self) {
            return view(self.cast<const Simulation&>().positions(), 2, self);
          },
          "Reference positions, (nodes, 2), a read-only view.")
      .def(
          "displacements",
          [](const py::object& self) {
            return view(self.cast<const Simulation&>().displacements(), 2, self);
          },
          "Displacements, (nodes, 2), a read-only view.")
      .def(
          "stresses",
          [](const py::object& self) {
            return view(self.cast<const Simulation&>().stresses(), 3, self);
          },
          "Element stresses sxx, syy, sxy in Pa, (elements, 3), a read-only view.")
      .def(
          "damage",
          [](const py::object& self) {
            return view(self.cast<const Simulation&>().damage(), 1, self);
          },
          "Element damage in [0, 1], (elements,), a read-only view.")
      .def(
          "element_blocks",
          [](const py::object& self) {
            return view(self.cast<const Simulation&>().element_blocks(), 1, self);
          },
          "Block id of each element, (elements,) int32, a read-only view.")
      .def(
          "connectivity",
          [](const py::object& self) {
            return view(self.cast<const Simulation&>().connectivity(), 3, self);
          },
          "Node ids of each element, counter-clockwise, (elements, 3) int32, a read-only view.");

  m.def(
      "run_ensemble",
      [](const Scene& scene, long realizations, std::optional<std::uint64_t> first_seed,
         const std::optional<std::string>& out_dir, int threads, bool write_frames) {
        EnsembleTable table;
        {
          py::gil_scoped_release released;
          table = run_ensemble(scene, realizations, first_seed,
                               settings_of(out_dir, threads, write_frames));
        }
        return table_dict(table);
      },
      py::arg("scene"), py::arg("realizations"), py::arg("first_seed") = py::none(),
      py::arg("out_dir") = py::none(), py::arg("threads") = 0, py::arg("write_frames") = false,
      "Runs the seeds in this process, as rockdd mc's workers do; returns mc.csv's table as "
      "{column: values}. The peaks.* columns need out_dir (NaN without).");
}
