// libFuzzer entry for one target (AFEMP_FUZZ_TARGET, its index in afemp::fuzz::targets): built
// with clang's -fsanitize=fuzzer,address,undefined by -DAFEMP_FUZZ=ON (tests/CMakeLists.txt).
// Uncaught exceptions other than core::InputError abort, which libFuzzer reports as a crash.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  afemp::fuzz::feed(afemp::fuzz::targets[AFEMP_FUZZ_TARGET],
                    {reinterpret_cast<const char*>(data), size});
  return 0;
}
