// Where the light's transmittance volume (light_transmittance.comp) keeps the pigment's box: one
// texel a cell of the box from the image's low corner, or, for a box wider than the image along an
// axis, the whole image along it. The march (smoke_march.glsl) and the light's march agree through this.
#ifndef MFX_SMOKE_LIGHT_GLSL
#define MFX_SMOKE_LIGHT_GLSL

// Texels of an image of `size` texels that a box of `boxCells` cells (whole numbers) takes.
vec3 lightTexels(vec3 boxCells, vec3 size) {
    return min(boxCells, size);
}

#endif
