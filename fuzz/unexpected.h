// What a fuzz target does with an exception its reader's contract does not allow
// (std::bad_alloc from a size taken on trust, std::length_error, a logic_error...):
// report it and abort, so that libFuzzer (and the replay driver) record a crash.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <typeinfo>

namespace dermis::fuzz {

[[noreturn]] inline void unexpected_exception(const char* target, const std::exception& e) {
  std::fprintf(stderr, "%s: unexpected %s: %s\n", target, typeid(e).name(), e.what());
  std::abort();
}

}  // namespace dermis::fuzz
