// The public header compiles on its own as C++ with every warning an error (tests/CMakeLists.txt
// builds this file; a warning fails the build).
#include <motionfx/motionfx.h>

uint32_t motionfxHeaderAloneCpp();
uint32_t motionfxHeaderAloneCpp() {
    MfxRuntimeDesc desc{};
    desc.structVersion = MFX_RUNTIME_DESC_VERSION;
    return desc.structVersion + uint32_t(MFX_SUCCESS);
}
