/*
 * diagnostics: dnsr_reference_diagnose from C. A frame an engine could have captured (an orthographic camera
 * above a ground plane that moved since the last frame, sky along one edge, normals stored UNORM as rgb * 0.5 +
 * 0.5, motion vectors in uv with prev_uv = uv + v) is reported clean; each mistake migrating engines make is
 * planted alone and must come back as its DNSR_DIAGNOSIS_* kind with a message: motion vectors negated (the
 * FidelityFX 1.2 sign) or at half scale, normals decoded without their unpack, the depth-inverted flag on
 * standard depth and off on reverse-Z, viewProjectionInverse of another camera. Also the count-only call, a
 * capacity smaller than the findings, and bad arguments.
 */
#include "dnsr.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 48
#define H 32

static int failures = 0;
#define EXPECT(cond, ...)                                                                                       \
    do {                                                                                                        \
        if (!(cond)) {                                                                                          \
            printf("%s:%d: FAILED: %s: ", __FILE__, __LINE__, #cond);                                          \
            printf(__VA_ARGS__);                                                                                \
            printf("\n");                                                                                       \
            failures++;                                                                                         \
        }                                                                                                       \
    } while (0)

/* The captured frame: raw texels as the engine stores them. */
typedef struct Capture {
    float depth[W * H];
    float normal[W * H][3];
    float velocity[W * H][2];
} Capture;

static float read_depth(void *user, int32_t x, int32_t y) { return ((Capture *)user)->depth[y * W + x]; }
static void read_normal(void *user, int32_t x, int32_t y, float *rgb) { memcpy(rgb, ((Capture *)user)->normal[y * W + x], 12); }
static void read_velocity(void *user, int32_t x, int32_t y, float *xy) { memcpy(xy, ((Capture *)user)->velocity[y * W + x], 8); }

/* Column-major element (row r, column c). */
#define M(m, r, c) (m)[(c) * 4 + (r)]

/* Orthographic camera looking straight down (-z) from height `height` at (ex, ey), half-extent `s` in x and y,
 * near n, far f; standard depth maps view distance n..f to 0..1, reverse-Z to 1..0. The camera was at
 * (ex - dx, ey - dy) last frame. */
typedef struct Camera {
    float ex, ey, height, s, n, f, dx, dy;
    int inverted;
} Camera;

static void frame_info(const Camera *c, DnsrReferenceFrameInfo *info)
{
    memset(info, 0, sizeof *info);
    info->sType = DNSR_STRUCTURE_TYPE_REFERENCE_FRAME_INFO;
    info->width = W;
    info->height = H;
    info->flags = c->inverted ? DNSR_REFERENCE_DEPTH_INVERTED : 0;
    info->motionVectorScale[0] = info->motionVectorScale[1] = 1.0f;
    info->normalsUnpackMul = 2.0f;
    info->normalsUnpackAdd = -1.0f;
    info->eye[0] = c->ex, info->eye[1] = c->ey, info->eye[2] = c->height;
    info->depthSimilaritySigma = 1.0f;
    /* view distance z = n + depth (f - n), or f - depth (f - n) with reverse-Z */
    float zs = c->inverted ? -(c->f - c->n) : (c->f - c->n), z0 = c->inverted ? c->f : c->n;
    float *p = info->projectionInverse, *v = info->viewProjectionInverse, *r = info->reprojectionMatrix;
    /* clip -> view: (x s, y s, -z): the view looks down -z */
    M(p, 0, 0) = c->s, M(p, 1, 1) = c->s, M(p, 2, 2) = -zs, M(p, 2, 3) = -z0, M(p, 3, 3) = 1;
    /* clip -> world: (ex + x s, ey + y s, height - z) */
    M(v, 0, 0) = c->s, M(v, 0, 3) = c->ex, M(v, 1, 1) = c->s, M(v, 1, 3) = c->ey;
    M(v, 2, 2) = -zs, M(v, 2, 3) = c->height - z0, M(v, 3, 3) = 1;
    /* clip -> previous clip: a world point sits (dx, dy) / s further along in last frame's NDC */
    M(r, 0, 0) = M(r, 1, 1) = M(r, 2, 2) = M(r, 3, 3) = 1;
    M(r, 0, 3) = c->dx / c->s, M(r, 1, 3) = c->dy / c->s;
}

static void capture(const Camera *c, Capture *cap)
{
    float ground = c->height; /* view distance of the plane z = 0 */
    float d = (ground - c->n) / (c->f - c->n);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            int sky = x >= W - 6;
            cap->depth[i] = sky ? (c->inverted ? 0.0f : 1.0f) : (c->inverted ? 1.0f - d : d);
            cap->normal[i][0] = cap->normal[i][1] = 0.5f, cap->normal[i][2] = 1.0f; /* (0, 0, 1) stored UNORM */
            /* uv moves by (dx, dy) / (2 s) between the frames */
            cap->velocity[i][0] = c->dx / (2 * c->s), cap->velocity[i][1] = c->dy / (2 * c->s);
        }
}

static DnsrReferenceCallbacks callbacks(Capture *cap)
{
    DnsrReferenceCallbacks cb;
    memset(&cb, 0, sizeof cb);
    cb.userData = cap;
    cb.readDepth = read_depth;
    cb.readNormal = read_normal;
    cb.readVelocity = read_velocity;
    return cb;
}

/* Diagnoses and returns the count; prints each finding. */
static uint32_t diagnose(const char *what, const DnsrReferenceFrameInfo *info, Capture *cap, DnsrDiagnosis *out)
{
    DnsrReferenceCallbacks cb = callbacks(cap);
    uint32_t count = DNSR_MAX_DIAGNOSES;
    DnsrResult r = dnsr_reference_diagnose(info, &cb, &count, out);
    EXPECT(r == DNSR_SUCCESS, "%s: %s: %s", what, dnsr_result_to_string(r), dnsr_last_error_message());
    for (uint32_t k = 0; k < count; k++) printf("%s: kind %u, value %g: %s\n", what, out[k].kind, out[k].value, out[k].message);
    return count;
}

static void expect_found(const char *what, const DnsrReferenceFrameInfo *info, Capture *cap, DnsrDiagnosisKind kind, double value)
{
    DnsrDiagnosis out[DNSR_MAX_DIAGNOSES];
    uint32_t n = diagnose(what, info, cap, out);
    int seen = 0;
    for (uint32_t k = 0; k < n; k++) {
        if (out[k].kind != kind) continue;
        seen = 1;
        EXPECT(isnan(value) || fabs(out[k].value - value) < 1e-9, "%s: value %g, want %g", what, out[k].value, value);
        EXPECT(strlen(out[k].message) > 20, "%s: message too short", what);
    }
    EXPECT(seen, "%s: kind %u not reported (%u findings)", what, kind, n);
}

int main(void)
{
    static Capture cap;
    Camera cams[2] = {{0.5f, -0.3f, 10.0f, 4.0f, 1.0f, 50.0f, 0.3f, -0.2f, 0}, {0.5f, -0.3f, 10.0f, 4.0f, 1.0f, 50.0f, 0.3f, -0.2f, 1}};
    DnsrReferenceFrameInfo info;
    DnsrDiagnosis out[DNSR_MAX_DIAGNOSES];

    for (int k = 0; k < 2; k++) {
        frame_info(&cams[k], &info);
        capture(&cams[k], &cap);
        uint32_t n = diagnose(cams[k].inverted ? "clean, reverse-Z" : "clean", &info, &cap, out);
        EXPECT(n == 0, "a clean frame gave %u findings", n);
    }

    frame_info(&cams[0], &info);
    capture(&cams[0], &cap);
    DnsrReferenceFrameInfo planted = info;
    planted.motionVectorScale[0] = planted.motionVectorScale[1] = -1.0f; /* FidelityFX 1.2: uv - v */
    expect_found("negated motion vectors", &planted, &cap, DNSR_DIAGNOSIS_VELOCITY_SIGN, -1.0);
    planted = info;
    planted.motionVectorScale[0] = planted.motionVectorScale[1] = 0.5f;
    expect_found("half-scale motion vectors", &planted, &cap, DNSR_DIAGNOSIS_VELOCITY_SCALE, 2.0);
    planted = info;
    planted.normalsUnpackMul = 1.0f, planted.normalsUnpackAdd = 0.0f;
    expect_found("normals without their unpack", &planted, &cap, DNSR_DIAGNOSIS_NORMALS_NOT_UNIT, NAN);
    planted = info;
    planted.flags |= DNSR_REFERENCE_DEPTH_INVERTED;
    expect_found("inverted flag on standard depth", &planted, &cap, DNSR_DIAGNOSIS_DEPTH_CONVENTION, 0.0);
    frame_info(&cams[1], &info);
    capture(&cams[1], &cap);
    planted = info;
    planted.flags &= ~(DnsrReferenceFlags)DNSR_REFERENCE_DEPTH_INVERTED;
    expect_found("standard flag on reverse-Z", &planted, &cap, DNSR_DIAGNOSIS_DEPTH_CONVENTION, 0.0);
    frame_info(&cams[0], &info);
    capture(&cams[0], &cap);
    planted = info;
    M(planted.viewProjectionInverse, 2, 3) += 3.0f; /* a camera 3 units higher than eye says */
    expect_found("matrices of another camera", &planted, &cap, DNSR_DIAGNOSIS_MATRICES_INCONSISTENT, NAN);

    /* Count only, then a capacity of 1 for two planted mistakes. */
    planted = info;
    planted.normalsUnpackMul = 1.0f, planted.normalsUnpackAdd = 0.0f;
    planted.motionVectorScale[0] = planted.motionVectorScale[1] = -1.0f;
    DnsrReferenceCallbacks cb = callbacks(&cap);
    uint32_t count = 0;
    EXPECT(dnsr_reference_diagnose(&planted, &cb, &count, NULL) == DNSR_SUCCESS && count == 2, "count-only: %u", count);
    count = 1;
    memset(out, 0, sizeof out);
    EXPECT(dnsr_reference_diagnose(&planted, &cb, &count, out) == DNSR_SUCCESS && count == 1 && out[0].message[0],
           "capacity 1: %u", count);

    /* Bad arguments. */
    EXPECT(dnsr_reference_diagnose(&info, &cb, NULL, out) == DNSR_ERROR_INVALID_ARGUMENT, "NULL count");
    EXPECT(dnsr_reference_diagnose(NULL, &cb, &count, out) == DNSR_ERROR_INVALID_ARGUMENT, "NULL info");
    DnsrReferenceCallbacks no_depth = cb;
    no_depth.readDepth = NULL;
    EXPECT(dnsr_reference_diagnose(&info, &no_depth, &count, out) == DNSR_ERROR_INVALID_ARGUMENT, "no readDepth");
    EXPECT(strstr(dnsr_last_error_message(), "readDepth") != NULL, "message: %s", dnsr_last_error_message());
    planted = info;
    planted.reprojectionMatrix[5] = NAN;
    EXPECT(dnsr_reference_diagnose(&planted, &cb, &count, out) == DNSR_ERROR_NON_FINITE, "NaN matrix");

    if (failures) {
        printf("diagnostics: %d check(s) failed\n", failures);
        return 1;
    }
    printf("diagnostics: clean frames clean, 6 planted mistakes reported, count and bad-argument cases ok\n");
    return 0;
}
