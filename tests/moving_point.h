// A character made for the simulation tests: one joint carrying one vertex, sliding along +x
// at 1.5 m/s, 0.6 m above the floor (clip "slide", 2 s).
#pragma once

#include "core/anim/character.h"

namespace mfx::test {

inline anim::Character movingPoint() {
    anim::Character c;
    c.name = "point";
    anim::Node root;
    root.name = "root";
    c.nodes.push_back(root);
    anim::Skin skin;
    skin.name = "skin";
    skin.joints = {0};
    skin.inverseBind = {glm::mat4(1.0f)};
    c.skins.push_back(skin);
    anim::Mesh mesh;
    mesh.name = "dot";
    anim::Primitive p;
    p.positions = {glm::vec3(0.0f)};
    p.normals = {glm::vec3(0, 1, 0)};
    p.joints = {glm::uvec4(0)};
    p.weights = {glm::vec4(1, 0, 0, 0)};
    p.skin = 0;
    mesh.primitives.push_back(p);
    c.meshes.push_back(mesh);
    anim::Clip clip;
    clip.name = "slide";
    clip.duration = 2.0f;
    anim::Channel ch;
    ch.node = 0;
    ch.path = anim::Path::Translation;
    ch.times = {0.0f, 2.0f};
    ch.values = {glm::vec4(-1.5f, 0.6f, 0.0f, 0.0f), glm::vec4(1.5f, 0.6f, 0.0f, 0.0f)};
    clip.channels.push_back(ch);
    c.clips.push_back(clip);
    return c;
}

} // namespace mfx::test
