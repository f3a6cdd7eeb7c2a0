/*
 * custom_gbuffer.c: dnsr reading an engine's own G-buffer encoding through shader callbacks.
 *
 * The engine stores linear view depth (R32_SFLOAT) and octahedral normals (RG16_SNORM). Instead of converting them
 * into dnsr's default inputs (hardware depth, normals decoded as rgb * mul + add) every frame, it compiles dnsr's
 * passes against its own callbacks file (engine_callbacks.glsl, compiled by build_shaders.sh from the installed
 * shader sources) and hands dnsr the SPIR-V at creation (DnsrContextCreateInfo::pShaderOverrides). The part to
 * copy is load_overrides() and the two create-info lines in main(); the Vulkan plumbing comes from the C API
 * tests' host (capi-tests/host.c).
 *
 * To show the result is dnsr's, it runs the same scene twice, side by side: the engine's encoding through its
 * callbacks, and the same depth and normals converted to dnsr's default formats through the default callbacks.
 * Every output pixel of every frame must agree within 2/255, what an 8-bit output shows: the two paths decode the
 * same normals and depths through different float arithmetic (about 1e-7 apart), and where one of dnsr's decisions
 * lies that close to its threshold the two take different sides. On lavapipe over 6 frames they agreed within
 * 1.4e-5 before classification's local window followed the pixel's own surface and within 9.8e-4 since, in one
 * cluster of pixels; not through the window's normal codes (the same with codes of scale 63 instead of 511), but
 * where the window's fixed-point row sums put values (with a scale of 1024 instead of 2048: within 1.5e-5).
 * Both contexts record GPU timestamps: it prints what
 * the engine's callbacks cost against the default ones (median over the frames after the first quarter).
 *
 *   build_shaders.sh <prefix>/share/dnsr/shaders spv && custom_gbuffer spv [--size WxH] [--frames N] [--no-layers]
 */
#include "host.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NEAR 0.5f
#define FAR 50.0f

static Host host;
static uint32_t W = 64, H = 40, FRAMES = 6;

/* The engine's compiled variants, read from `dir`: the names are dnsr's (dnsr_get_shader_variants). */
static const char *const kVariants[] = {"tile_classification_r32f", "filter", "filter_later", "filter_final_r32f",
                                        "filter_later_final_r32f"};
#define VARIANT_COUNT (sizeof kVariants / sizeof kVariants[0])
static uint32_t *code[VARIANT_COUNT];
static DnsrShaderOverride overrides[VARIANT_COUNT];

static void load_overrides(const char *dir)
{
    for (size_t i = 0; i < VARIANT_COUNT; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s.spv", dir, kVariants[i]);
        FILE *f = fopen(path, "rb");
        CHECK(f != NULL, "cannot open %s (run build_shaders.sh first)", path);
        fseek(f, 0, SEEK_END);
        long size = ftell(f);
        fseek(f, 0, SEEK_SET);
        CHECK(size > 0 && size % 4 == 0, "%s: %ld bytes is not SPIR-V", path, size);
        code[i] = malloc((size_t)size);
        CHECK(code[i] && fread(code[i], 1, (size_t)size, f) == (size_t)size, "cannot read %s", path);
        fclose(f);
        overrides[i] = (DnsrShaderOverride){kVariants[i], code[i], (size_t)size};
    }
}

/* A Vulkan-convention perspective (depth 0 near, 1 far) as projectionInverse, column-major: clip (x, y, d, 1) to
 * the view point (x / sx, y / sy, -1, (d + A) / B) with A = far / (near - far), B = near far / (near - far). */
static void projection_inverse(float m[16])
{
    float sx = 1.2f, sy = 1.2f * W / H, A = FAR / (NEAR - FAR), B = NEAR * FAR / (NEAR - FAR);
    memset(m, 0, 16 * sizeof(float));
    m[0] = 1.0f / sx, m[5] = 1.0f / sy, m[3 * 4 + 2] = -1.0f, m[2 * 4 + 3] = 1.0f / B, m[3 * 4 + 3] = A / B;
}

/* Distance along the view axis of clip (ndc, d): what the engine stores as linear depth. */
static float view_distance(const float m[16], float x, float y, float d)
{
    float z = m[0 * 4 + 2] * x + m[1 * 4 + 2] * y + m[2 * 4 + 2] * d + m[3 * 4 + 2];
    float w = m[0 * 4 + 3] * x + m[1 * 4 + 3] * y + m[2 * 4 + 3] * d + m[3 * 4 + 3];
    return -z / w;
}

static float clampf(float v, float lo, float hi) { return v < lo ? lo : (v > hi ? hi : v); }

/* Octahedral encoding of a unit normal into RG16_SNORM, and its exact decode (what the shader computes). */
static void oct_encode(const float n[3], int16_t out[2])
{
    float s = fabsf(n[0]) + fabsf(n[1]) + fabsf(n[2]);
    float x = n[0] / s, y = n[1] / s;
    if (n[2] < 0) {
        float ox = (1 - fabsf(y)) * (x >= 0 ? 1 : -1), oy = (1 - fabsf(x)) * (y >= 0 ? 1 : -1);
        x = ox, y = oy;
    }
    out[0] = (int16_t)lrintf(clampf(x, -1, 1) * 32767.0f), out[1] = (int16_t)lrintf(clampf(y, -1, 1) * 32767.0f);
}

static void oct_decode(const int16_t e[2], float n[3])
{
    float x = fmaxf(e[0] / 32767.0f, -1.0f), y = fmaxf(e[1] / 32767.0f, -1.0f);
    n[0] = x, n[1] = y, n[2] = 1 - fabsf(x) - fabsf(y);
    float t = fmaxf(-n[2], 0.0f);
    n[0] += n[0] >= 0 ? -t : t, n[1] += n[1] >= 0 ? -t : t;
    float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) n[k] /= len;
}

static int compare_floats(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* GPU milliseconds of the most recent completed frame of `ctx`. */
static float frame_ms(DnsrContext ctx)
{
    DnsrPassTimings t;
    memset(&t, 0, sizeof t);
    t.sType = DNSR_STRUCTURE_TYPE_PASS_TIMINGS;
    DNSR_CHECK(dnsr_context_get_timings(ctx, &t));
    return t.totalMs;
}

int main(int argc, char **argv)
{
    HostOptions options = {0};
    CHECK(argc >= 2, "usage: custom_gbuffer SPV_DIR [--size WxH] [--frames N] [--no-layers] (see build_shaders.sh)");
    for (int i = 2; i < argc; i++) {
        if (!strcmp(argv[i], "--size") && i + 1 < argc) {
            CHECK(sscanf(argv[++i], "%ux%u", &W, &H) == 2 && W >= 8 && H >= 8, "--size wants WxH, 8 or more");
        } else if (!strcmp(argv[i], "--frames") && i + 1 < argc) {
            FRAMES = (uint32_t)atoi(argv[++i]);
            CHECK(FRAMES >= 2, "--frames wants 2 or more");
        } else {
            CHECK(!strcmp(argv[i], "--no-layers"), "unknown argument %s", argv[i]);
            options.noLayers = true; /* a machine without the validation layer (timing runs) */
        }
    }
    load_overrides(argv[1]);
    host_create_with(&host, &options);

    /* The scene: a floor tilting away from the camera under a bumpy normal field, sky in the top rows. */
    float pinv[16];
    projection_inverse(pinv);
    size_t n = (size_t)W * H;
    float *hwDepth = malloc(n * sizeof(float)), *linear = malloc(n * sizeof(float));
    float(*worldNormal)[4] = malloc(n * sizeof *worldNormal);
    int16_t(*octNormal)[2] = malloc(n * sizeof *octNormal);
    float *zeros = calloc(2 * n, sizeof(float));
    uint32_t *bits = malloc(((W + 7) / 8) * ((H + 3) / 4) * sizeof(uint32_t));
    float *msPlain = malloc(FRAMES * sizeof(float)), *msEngine = malloc(FRAMES * sizeof(float));
    CHECK(hwDepth && linear && worldNormal && octNormal && zeros && bits && msPlain && msEngine, "out of memory");
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            uint32_t i = y * W + x;
            float nx = (x + 0.5f) / W * 2 - 1, ny = (y + 0.5f) / H * 2 - 1;
            float z = 3.0f + 4.0f * (1.0f - ny); /* distance along the view axis */
            int sky = y < 4;
            float A = FAR / (NEAR - FAR), B = NEAR * FAR / (NEAR - FAR);
            hwDepth[i] = sky ? 1.0f : B / z - A;
            linear[i] = sky ? 0.0f : view_distance(pinv, nx, ny, hwDepth[i]);
            float n[3] = {0.35f * sinf(5.0f * nx), 0.35f * cosf(4.0f * ny), 1.0f};
            float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int k = 0; k < 3; k++) n[k] /= len;
            oct_encode(n, octNormal[i]);
            oct_decode(octNormal[i], worldNormal[i]); /* the default path sees the same normals */
            worldNormal[i][3] = 0;
        }

    HostImage mask, depthDefault, depthEngine, normalsDefault, normalsEngine, velocity, outDefault, outEngine;
    VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    uint32_t tx = (W + 7) / 8, ty = (H + 3) / 4;
    host_image_create(&host, &mask, VK_FORMAT_R32_UINT, tx, ty, read);
    host_image_create(&host, &depthDefault, VK_FORMAT_R32_SFLOAT, W, H, read);
    host_image_create(&host, &depthEngine, VK_FORMAT_R32_SFLOAT, W, H, read);
    host_image_create(&host, &normalsDefault, VK_FORMAT_R32G32B32A32_SFLOAT, W, H, read);
    host_image_create(&host, &normalsEngine, VK_FORMAT_R16G16_SNORM, W, H, read);
    host_image_create(&host, &velocity, VK_FORMAT_R32G32_SFLOAT, W, H, read);
    host_image_create(&host, &outDefault, VK_FORMAT_R32_SFLOAT, W, H, VK_IMAGE_LAYOUT_GENERAL);
    host_image_create(&host, &outEngine, VK_FORMAT_R32_SFLOAT, W, H, VK_IMAGE_LAYOUT_GENERAL);
    host_upload(&host, &depthDefault, hwDepth, n * sizeof(float));
    host_upload(&host, &depthEngine, linear, n * sizeof(float));
    host_upload(&host, &normalsDefault, worldNormal, n * sizeof *worldNormal);
    host_upload(&host, &normalsEngine, octNormal, n * sizeof *octNormal);
    host_upload(&host, &velocity, zeros, 2 * n * sizeof(float));

    /* The engine's context: the same create info plus its compiled variants. */
    DnsrContextCreateInfo info = host_create_info(&host, W, H);
    info.flags |= DNSR_CONTEXT_CREATE_ENABLE_TIMESTAMPS;
    DnsrContext plain = NULL, engine = NULL;
    DNSR_CHECK(dnsr_context_create(&info, &plain));
    info.shaderOverrideCount = (uint32_t)VARIANT_COUNT;
    info.pShaderOverrides = overrides;
    DNSR_CHECK(dnsr_context_create(&info, &engine));

    HostBuffer readback;
    host_buffer_create(&host, &readback, 2 * W * H * sizeof(float));
    float worst = 0;
    for (uint32_t frame = 0; frame < FRAMES; frame++) {
        uint32_t s = 977u * (frame + 1);
        for (uint32_t i = 0; i < tx * ty; i++) s = s * 1664525u + 1013904223u, bits[i] = s ^ (s >> 11);
        host_upload(&host, &mask, bits, (size_t)tx * ty * sizeof(uint32_t));

        VkCommandBuffer cmd = host_begin(&host);
        host_cmd_full_barrier(cmd);
        DnsrShadowsDispatch d = host_dispatch(cmd, &mask, &depthDefault, &velocity, &normalsDefault, &outDefault);
        memcpy(d.projectionInverse, pinv, sizeof pinv);
        memcpy(d.viewProjectionInverse, pinv, sizeof pinv); /* camera at the origin, looking down -z */
        d.frameIndex = frame;
        DNSR_CHECK(dnsr_shadows_record(plain, &d));
        /* The engine hands dnsr its own images; the callbacks decode them (the unpack knobs are not used). */
        d.depth = host_image_desc(&depthEngine);
        d.normals = host_image_desc(&normalsEngine);
        d.output = host_image_desc(&outEngine);
        DNSR_CHECK(dnsr_shadows_record(engine, &d));
        host_cmd_copy(cmd, &outDefault, &readback, 0, false);
        host_cmd_copy(cmd, &outEngine, &readback, W * H * sizeof(float), false);
        host_cmd_host_read_barrier(cmd);
        host_submit(&host, cmd);

        msPlain[frame] = frame_ms(plain), msEngine[frame] = frame_ms(engine);
        const float *a = readback.mapped, *b = a + n;
        for (uint32_t i = 0; i < n; i++) {
            float diff = fabsf(a[i] - b[i]);
            worst = diff > worst ? diff : worst;
            CHECK(diff <= 2.0f / 255.0f, "frame %u pixel (%u, %u): default callbacks %.7f, engine callbacks %.7f", frame,
                  i % W, i / W, a[i], b[i]);
        }
    }
    host_expect_clean(&host, "custom_gbuffer");
    uint32_t skip = FRAMES / 4, timed = FRAMES - skip;
    qsort(msPlain + skip, timed, sizeof(float), compare_floats);
    qsort(msEngine + skip, timed, sizeof(float), compare_floats);
    printf("custom_gbuffer: %s, %ux%u, %u frames, engine callbacks (linear depth, octahedral RG16 normals) = "
           "default path within %.2g (bound 2/255); GPU ms (median of %u): default %.3f, engine callbacks %.3f\n",
           host.deviceName, W, H, FRAMES, worst, timed, msPlain[skip + timed / 2], msEngine[skip + timed / 2]);

    DNSR_CHECK(dnsr_context_destroy(engine));
    DNSR_CHECK(dnsr_context_destroy(plain));
    host_buffer_destroy(&host, &readback);
    HostImage *images[] = {&mask, &depthDefault, &depthEngine, &normalsDefault, &normalsEngine, &velocity, &outDefault, &outEngine};
    for (size_t i = 0; i < sizeof images / sizeof images[0]; i++) host_image_destroy(&host, images[i]);
    host_destroy(&host);
    for (size_t i = 0; i < VARIANT_COUNT; i++) free(code[i]);
    free(hwDepth), free(linear), free(worldNormal), free(octNormal), free(zeros), free(bits), free(msPlain), free(msEngine);
    return 0;
}
