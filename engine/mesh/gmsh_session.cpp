#include "engine/mesh/gmsh_session.hpp"

#include <gmsh.h>
#include <omp.h>

#include <exception>
#include <string>
#include <utility>
#include <vector>

namespace rockdd {

namespace {

std::mutex& gmsh_mutex() {
  static std::mutex mutex;
  return mutex;
}

// Options are global in Gmsh, not per model: a .geo file that sets one of these would otherwise
// change every later mesh of the process. Gmsh 4.8 has no API call to restore all defaults.
constexpr const char* kRestoredOptions[] = {
    "General.AbortOnError",
    "General.NumThreads",
    "Geometry.Tolerance",
    "Geometry.AutoCoherence",
    "Mesh.MeshSizeMax",
    "Mesh.MeshSizeMin",
    "Mesh.MeshSizeFactor",
    "Mesh.MeshSizeFromPoints",
    "Mesh.MeshSizeFromCurvature",
    "Mesh.MeshSizeExtendFromBoundary",
    "Mesh.Algorithm",
    "Mesh.RecombineAll",
    "Mesh.RecombinationAlgorithm",
    "Mesh.SubdivisionAlgorithm",
    "Mesh.ElementOrder",
    "Mesh.SecondOrderLinear",
    "Mesh.SecondOrderIncomplete",
    "Mesh.Smoothing",
    "Mesh.Renumber",
    "Mesh.RandomFactor",
    "Mesh.RandomSeed",
    "Mesh.ScalingFactor",
    "Mesh.SaveAll",
    "Mesh.MshFileVersion",
    "Mesh.Binary",
    "Mesh.IgnorePeriodicity",
    "Mesh.AnisoMax",
    "Mesh.AllowSwapAngle",
    "Mesh.Optimize",
};

/// The default value of each restored option that this Gmsh knows.
std::vector<std::pair<std::string, double>> read_option_defaults() {
  std::vector<std::pair<std::string, double>> defaults;
  for (const char* name : kRestoredOptions) {
    try {
      double value = 0.0;
      gmsh::option::getNumber(name, value);
      defaults.emplace_back(name, value);
    } catch (...) {  // not an option of this Gmsh version
    }
  }
  return defaults;
}

void make_quiet() {
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 1);  // errors only
}

/// Gmsh's "Error: " prefix, removed.
std::string without_level(const std::string& line) {
  const std::string prefix = "Error: ";
  return line.rfind(prefix, 0) == 0 ? line.substr(prefix.size()) : line;
}

/// Logs Gmsh's errors for the lifetime of this object, instead of throwing them.
class ErrorLog {
 public:
  ErrorLog() {
    gmsh::option::getNumber("General.AbortOnError", abort_on_error_);
    gmsh::logger::start();
    gmsh::option::setNumber("General.AbortOnError", 0);
  }
  ~ErrorLog() {
    try {
      gmsh::option::setNumber("General.AbortOnError", abort_on_error_);
      gmsh::logger::stop();
    } catch (...) {  // nothing useful to do while unwinding
    }
  }
  ErrorLog(const ErrorLog&) = delete;
  ErrorLog& operator=(const ErrorLog&) = delete;
  std::string first_error() const {
    std::vector<std::string> lines;
    gmsh::logger::get(lines);
    for (const auto& line : lines)
      if (line.rfind("Error", 0) == 0) return without_level(line);
    return "";
  }

 private:
  double abort_on_error_ = 2.0;
};

}  // namespace

std::string first_gmsh_error(const std::function<void()>& step) {
  ErrorLog log;
  try {
    step();
  } catch (const std::string& text) {
    return text;
  } catch (const std::exception& error) {
    return error.what();
  }
  return log.first_error();
}

GmshSession::GmshSession() : lock_(gmsh_mutex()), openmp_threads_(omp_get_max_threads()) {
  // Guarded by the mutex. Gmsh is never finalized: it lives as long as the process.
  static bool initialized = false;
  static std::vector<std::pair<std::string, double>> defaults;
  if (!initialized) {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    make_quiet();
    defaults = read_option_defaults();
    initialized = true;
  }
  for (const auto& [name, value] : defaults) gmsh::option::setNumber(name, value);
  make_quiet();
  gmsh::clear();
}

GmshSession::~GmshSession() {
  try {
    gmsh::clear();
  } catch (...) {  // nothing useful to do about a failed clear while unwinding
  }
  omp_set_num_threads(openmp_threads_);
}

}  // namespace rockdd
