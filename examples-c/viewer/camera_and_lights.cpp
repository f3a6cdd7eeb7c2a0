// camera_and_lights.cpp: see camera_and_lights.h.
#include "camera_and_lights.h"

#include <algorithm>

Orbit initialOrbit(const Scene &scene)
{
    Vec3 center = (scene.boundsMin + scene.boundsMax) * 0.5f;
    float radius = std::max(length(scene.boundsMax - scene.boundsMin) * 0.5f, 1e-3f);
    Orbit o;
    if (scene.hasCamera) {
        Vec3 eye = scene.cameraToWorld.transformPoint({0, 0, 0});
        Vec3 forward = normalize(scene.cameraToWorld.transformPoint({0, 0, -1}) - eye);
        if (isFinite(eye) && length(forward) > 0.5f) {
            // Orbit around the point of the view axis nearest to the scene's centre.
            float along = std::max(dot(center - eye, forward), 0.05f * radius);
            o.target = eye + forward * along;
            Vec3 back = eye - o.target;
            o.distance = length(back);
            o.pitch = std::asin(std::clamp(back.y / o.distance, -1.0f, 1.0f));
            o.yaw = std::atan2(back.x, back.z);
            o.fovY = scene.cameraYFov;
            return o;
        }
    }
    o.target = center;
    o.fovY = 0.8f;
    // 0.7 of the distance at which the bounding sphere would just fit: most scenes are flatter than a sphere.
    o.distance = 0.7f * radius / std::sin(o.fovY * 0.5f);
    o.pitch = radians(30.0f);
    o.yaw = radians(35.0f);
    return o;
}

SceneFrame frameScene(const Scene &scene)
{
    return {&scene, (scene.boundsMin + scene.boundsMax) * 0.5f,
            std::max(length(scene.boundsMax - scene.boundsMin) * 0.5f, 1e-3f)};
}

FrameInput makeFrame(const SceneFrame &sf, const Orbit &orbit, const LightState &light, uint32_t width, uint32_t height)
{
    FrameInput in;
    in.eye = orbit.eye();
    in.viewMatrix = lookAt(in.eye, orbit.target, {0, 1, 0});
    // A far plane behind the whole scene from anywhere on the orbit, and a near plane at 1% of the orbit distance:
    // with standard depth, a much closer near plane squeezes every receiver's depth against 1 and costs dnsr's
    // depth tests their precision (see reprojection() in vec_math.h).
    float zNear = std::max(orbit.distance * 0.01f, sf.radius * 1e-4f);
    float zFar = orbit.distance + 2.5f * sf.radius;
    in.projection = perspectiveVulkan(orbit.fovY, float(width) / float(height), zNear, zFar);
    in.pointLight = light.point;
    in.hitDistance = light.hitDistance;
    in.hardLight = light.hardLight && light.angle == 0.0f;
    in.lightPosition = light.lightPosition;
    if (light.point) {
        // A sphere at half the scene radius from the centre; the angular radius is as seen from the centre. dnsr's
        // penumbra guidance takes one angular diameter for all receivers: the one seen from the centre, 2 asin(r / D)
        // (receivers farther from the light see it smaller, nearer ones larger).
        float dist = 0.5f * sf.radius;
        for (uint32_t i = 0; i < kMaxLights; i++) in.lights[i] = sf.center + light.direction(i) * dist;
        in.lightSize = dist * std::tan(light.angle);
        in.lightAngularSize = 2.0f * std::asin(std::min(in.lightSize / dist, 1.0f));
    } else {
        // Rays leave within a cone of half-angle light.angle (tan of it scales the disk): diameter 2 * angle.
        for (uint32_t i = 0; i < kMaxLights; i++) in.lights[i] = light.direction(i);
        in.lightSize = std::tan(light.angle);
        in.lightAngularSize = 2.0f * light.angle;
    }
    return in;
}
