/// @file The libFuzzer entry point of every fuzz target: the target's input kind is its compile
/// definition STIFFSOFT_FUZZ_INPUT ("scene", "obj", "stl", "msh"; fuzz/CMakeLists.txt). An input
/// that the loader refuses without naming it aborts, so libFuzzer keeps it as a finding.

#include <cstdio>
#include <cstdlib>

#include "fuzz/fuzz_entries.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stiffsoft::fuzz;
  static const InputKind kind = input_kind(STIFFSOFT_FUZZ_INPUT);
  const Outcome outcome = run_input(kind, {data, size});
  if (!is_clear(outcome, input_label(kind))) {
    std::fprintf(stderr, "unclear error (does not name %s): %s\n", input_label(kind).c_str(), outcome.error.c_str());
    std::abort();
  }
  return 0;
}
