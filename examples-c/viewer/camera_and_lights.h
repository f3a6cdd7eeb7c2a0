// camera_and_lights.h: where the viewer looks from and where its lights are: an orbit camera around the scene, the
// lights turned about its up axis, and the camera matrices and light parameters of one frame for the renderer.
#pragma once

#include <cmath>

#include "renderer.h"
#include "scene_gltf.h"
#include "vec_math.h"

constexpr float kPi = 3.14159265358979f;
inline float radians(float degrees) { return degrees * kPi / 180.0f; }

// An orbit camera: looks at `target` from `distance` away, at angles yaw (around +y) and pitch (above the
// horizon). The scene's own camera, when it has one, gives the starting orbit.
struct Orbit {
    Vec3 target;
    float yaw = 0, pitch = 0, distance = 1, fovY = 0.8f;

    Vec3 eye() const
    {
        return target + Vec3{std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw)} *
                            distance;
    }
};

Orbit initialOrbit(const Scene &scene);

// The lights: light 0 as the options place it, light i the same turned i x 100 degrees about the up axis (same
// elevation, angle and kind), so that every light's shadows fall elsewhere, in any scene, with any options.
struct LightState {
    bool point = false;
    float azimuth = 0, elevation = radians(50.0f);  // light 0's
    float angle = radians(3.0f);  // angular radius
    bool moving = false;
    bool hitDistance = true;  // penumbra guidance for dnsr
    bool hardLight = true;    // tell dnsr when the light has no size (angle 0)
    bool lightPosition = true;  // tell dnsr where the light is

    Vec3 direction(uint32_t light) const
    {
        float a = azimuth + radians(100.0f) * float(light);
        return {std::cos(elevation) * std::sin(a), std::sin(elevation), std::cos(elevation) * std::cos(a)};
    }
};

// The scene and its bounding sphere: the orbit's start, the clip planes and the point light's distance scale with it.
struct SceneFrame {
    const Scene *scene = nullptr;
    Vec3 center;
    float radius = 1;
};

SceneFrame frameScene(const Scene &scene);

// The frame description for the renderer: camera matrices and light.
FrameInput makeFrame(const SceneFrame &sf, const Orbit &orbit, const LightState &light, uint32_t width,
                     uint32_t height);
