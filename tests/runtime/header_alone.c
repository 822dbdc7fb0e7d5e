/* The public header compiles on its own as C99 with every warning an error (tests/CMakeLists.txt
 * builds this file; a warning fails the build). */
#include <motionfx/motionfx.h>

uint32_t motionfxHeaderAloneC(void);
uint32_t motionfxHeaderAloneC(void) {
    MfxRuntimeDesc desc = {0};
    desc.structVersion = MFX_RUNTIME_DESC_VERSION;
    return desc.structVersion + (uint32_t)MFX_SUCCESS;
}
