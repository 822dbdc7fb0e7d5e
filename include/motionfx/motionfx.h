/* motionfx: real-time motion effects (speed-lines, trails, smoke) for skinned characters, drawn
 * into a host application's Vulkan frame.
 *
 * The one public header of the motionfx runtime library (find_package(motionfx CONFIG),
 * target motionfx::runtime). Plain C, usable from C and C++; the only other header it needs is
 * <vulkan/vulkan.h>. docs/embedding.md shows every call in order.
 *
 * The host owns the Vulkan instance, physical device, device and queue; a runtime borrows them
 * (it never destroys them) and checks that the device was created with what motionfx needs
 * (mfxRequiredDeviceExtensions, and the features listed in docs/embedding.md), naming each thing
 * that is missing. A runtime holds no global state: several can live in one process, on one
 * device or on several.
 *
 * Threads: calls on one runtime (and on what it made) must not overlap. Runtimes on different
 * queues are independent; runtimes given the same queue must not be called at the same time
 * either. A call that submits to or waits on the runtime's queue says so: the host must not use
 * that queue on another thread meanwhile (Vulkan's external synchronisation of queues).
 */
#ifndef MOTIONFX_MOTIONFX_H
#define MOTIONFX_MOTIONFX_H

#include <stddef.h>
#include <stdint.h>
#include <vulkan/vulkan.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#define MFX_API __attribute__((visibility("default")))
#else
#define MFX_API
#endif

/* The library's version (also motionfx_VERSION in CMake). */
#define MFX_VERSION_MAJOR 0
#define MFX_VERSION_MINOR 2
#define MFX_VERSION_PATCH 0
/* The version the library was built as: MFX_VERSION_MAJOR * 10000 + MINOR * 100 + PATCH. A host
 * may compare it with the header's to catch a mismatched install. */
MFX_API uint32_t mfxVersion(void);

typedef enum MfxResult {
    MFX_SUCCESS = 0,
    MFX_ERROR_INVALID_ARGUMENT = 1,   /* a null pointer, an unknown struct version, a bad value */
    MFX_ERROR_UNSUPPORTED_DEVICE = 2, /* the device lacks a feature or extension motionfx needs */
    MFX_ERROR_VULKAN = 3,             /* a Vulkan call failed (out of memory, device lost) */
    MFX_ERROR_INTERNAL = 4,
    MFX_ERROR_SCENE = 5 /* a scene file, its text or its character is wrong (the message says
                           what and where) */
} MfxResult;

/* A short name for a result ("MFX_ERROR_UNSUPPORTED_DEVICE"); never null. */
MFX_API const char* mfxResultName(MfxResult result);

/* Receives the message of every failed call: one or more lines saying what is wrong and where.
 * `message` lives until the callback returns. */
typedef void (*MfxMessageCallback)(MfxResult result, const char* message, void* user);

/* The device extensions motionfx needs the host's device to have enabled: writes up to
 * `capacity` names into `names` (static strings) and returns how many there are in all. */
MFX_API uint32_t mfxRequiredDeviceExtensions(const char** names, uint32_t capacity);

typedef struct MfxRuntime_T* MfxRuntime;

#define MFX_RUNTIME_DESC_VERSION 1

typedef struct MfxRuntimeDesc {
    uint32_t structVersion; /* MFX_RUNTIME_DESC_VERSION */
    VkInstance instance;    /* created with apiVersion 1.3 or later */
    VkPhysicalDevice physicalDevice;
    VkDevice device;
    /* A family with graphics and compute, and one of its queues: one-shot uploads while effects
     * are made are submitted there and waited for. */
    uint32_t queueFamilyIndex;
    VkQueue queue;
    /* What the device was created with: its VkDeviceCreateInfo's feature chain (a
     * VkPhysicalDeviceFeatures2 with VkPhysicalDeviceVulkan11Features, ...12Features and
     * ...13Features linked after it, in any order; other structs are skipped) and its enabled
     * extensions. Vulkan cannot be asked which features a device enabled, so the host says. */
    const VkPhysicalDeviceFeatures2* enabledFeatures;
    uint32_t enabledExtensionCount;
    const char* const* enabledExtensionNames;
    /* Optional: where the messages of failed calls go (none: they are kept for
     * mfxRuntimeLastError only, and a failed mfxCreateRuntime says only its result). */
    MfxMessageCallback messageCallback;
    void* messageUser;
} MfxRuntimeDesc;

/* Makes a runtime on the host's device. MFX_ERROR_UNSUPPORTED_DEVICE when the device lacks what
 * motionfx needs; the message names every missing feature and extension, one a line. */
MFX_API MfxResult mfxCreateRuntime(const MfxRuntimeDesc* desc, MfxRuntime* runtime);

/* Waits for the runtime's queue to be idle, then frees everything the runtime made, effects the
 * host has not destroyed included (their handles are invalid afterwards). The host's objects
 * stay. Null is allowed. */
MFX_API void mfxDestroyRuntime(MfxRuntime runtime);

/* The message of the runtime's last failed call ("" when none failed); valid until the next call
 * on the runtime. */
MFX_API const char* mfxRuntimeLastError(MfxRuntime runtime);

/* The name of the device the runtime runs on (valid while the runtime lives). */
MFX_API const char* mfxRuntimeDeviceName(MfxRuntime runtime);

/* --- Effects ------------------------------------------------------------------------------ */

/* The effects of one scene (the files in docs/scenes; README.md, "Scene files"): its character, its
 * trail effects (speed-lines, blur volumes, particles, ...) and its smoke grids, with the GPU
 * resources they simulate in. */
typedef struct MfxEffects_T* MfxEffects;

#define MFX_EFFECTS_DESC_VERSION 1

typedef struct MfxEffectsDesc {
    uint32_t structVersion; /* MFX_EFFECTS_DESC_VERSION */
    /* Exactly one of the two: a scene file's path, or a scene's JSON text. */
    const char* sceneFile;
    const char* sceneJson;
    /* With sceneJson: the folder its relative paths (character.source) are read against; null:
     * the working folder. A scene file's relative paths are read against its own folder. */
    const char* baseFolder;
} MfxEffectsDesc;

/* Reads the scene and its character (the built-in fighter or a glTF file) and makes its effects
 * on the runtime's device; uploads are submitted to the runtime's queue and waited for.
 * MFX_ERROR_SCENE names what in the scene is wrong, and where. */
MFX_API MfxResult mfxCreateEffects(MfxRuntime runtime, const MfxEffectsDesc* desc,
                                   MfxEffects* effects);

/* Waits for the runtime's queue to be idle, then frees the effects. Null is allowed. */
MFX_API void mfxDestroyEffects(MfxEffects effects);

#define MFX_EFFECTS_INFO_VERSION 1

typedef struct MfxEffectsInfo {
    uint32_t structVersion; /* MFX_EFFECTS_INFO_VERSION, set by the caller */
    uint32_t effectCount;   /* the scene's effects, in its order */
    uint32_t smokeGrids;    /* smoke effects with equal grid settings share one grid */
    uint32_t frameCount;    /* the frames the scene's clip (or output.frames) lasts */
    float framesPerSecond;  /* the scene's output.fps: the simulation's frame rate */
    float floorHeight;      /* where the scene's stage has its floor (world y) */
} MfxEffectsInfo;

/* Fills `info`, whose structVersion the caller has set. */
MFX_API MfxResult mfxGetEffectsInfo(MfxEffects effects, MfxEffectsInfo* info);

/* The name of effect `index` (the scene's "name", or its kind and index, e.g. "speed_lines#0");
 * null past the last. Valid while the effects live. */
MFX_API const char* mfxEffectName(MfxEffects effects, uint32_t index);

/* --- The character ------------------------------------------------------------------------- */

/* A scene of several characters ("characters") gives these functions its first: the host draws
 * and animates that one; the others play their clips and are drawn by mfxRecordFrame. A scene's
 * hit-stops hold the clips it plays, not the host's own animation. */

/* The scene's character as triangles, for a host that draws it with its own shading and has no
 * animation of its own: every primitive's vertices one after another. */
MFX_API MfxResult mfxGetCharacterMeshSize(MfxEffects effects, uint32_t* vertexCount,
                                          uint32_t* indexCount);

/* The character at scene time `time` (seconds) as the scene animates and places it, in world
 * space: `positions` and `normals` 3 floats a vertex, `indices` a triangle list (3 a triangle),
 * each sized by mfxGetCharacterMeshSize; any may be null (not written). Skinned on the CPU by the
 * same dual quaternion blend as motionfx's own drawing. */
MFX_API MfxResult mfxGetCharacterMesh(MfxEffects effects, double time, float* positions,
                                      float* normals, uint32_t* indices);

/* The character's nodes (its joints and the nodes above them; a glTF file's nodes, in its
 * order): how many there are, and the name of node `index` (null past the last). */
MFX_API uint32_t mfxGetCharacterNodeCount(MfxEffects effects);
MFX_API const char* mfxGetCharacterNodeName(MfxEffects effects, uint32_t index);

/* The world matrix of every node at scene time `time` as the scene's clip poses it (16 floats a
 * node, column-major, before the scene's character.position and facing place it): what
 * MfxFrameDesc.nodeMatrices takes, for a host that animates the character itself and wants a
 * start from the scene's clip. `matrices` holds 16 * mfxGetCharacterNodeCount floats. */
MFX_API MfxResult mfxGetCharacterNodeMatrices(MfxEffects effects, double time, float* matrices);

/* --- One frame ---------------------------------------------------------------------------- */

/* One of the host's images: 2D, one mip level and array layer, single-sampled. */
typedef struct MfxImage {
    VkImage image;
    VkFormat format;
    VkImageLayout layout;      /* the layout it is in when motionfx's commands begin */
    VkImageLayout finalLayout; /* the layout motionfx leaves it in */
} MfxImage;

/* The host's camera, matrices column-major (as GLM and GLSL store them). */
typedef struct MfxCamera {
    float view[16]; /* world to view space, right-handed (the camera looks down -z) */
    /* View to Vulkan's clip space: a perspective projection with depth 0 at the near plane and 1
     * at the far one (as the host's depth image holds it; reversed or infinite depth is refused).
     */
    float projection[16];
    /* 0: clip-space +y points up (glm::perspective as it comes); 1: down (the projection's y
     * already flipped for a viewport of positive height). */
    uint32_t clipYDown;
} MfxCamera;

/* The scene's camera (its "camera" keys, or the one framed on the character) for a picture of
 * `aspect` = width / height, as motionfx render draws from it (clipYDown 0). */
MFX_API MfxResult mfxGetSceneCamera(MfxEffects effects, float aspect, MfxCamera* camera);

#define MFX_FRAME_DESC_VERSION 1

typedef struct MfxFrameDesc {
    uint32_t structVersion; /* MFX_FRAME_DESC_VERSION */
    /* In the recording state, outside any render pass, for the runtime's queue family. */
    VkCommandBuffer commandBuffer;
    /* The scene time, in seconds, from 0 on the first frame; it must not go back. The effects
     * advance at the scene's frame rate (mfxGetEffectsInfo: framesPerSecond), at most one of its
     * frames a call: a call whose time reaches the next frame simulates it, others draw the frame
     * they have again. */
    double time;
    MfxCamera camera;
    uint32_t width, height; /* of both images */
    /* Colour: made with COLOR_ATTACHMENT usage, of a format the device blends into (e.g.
     * VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT). The
     * effects are laid over it as premultiplied colour: out = effects + (1 - coverage) colour. */
    MfxImage colour;
    /* Depth: made with SAMPLED usage, one of VK_FORMAT_D16_UNORM, VK_FORMAT_X8_D24_UNORM_PACK32,
     * VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D32_SFLOAT, VK_FORMAT_D32_SFLOAT_S8_UINT; the host's
     * surfaces hide the effects behind them and the soft effects fade into them. Read only. */
    MfxImage depth;
    /* The effects' own antialiasing: 1, 2, 4 or 8 samples a pixel (fewer where the device has
     * fewer); 0: 4. */
    uint32_t samples;
    /* Optional, the host's animation: the world matrix of every character node at `time`
     * (nodeMatrixCount = mfxGetCharacterNodeCount, 16 floats a node, column-major, in the
     * character's own space: the scene's character.position and facing place it, so leave them
     * at 0 for matrices already in the host's world). Used when the call simulates a frame; the
     * smoke's steps between two frames blend the two poses. Null: the scene's clip poses it. */
    const float* nodeMatrices;
    uint32_t nodeMatrixCount;
} MfxFrameDesc;

/* Records one frame of the effects into the host's command buffer: the scene's next simulation
 * frame when `time` has reached it (its trajectories and smoke steps), then the effects drawn from
 * the host's camera against the host's depth and laid over the host's colour; both images are
 * left in their final layouts. The host submits the command buffer; the commands of the previous
 * mfxRecordFrame on these effects must have finished executing before this call (one frame in
 * flight: wait for its fence first). A call may submit to and wait on the runtime's queue (a
 * sparse smoke grid growing its storage). MFX_ERROR_INVALID_ARGUMENT names the field that is
 * wrong: a depth format motionfx cannot read, a colour format the device cannot blend into, a
 * layout, a camera that is not a perspective one. */
MFX_API MfxResult mfxRecordFrame(MfxEffects effects, const MfxFrameDesc* frame);

#ifdef __cplusplus
}
#endif

#endif /* MOTIONFX_MOTIONFX_H */
