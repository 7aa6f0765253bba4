#pragma once
// What a harness accepts from the engine: an InputError that names where the input came from.
// Anything else leaving the call (another exception, a crash, a sanitizer report, a hang, a
// memory blow-up) is a finding, so it is left for libFuzzer to report.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "engine/common/errors.hpp"

namespace rockdd::fuzz {

/// Runs `step`; returns normally if it succeeds or throws an InputError whose `where` starts
/// with `file` (the CLI's exit status 2 with a message naming the file). An InputError that
/// does not name the file is a finding too: the user could not tell which input is wrong.
template <class Step>
void expect_success_or_input_error(const std::string& file, Step&& step) {
  try {
    step();
  } catch (const InputError& error) {
    if (error.where().rfind(file, 0) != 0 || error.expected().empty()) {
      std::fprintf(stderr, "InputError without the file or what was expected: %s\n", error.what());
      std::abort();
    }
  }
}

}  // namespace rockdd::fuzz
