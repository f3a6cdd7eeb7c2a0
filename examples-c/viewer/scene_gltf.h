// scene_gltf.h: loads a glTF 2.0 scene into a flat list of world-space triangles.
//
// Supported: meshes with POSITION (float VEC3) and optional NORMAL (float VEC3), indexed (u8/u16/u32) or not,
// triangle primitives, node transforms (matrix or TRS) through the default scene's node hierarchy, the base
// colour factor of materials, and the first perspective camera of the scene (as the starting view). Everything
// else (textures, skins, morph targets, animations, sparse accessors) is ignored or refused with a message.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "vec_math.h"

// Thrown for a file that cannot be loaded or that the viewer does not support; the message is one line that
// names the file and the offending element (the viewer prints it and exits with status 2).
struct SceneError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Scene {
    // Three entries per triangle, in world space.
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;
    // One packed RGBA8 base colour per triangle.
    std::vector<uint32_t> albedo;
    Vec3 boundsMin, boundsMax;
    // The scene's first perspective camera, if it has one: world transform (camera looks down its -z) and yfov.
    bool hasCamera = false;
    Mat4 cameraToWorld;
    float cameraYFov = 0.8f;
    std::string name;

    size_t triangleCount() const { return positions.size() / 3; }
};

// Throws SceneError (never crashes or blocks) for a path that is not a regular file (directory, FIFO, device),
// a missing or malformed file, glTF other than 2.0 (1.0 is named as such), an extension the viewer lacks that
// the file requires (Draco and meshopt compression are named), an accessor that does not fit its buffer view,
// indices out of range, non-finite positions or transforms, or a scene without triangles.
Scene loadGltfScene(const std::string &path);
