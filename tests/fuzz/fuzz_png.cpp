// libFuzzer harness: a ribbon texture's loading and decoding (tests/fuzz/fuzz_targets.h). Built
// and run by `./build.sh fuzz [seconds]`.
#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    mfx::fuzz::loadTextureInput(std::span<const uint8_t>(data, size));
    return 0;
}
