#pragma once
// How the engine's exceptions become the API's one Error, at every entry of the API.
#include <exception>
#include <new>

#include "engine/common/errors.hpp"
#include "rockdd/rockdd.hpp"

namespace rockdd::api {

/// Calls `f`, turning InputError and RunFailure into Error of their kind and any other
/// std::exception into ErrorKind::error; an Error passes through unchanged.
template <class F>
decltype(auto) translate_errors(F&& f) {
  try {
    return f();
  } catch (const Error&) {
    throw;
  } catch (const InputError& e) {
    throw Error(ErrorKind::bad_input, e.what());
  } catch (const RunFailure& e) {
    throw Error(ErrorKind::run_failed, e.what());
  } catch (const std::exception& e) {
    throw Error(ErrorKind::error, e.what());
  }
}

}  // namespace rockdd::api
