// session.cpp: see session.h.
#include "session.h"

#include <cstdio>
#include <cstdlib>
#include <string>

VulkanContextOptions contextOptions(const Options &options)
{
    VulkanContextOptions vo;
    vo.validate = options.validate;
    if (const char *d = std::getenv("VIEWER_DEVICE")) vo.deviceSubstring = d;
    return vo;
}

Session::Session(const Options &options, const Scene &s, VulkanContext &context)
    : opt(options), ctx(context), scene(frameScene(s))
{
    orbit0 = orbit = initialOrbit(s);
    light.point = opt.pointLight;
    light.angle = radians(opt.lightAngleDeg);
    light.moving = opt.lightMotion;
    light.hitDistance = opt.hitDistance;
    light.hardLight = opt.hardLight;
    light.lightPosition = opt.lightPosition;
    // Light from the side of the starting view (100 degrees around from the camera), so that the shadows fall where
    // the camera sees them whatever the scene.
    light.azimuth = orbit.yaw + radians(opt.lightAzimuthDeg);
    light.elevation = radians(opt.lightElevationDeg);
    hybrid = opt.hybrid;
    hybridAvailable = opt.hybrid || (!opt.headless && hybridUnsupported(opt).empty());
}

void Session::createRenderer()
{
    RendererSettings rs;
    rs.width = opt.width, rs.height = opt.height;
    rs.sceneRadius = scene.radius;
    rs.preset = opt.preset;
    rs.settingOverrides = opt.settings;
    rs.packedGbuffer = opt.packedGbuffer;
    rs.normalDetail = opt.normalDetail;
    rs.normalDetailDnsrOnly = opt.normalDetailDnsrOnly;
    rs.rays = opt.rays;
    rs.checkerboard = opt.checkerboard;
    rs.lights = opt.lights;
    rs.sceneCenter = scene.center;
    HybridSettings &h = rs.hybrid;
    h.enabled = hybridAvailable;
    h.cascades = opt.cascades, h.cascadeSize = opt.cascadeSize, h.taps = opt.taps, h.tileCutoff = opt.tileCutoff;
    h.blockerOffset = opt.blockerOffset < 0 ? -1.0f : opt.blockerOffset * scene.radius;
    h.reverseRays = opt.reverseRays;
    renderer.create(ctx, *scene.scene, rs);
    std::printf("viewer: %s on %s, %ux%u, %u triangles, BVH %u nodes (depth %u), push descriptors %s\n",
                opt.scene.c_str(), ctx.properties.deviceName, opt.width, opt.height, renderer.triangles,
                renderer.bvhNodes, renderer.bvhDepth, ctx.pushDescriptorEnabled ? "on" : "off");
    if (hybridAvailable)
        std::printf("viewer: hybrid shadows %s: %u cascades of %u^2, %u taps, tile cut-off %u, blocker offset %s%s\n",
                    hybrid ? "on" : "available (key C)", opt.cascades, renderer.cascadeSize(), opt.taps, opt.tileCutoff,
                    opt.blockerOffset < 0 ? "2 texels" : std::to_string(rs.hybrid.blockerOffset).c_str(),
                    opt.reverseRays ? ", reversed rays" : "");
}
