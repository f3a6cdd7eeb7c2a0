// vec_math.h: the little vector and matrix math the viewer needs.
//
// Matrices are column-major float[16] mapping column vectors (m[col * 4 + row]): the layout GLSL's mat4 and
// dnsr's DnsrShadowsDispatch both use, so a Mat4 is copied to either as is.
#pragma once

#include <cmath>
#include <cstring>

struct Vec3 {
    float x = 0, y = 0, z = 0;
};
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline float length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a)
{
    float l = length(a);
    return l > 0 ? a * (1.0f / l) : Vec3{0, 0, 0};
}
inline Vec3 vmin(Vec3 a, Vec3 b) { return {std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z)}; }
inline Vec3 vmax(Vec3 a, Vec3 b) { return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z)}; }
inline float component(Vec3 a, int axis) { return axis == 0 ? a.x : axis == 1 ? a.y : a.z; }
inline bool isFinite(Vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

struct Vec4 {
    float x = 0, y = 0, z = 0, w = 0;
};

struct Mat4 {
    float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // identity

    float &at(int row, int col) { return m[col * 4 + row]; }
    float at(int row, int col) const { return m[col * 4 + row]; }

    Mat4 operator*(const Mat4 &b) const
    {
        Mat4 r;
        for (int row = 0; row < 4; row++)
            for (int col = 0; col < 4; col++) {
                float s = 0;
                for (int k = 0; k < 4; k++) s += at(row, k) * b.at(k, col);
                r.at(row, col) = s;
            }
        return r;
    }
    Vec4 operator*(Vec4 v) const
    {
        const float in[4] = {v.x, v.y, v.z, v.w};
        float out[4];
        for (int row = 0; row < 4; row++)
            out[row] = at(row, 0) * in[0] + at(row, 1) * in[1] + at(row, 2) * in[2] + at(row, 3) * in[3];
        return {out[0], out[1], out[2], out[3]};
    }
    Vec3 transformPoint(Vec3 p) const
    {
        Vec4 r = (*this) * Vec4{p.x, p.y, p.z, 1.0f};
        return {r.x, r.y, r.z};  // affine matrices only (node transforms): no divide by w
    }
    bool isFinite() const
    {
        for (float v : m)
            if (!std::isfinite(v)) return false;
        return true;
    }
};

// General 4x4 inverse by cofactors, in double: a perspective matrix has entries of very different magnitudes.
// Returns false for a singular matrix.
inline bool inverseDouble(const double m[16], double out[16])
{
    double inv[16];
    inv[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] + m[9] * m[7] * m[14] +
             m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    inv[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] - m[8] * m[7] * m[14] -
             m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    inv[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] + m[8] * m[7] * m[13] +
             m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    inv[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] - m[8] * m[6] * m[13] -
              m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    inv[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] - m[9] * m[3] * m[14] -
             m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    inv[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] + m[8] * m[3] * m[14] +
             m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    inv[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] - m[8] * m[3] * m[13] -
             m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    inv[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] + m[8] * m[2] * m[13] +
              m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    inv[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] + m[5] * m[3] * m[14] +
             m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
    inv[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] - m[4] * m[3] * m[14] -
             m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    inv[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] + m[4] * m[3] * m[13] +
              m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    inv[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] - m[4] * m[2] * m[13] -
              m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    inv[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] - m[5] * m[3] * m[10] -
             m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
    inv[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] + m[4] * m[3] * m[10] +
             m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
    inv[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] - m[4] * m[3] * m[9] -
              m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
    inv[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] + m[4] * m[2] * m[9] +
              m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
    double det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
    if (det == 0 || !std::isfinite(det)) return false;
    for (int i = 0; i < 16; i++) out[i] = inv[i] / det;
    return true;
}

inline bool inverse(const Mat4 &a, Mat4 &out)
{
    double m[16], inv[16];
    for (int i = 0; i < 16; i++) m[i] = a.m[i];
    if (!inverseDouble(m, inv)) return false;
    for (int i = 0; i < 16; i++) out.m[i] = static_cast<float>(inv[i]);
    return out.isFinite();
}

// prev * inverse(cur), all in double (dnsr's reprojection matrix: current clip -> previous clip). In float, with
// a near plane close to the camera, the large entries of the inverse cancel in the product and leave errors near
// 1e-4 in the reprojected depth: with standard depth that is a few percent of linear depth, enough for dnsr's
// disocclusion test to throw away the history of every pixel even when the camera stands still.
inline bool reprojection(const Mat4 &prev, const Mat4 &cur, Mat4 &out)
{
    double c[16], inv[16];
    for (int i = 0; i < 16; i++) c[i] = cur.m[i];
    if (!inverseDouble(c, inv)) return false;
    for (int row = 0; row < 4; row++)
        for (int col = 0; col < 4; col++) {
            double sum = 0;
            for (int k = 0; k < 4; k++) sum += double(prev.m[k * 4 + row]) * inv[col * 4 + k];
            out.m[col * 4 + row] = static_cast<float>(sum);
        }
    return out.isFinite();
}

// Right-handed view matrix: the camera at `eye` looks down its -z axis at `target`, +y up.
inline Mat4 lookAt(Vec3 eye, Vec3 target, Vec3 up)
{
    Vec3 f = normalize(target - eye);
    Vec3 s = normalize(cross(f, up));
    Vec3 u = cross(s, f);
    Mat4 v;
    v.at(0, 0) = s.x, v.at(0, 1) = s.y, v.at(0, 2) = s.z, v.at(0, 3) = -dot(s, eye);
    v.at(1, 0) = u.x, v.at(1, 1) = u.y, v.at(1, 2) = u.z, v.at(1, 3) = -dot(u, eye);
    v.at(2, 0) = -f.x, v.at(2, 1) = -f.y, v.at(2, 2) = -f.z, v.at(2, 3) = dot(f, eye);
    return v;
}

// Standard-depth perspective projection in Vulkan's clip space: view-space y up lands at the top of the image
// (NDC y = -1, uv y = 0), depth 0 at the near plane and 1 at the far plane, the convention dnsr expects.
inline Mat4 perspectiveVulkan(float fovY, float aspect, float zNear, float zFar)
{
    float f = 1.0f / std::tan(fovY * 0.5f);
    Mat4 p;
    std::memset(p.m, 0, sizeof p.m);
    p.at(0, 0) = f / aspect;
    p.at(1, 1) = -f;
    p.at(2, 2) = zFar / (zNear - zFar);
    p.at(2, 3) = zNear * zFar / (zNear - zFar);
    p.at(3, 2) = -1.0f;
    return p;
}
