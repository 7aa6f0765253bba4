#include "engine/mesh/gmsh_session.hpp"

#include <gmsh.h>
#include <omp.h>

#include <exception>
#include <string>
#include <vector>

namespace rockdd {

namespace {

std::mutex& gmsh_mutex() {
  static std::mutex mutex;
  return mutex;
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

GmshSession::GmshSession(int threads)
    : lock_(gmsh_mutex()), openmp_threads_(omp_get_max_threads()) {
  // A fresh Gmsh for every mesh (0.4 ms): options are global in Gmsh, and its model state
  // outlives gmsh::clear(). Kept alive across meshes, the interior nodes of a transfinite
  // rectangle moved by up to 1e-15 of their coordinates between the first mesh of a process
  // and later ones, so a mesh depended on what the process had meshed before.
  gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
  make_quiet();
  if (threads > 1) gmsh::option::setNumber("General.NumThreads", threads);
}

GmshSession::~GmshSession() {
  try {
    gmsh::finalize();
  } catch (...) {  // nothing useful to do about a failed finalize while unwinding
  }
  omp_set_num_threads(openmp_threads_);
}

}  // namespace rockdd
