// Included by both GLSL and C++: the type names GLSL uses, mapped to GLM on the C++ side, so a
// struct declared once under shaders/shared/ is the same struct on both sides. C++ checks each
// struct's size and offsets with static_assert next to its declaration, inside #ifdef __cplusplus.
//
// Layout rules: only 4-byte scalars, vec4/uvec4/ivec4 and mat4 (and vec2 at 8-byte offsets);
// no vec3 members, whose std140/std430 alignment differs from C++.
#ifndef MFX_SHARED_COMMON_H
#define MFX_SHARED_COMMON_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#define MFX_SHARED_BEGIN                                                                           \
    namespace mfx::shared {                                                                        \
    using uint = std::uint32_t;                                                                    \
    using vec2 = glm::vec2;                                                                        \
    using vec4 = glm::vec4;                                                                        \
    using uvec4 = glm::uvec4;                                                                      \
    using ivec4 = glm::ivec4;                                                                      \
    using mat4 = glm::mat4;
#define MFX_SHARED_END }
#define MFX_CHECK_LAYOUT(type, member, offset)                                                     \
    static_assert(offsetof(mfx::shared::type, member) == (offset),                                 \
                  #type "." #member " must sit at byte " #offset)
#define MFX_CHECK_SIZE(type, size)                                                                 \
    static_assert(sizeof(mfx::shared::type) == (size), #type " must be " #size " bytes")
#else
#define MFX_SHARED_BEGIN
#define MFX_SHARED_END
#endif

#endif
