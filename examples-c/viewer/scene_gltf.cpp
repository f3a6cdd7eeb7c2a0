// scene_gltf.cpp: glTF loading with tinygltf (Debian's shared libtinygltf), then our own validation of every
// accessor before a single byte is read: tinygltf parses the JSON and loads the buffers, but it does not check
// that an accessor fits inside its buffer view, that indices are in range, or that positions are finite.
//
// Before tinygltf sees anything, the path is stat()ed (only a regular file is read: a directory made tinygltf
// allocate 2^63 bytes, a FIFO blocked in open(); buffer and image URIs likewise, through tinygltf's file-system
// callbacks) and the JSON's top level is scanned for the glTF version and the
// required extensions (tinygltf reads glTF 2.0 only, and met glTF 1.0 or Draco files with messages about
// whatever it tripped on first).
#include "scene_gltf.h"

#include <tiny_gltf.h>

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

namespace {

// tinygltf's messages can span lines, and a JSON parse error quotes the file's bytes (a PNG's 0x89 and all); the
// viewer promises one line of printable ASCII (anything else becomes '?') of reasonable length.
std::string oneLine(std::string s)
{
    for (char &c : s) {
        unsigned char u = static_cast<unsigned char>(c);
        if (c == '\n' || c == '\r' || c == '\t') c = ' ';
        else if (u < 0x20 || u >= 0x7f) c = '?';
    }
    while (!s.empty() && s.back() == ' ') s.pop_back();
    if (s.size() > 400) s = s.substr(0, 400) + "...";
    return s;
}

[[noreturn]] void fail(const std::string &path, const std::string &what)
{
    throw SceneError(path + ": " + oneLine(what));
}

// Image decoding is not needed (the viewer ignores textures): accept every image without decoding it, so that a
// broken or unsupported texture never stops the geometry from loading.
bool skipImage(tinygltf::Image *, const int, std::string *, std::string *, int, int, const unsigned char *, int, void *)
{
    return true;
}

// A validated view of an accessor's elements: element i starts at base + i * stride and is `elementSize` bytes.
struct AccessorData {
    const uint8_t *base = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int componentType = 0;
};

size_t componentSize(int componentType)
{
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return 8;
    default: return 0;
    }
}

const char *typeName(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown";
    }
}

class Loader {
public:
    Loader(const std::string &path, const tinygltf::Model &model, Scene &scene)
        : path_(path), model_(model), scene_(scene)
    {
    }

    void run()
    {
        if (model_.scenes.empty()) fail(path_, "the file has no scenes (nothing to show)");
        int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
        if (sceneIndex >= static_cast<int>(model_.scenes.size()))
            fail(path_, "\"scene\" is " + std::to_string(sceneIndex) + " but there are only " +
                            std::to_string(model_.scenes.size()) + " scenes");
        const tinygltf::Scene &scene = model_.scenes[sceneIndex];
        scene_.name = scene.name;
        onPath_.assign(model_.nodes.size(), false);
        for (int root : scene.nodes) visit(root, Mat4{}, 0);
        std::string skipped;
        if (skippedPrimitives_)
            skipped = std::to_string(skippedPrimitives_) + " non-triangle primitive(s) (mode " +
                      std::to_string(skippedMode_) + ") skipped: only triangles are supported";
        if (scene_.positions.empty())
            fail(path_, "scene " + std::to_string(sceneIndex) + " has no triangle meshes" +
                            (skipped.empty() ? "" : " (" + skipped + ")"));
        if (!skipped.empty()) std::fprintf(stderr, "viewer: %s: %s\n", path_.c_str(), skipped.c_str());
    }

private:
    // Validates accessor `index` as `expectedType` with one of `componentTypes`, returns where its bytes are.
    AccessorData accessor(int index, const char *what, int expectedType, std::initializer_list<int> componentTypes)
    {
        std::string name = std::string(what) + " accessor " + std::to_string(index);
        if (index < 0 || index >= static_cast<int>(model_.accessors.size()))
            fail(path_, name + " does not exist (" + std::to_string(model_.accessors.size()) + " accessors)");
        const tinygltf::Accessor &a = model_.accessors[index];
        if (a.type != expectedType)
            fail(path_, name + " has type " + typeName(a.type) + ", expected " + typeName(expectedType));
        if (std::find(componentTypes.begin(), componentTypes.end(), a.componentType) == componentTypes.end())
            fail(path_, name + " has unsupported componentType " + std::to_string(a.componentType));
        if (a.sparse.isSparse) fail(path_, name + " is sparse (not supported)");
        if (a.bufferView < 0 || a.bufferView >= static_cast<int>(model_.bufferViews.size()))
            fail(path_, name + " has no valid bufferView (accessors without data are not supported)");
        if (a.count == 0) fail(path_, name + " has count 0");
        const tinygltf::BufferView &view = model_.bufferViews[a.bufferView];
        if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size()))
            fail(path_, "bufferView " + std::to_string(a.bufferView) + " refers to a missing buffer");
        const std::vector<unsigned char> &data = model_.buffers[view.buffer].data;
        // Every comparison is arranged so that no sum can overflow, whatever the file says.
        if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
            fail(path_, "bufferView " + std::to_string(a.bufferView) + " (offset " + std::to_string(view.byteOffset) +
                            ", length " + std::to_string(view.byteLength) + ") does not fit in buffer " +
                            std::to_string(view.buffer) + " of " + std::to_string(data.size()) + " bytes");
        size_t components = a.type == TINYGLTF_TYPE_SCALAR ? 1 : a.type == TINYGLTF_TYPE_VEC3 ? 3 : 0;
        size_t elementSize = componentSize(a.componentType) * components;
        size_t stride = view.byteStride ? view.byteStride : elementSize;
        if (elementSize == 0 || stride < elementSize)
            fail(path_, name + ": byteStride " + std::to_string(view.byteStride) + " is smaller than an element");
        if (a.byteOffset > view.byteLength || elementSize > view.byteLength - a.byteOffset ||
            (a.count - 1) > (view.byteLength - a.byteOffset - elementSize) / stride)
            fail(path_, name + " (" + std::to_string(a.count) + " elements from offset " + std::to_string(a.byteOffset) +
                            ") does not fit in its bufferView of " + std::to_string(view.byteLength) + " bytes");
        return {data.data() + view.byteOffset + a.byteOffset, stride, a.count, a.componentType};
    }

    static Vec3 readVec3(const AccessorData &d, size_t i)
    {
        float v[3];
        std::memcpy(v, d.base + i * d.stride, sizeof v);  // memcpy: glTF data need not be aligned for us
        return {v[0], v[1], v[2]};
    }

    static uint32_t readIndex(const AccessorData &d, size_t i)
    {
        const uint8_t *p = d.base + i * d.stride;
        if (d.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return *p;
        if (d.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }

    Mat4 localTransform(const tinygltf::Node &node, int index)
    {
        std::string name = "node " + std::to_string(index);
        Mat4 m;
        if (!node.matrix.empty()) {
            if (node.matrix.size() != 16) fail(path_, name + ": matrix must have 16 numbers");
            for (int i = 0; i < 16; i++) m.m[i] = static_cast<float>(node.matrix[i]);
        } else {
            auto check = [&](const std::vector<double> &v, size_t n, const char *field) {
                if (!v.empty() && v.size() != n)
                    fail(path_, name + ": " + field + " must have " + std::to_string(n) + " numbers");
            };
            check(node.translation, 3, "translation");
            check(node.rotation, 4, "rotation");
            check(node.scale, 3, "scale");
            Vec3 t = node.translation.empty() ? Vec3{} : Vec3{float(node.translation[0]), float(node.translation[1]),
                                                              float(node.translation[2])};
            Vec3 s = node.scale.empty() ? Vec3{1, 1, 1}
                                        : Vec3{float(node.scale[0]), float(node.scale[1]), float(node.scale[2])};
            float x = 0, y = 0, z = 0, w = 1;
            if (!node.rotation.empty()) {
                x = float(node.rotation[0]), y = float(node.rotation[1]), z = float(node.rotation[2]);
                w = float(node.rotation[3]);
                float n = std::sqrt(x * x + y * y + z * z + w * w);
                if (!(n > 0) || !std::isfinite(n)) fail(path_, name + ": rotation is not a valid quaternion");
                x /= n, y /= n, z /= n, w /= n;
            }
            // M = T * R * S (glTF's order), the rotation matrix from the unit quaternion.
            const float r[3][3] = {
                {1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)},
            };
            const float sc[3] = {s.x, s.y, s.z};
            for (int row = 0; row < 3; row++)
                for (int col = 0; col < 3; col++) m.at(row, col) = r[row][col] * sc[col];
            m.at(0, 3) = t.x, m.at(1, 3) = t.y, m.at(2, 3) = t.z;
        }
        if (!m.isFinite()) fail(path_, name + ": transform contains a non-finite number");
        return m;
    }

    void visit(int index, const Mat4 &parent, int depth)
    {
        if (index < 0 || index >= static_cast<int>(model_.nodes.size()))
            fail(path_, "node " + std::to_string(index) + " does not exist");
        if (onPath_[index]) fail(path_, "node " + std::to_string(index) + " is its own ancestor (cycle)");
        if (depth > 1000) fail(path_, "node hierarchy deeper than 1000 levels");
        onPath_[index] = true;
        const tinygltf::Node &node = model_.nodes[index];
        Mat4 world = parent * localTransform(node, index);
        if (!world.isFinite()) fail(path_, "node " + std::to_string(index) + ": world transform overflows");
        if (node.mesh >= 0) {
            if (node.mesh >= static_cast<int>(model_.meshes.size()))
                fail(path_, "node " + std::to_string(index) + " refers to missing mesh " + std::to_string(node.mesh));
            addMesh(model_.meshes[node.mesh], node.mesh, world);
        }
        if (node.camera >= 0 && !scene_.hasCamera && node.camera < static_cast<int>(model_.cameras.size()) &&
            model_.cameras[node.camera].type == "perspective") {
            double yfov = model_.cameras[node.camera].perspective.yfov;
            if (yfov > 0.01 && yfov < 3.0) {
                scene_.hasCamera = true;
                scene_.cameraToWorld = world;
                scene_.cameraYFov = static_cast<float>(yfov);
            }
        }
        for (int child : node.children) visit(child, world, depth + 1);
        onPath_[index] = false;
    }

    uint32_t materialColor(int material)
    {
        float c[3] = {0.8f, 0.8f, 0.8f};
        if (material >= 0 && material < static_cast<int>(model_.materials.size())) {
            const std::vector<double> &f = model_.materials[material].pbrMetallicRoughness.baseColorFactor;
            for (int i = 0; i < 3 && f.size() == 4; i++)
                c[i] = std::isfinite(f[i]) ? static_cast<float>(std::clamp(f[i], 0.0, 1.0)) : 0.8f;
        }
        uint32_t packed = 0xff000000u;
        for (int i = 0; i < 3; i++) packed |= static_cast<uint32_t>(c[i] * 255.0f + 0.5f) << (8 * i);
        return packed;
    }

    void addMesh(const tinygltf::Mesh &mesh, int meshIndex, const Mat4 &world)
    {
        // Normals transform with the inverse transpose of the upper 3x3.
        Mat4 normalMatrix;
        Mat4 inv;
        bool invertible = inverse(world, inv);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) normalMatrix.at(r, c) = invertible ? inv.at(c, r) : world.at(r, c);

        for (size_t p = 0; p < mesh.primitives.size(); p++) {
            const tinygltf::Primitive &prim = mesh.primitives[p];
            std::string name = "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(p);
            const bool strip = prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP, fan = prim.mode == TINYGLTF_MODE_TRIANGLE_FAN;
            if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES && !strip && !fan) {  // points, lines
                skippedPrimitives_++;
                skippedMode_ = prim.mode;
                continue;
            }
            auto pos = prim.attributes.find("POSITION");
            if (pos == prim.attributes.end()) fail(path_, name + " has no POSITION attribute");
            AccessorData positions = accessor(pos->second, "POSITION", TINYGLTF_TYPE_VEC3,
                                              {TINYGLTF_COMPONENT_TYPE_FLOAT});
            AccessorData normals;
            auto nor = prim.attributes.find("NORMAL");
            if (nor != prim.attributes.end()) {
                normals = accessor(nor->second, "NORMAL", TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT});
                if (normals.count != positions.count)
                    fail(path_, name + ": NORMAL has " + std::to_string(normals.count) + " elements, POSITION " +
                                    std::to_string(positions.count));
            }
            for (size_t i = 0; i < positions.count; i++)
                if (!isFinite(readVec3(positions, i)))
                    fail(path_, name + ": POSITION " + std::to_string(i) + " is not finite");

            std::vector<uint32_t> indices;
            if (prim.indices >= 0) {
                AccessorData idx = accessor(prim.indices, "indices", TINYGLTF_TYPE_SCALAR,
                                            {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
                if (!strip && !fan && idx.count % 3 != 0)
                    fail(path_, name + ": index count " + std::to_string(idx.count) + " is not a multiple of 3");
                indices.resize(idx.count);
                for (size_t i = 0; i < idx.count; i++) {
                    indices[i] = readIndex(idx, i);
                    if (indices[i] >= positions.count)
                        fail(path_, name + ": index " + std::to_string(i) + " is " + std::to_string(indices[i]) +
                                        ", out of range for " + std::to_string(positions.count) + " vertices");
                }
            } else {
                if (!strip && !fan && positions.count % 3 != 0)
                    fail(path_, name + ": " + std::to_string(positions.count) +
                                    " vertices without indices is not a multiple of 3");
                indices.resize(positions.count);
                for (size_t i = 0; i < positions.count; i++) indices[i] = static_cast<uint32_t>(i);
            }
            // Strips and fans as triangle lists: strip triangle k is (k, k+1, k+2), every other one with its
            // first two swapped so that all keep the strip's winding; fan triangle k is (0, k+1, k+2).
            if (strip || fan) {
                if (indices.size() < 3) fail(path_, name + ": a triangle " + (strip ? "strip" : "fan") + " of " +
                                                         std::to_string(indices.size()) + " vertices");
                std::vector<uint32_t> list;
                list.reserve(3 * (indices.size() - 2));
                for (size_t k = 0; k + 2 < indices.size(); k++) {
                    uint32_t a = fan ? indices[0] : indices[k], b = indices[k + 1], c = indices[k + 2];
                    if (strip && k % 2 == 1) std::swap(a, b);
                    list.insert(list.end(), {a, b, c});
                }
                indices = std::move(list);
            }

            uint32_t color = materialColor(prim.material);
            for (size_t t = 0; t < indices.size(); t += 3) {
                Vec3 v[3], n[3];
                for (int k = 0; k < 3; k++) v[k] = world.transformPoint(readVec3(positions, indices[t + k]));
                if (!isFinite(v[0]) || !isFinite(v[1]) || !isFinite(v[2]))
                    fail(path_, name + ": a transformed position overflows");
                Vec3 geometric = normalize(cross(v[1] - v[0], v[2] - v[0]));
                if (length(geometric) == 0) continue;  // degenerate: invisible to rays anyway
                for (int k = 0; k < 3; k++) {
                    n[k] = geometric;
                    if (normals.base) {
                        Vec3 local = readVec3(normals, indices[t + k]);
                        Vec3 w = normalize(normalMatrix.transformPoint(local));  // no translation part
                        if (isFinite(w) && length(w) > 0.5f) n[k] = w;  // keeps the face normal for bad normals
                    }
                    scene_.positions.push_back(v[k]);
                    scene_.normals.push_back(n[k]);
                }
                scene_.albedo.push_back(color);
            }
        }
    }

    const std::string &path_;
    const tinygltf::Model &model_;
    Scene &scene_;
    std::vector<bool> onPath_;
    size_t skippedPrimitives_ = 0;
    int skippedMode_ = 0;
};

// ---- The file itself, and what kind of glTF it is ----

// Reads `path` whole, refusing anything that is not a regular file. stat() first, never open(): opening a FIFO
// blocks until a writer comes, and a directory opens fine but then reads as a file of absurd length.
// Reads a regular file whole (`what` names it in messages): anything else is refused before it is opened.
std::vector<unsigned char> readRegularFile(const std::string &path, const char *what)
{
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) fail(path, std::string("cannot open file: ") + std::strerror(errno));
    const char *kind = S_ISREG(st.st_mode)    ? nullptr
                       : S_ISDIR(st.st_mode)  ? "a directory"
                       : S_ISFIFO(st.st_mode) ? "a FIFO (named pipe)"
                       : S_ISSOCK(st.st_mode) ? "a socket"
                       : S_ISCHR(st.st_mode)  ? "a character device"
                       : S_ISBLK(st.st_mode)  ? "a block device"
                                              : "not a regular file";
    if (kind) throw SceneError(path + " is " + kind + ", not " + what);
    if (st.st_size == 0) fail(path, "the file is empty");
    // tinygltf takes the length as an unsigned int.
    if (static_cast<unsigned long long>(st.st_size) > std::numeric_limits<unsigned int>::max())
        fail(path, "the file is larger than 4 GiB");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open file");
    std::vector<unsigned char> data(static_cast<size_t>(st.st_size));
    in.read(reinterpret_cast<char *>(data.data()), static_cast<std::streamsize>(data.size()));
    if (static_cast<size_t>(in.gcount()) != data.size()) fail(path, "cannot read the whole file (did it change?)");
    return data;
}

std::vector<unsigned char> readSceneFile(const std::string &path) { return readRegularFile(path, "a glTF file"); }

// tinygltf's file-system callbacks for the buffers and images a glTF names by URI: each is read as the scene file is
// (a regular file, checked before it is opened). tinygltf's own blocked forever in open() on a FIFO, reported
// std::bad_alloc for a directory and "File not found" for /dev/zero. A path that exists goes on to the read, which
// says why it cannot be used.
bool uriExists(const std::string &path, void *)
{
    struct stat st;
    return ::stat(path.c_str(), &st) == 0;
}
bool readUri(std::vector<unsigned char> *out, std::string *err, const std::string &path, void *)
{
    try {
        *out = readRegularFile(path, "a buffer or image file");
        return true;
    } catch (const SceneError &e) {
        if (err) *err += e.what();
        return false;
    }
}
bool refuseWrite(std::string *err, const std::string &, const std::vector<unsigned char> &, void *)
{
    if (err) *err += "dnsr_viewer writes no glTF files";
    return false;
}

// JSON nested deeper than this is refused before tinygltf parses it: its parser recurses per level, and a file
// whose "extras" nested arrays 20,000 deep overflowed the stack. glTF itself nests a few levels.
constexpr int kMaxJsonNesting = 256;

// The deepest nesting of arrays and objects in [begin, end), strings skipped (stops counting past the limit).
int jsonNesting(const unsigned char *begin, const unsigned char *end)
{
    int depth = 0, deepest = 0;
    bool inString = false;
    for (const unsigned char *p = begin; p < end && deepest <= kMaxJsonNesting; ++p) {
        if (inString) {
            if (*p == '\\') ++p;
            else if (*p == '"') inString = false;
        } else if (*p == '"') {
            inString = true;
        } else if (*p == '[' || *p == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((*p == ']' || *p == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

// What the top level of a glTF's JSON says about its version and extensions.
struct GltfHeader {
    bool hasAssetVersion = false;
    bool assetVersionIsString = false;
    std::string assetVersion;
    std::string gltf1Sign;  // the first top-level member shaped as in glTF 1.0, described; empty if none
    std::string objectNotArray;  // the first member that glTF 2.0 makes an array but this file an object
    std::vector<std::string> required, used;
    bool sceneNotIndex = false;  // a top-level "scene" that is no number (tinygltf ignores it without a word)
    // Members of the top-level arrays' objects whose JSON type is not glTF's (tinygltf ignores them without a
    // word), described: the first kMaxWrongTypes, and how many there were.
    std::vector<std::string> wrongTypes;
    size_t wrongTypeCount = 0;
};

constexpr size_t kMaxWrongTypes = 4;

enum class JsonType { String, Number, Bool, Array, Object, Null };

const char *jsonTypeName(JsonType t)
{
    switch (t) {
    case JsonType::String: return "a string";
    case JsonType::Number: return "a number";
    case JsonType::Bool: return "a boolean";
    case JsonType::Array: return "an array";
    case JsonType::Object: return "an object";
    case JsonType::Null: return "null";
    }
    return "?";
}

// The JSON type glTF 2.0 gives a member of an element of a top-level array ("*": of every such array), for the
// members the viewer reads or that are commonly wrong; others are not checked.
struct MemberType {
    const char *array, *member;
    JsonType type;
};
const MemberType kMemberTypes[] = {
    {"*", "name", JsonType::String},
    {"materials", "doubleSided", JsonType::Bool},
    {"materials", "alphaMode", JsonType::String},
    {"materials", "alphaCutoff", JsonType::Number},
    {"materials", "emissiveFactor", JsonType::Array},
    {"materials", "pbrMetallicRoughness", JsonType::Object},
    {"materials", "normalTexture", JsonType::Object},
    {"materials", "occlusionTexture", JsonType::Object},
    {"materials", "emissiveTexture", JsonType::Object},
    {"textures", "source", JsonType::Number},
    {"textures", "sampler", JsonType::Number},
    {"images", "uri", JsonType::String},
    {"images", "mimeType", JsonType::String},
    {"images", "bufferView", JsonType::Number},
    {"nodes", "mesh", JsonType::Number},
    {"nodes", "camera", JsonType::Number},
    {"nodes", "children", JsonType::Array},
    {"nodes", "matrix", JsonType::Array},
    {"nodes", "translation", JsonType::Array},
    {"nodes", "rotation", JsonType::Array},
    {"nodes", "scale", JsonType::Array},
    {"meshes", "primitives", JsonType::Array},
    {"scenes", "nodes", JsonType::Array},
};

// Just enough JSON to fill a GltfHeader: the members named above are read, every other value is skipped without
// recursion (no depth limit needed). scan() returns false for anything it cannot follow; the caller then
// concludes nothing and leaves the error message to tinygltf's full parser.
class HeaderScanner {
public:
    HeaderScanner(const unsigned char *begin, const unsigned char *end)
        : p_(reinterpret_cast<const char *>(begin)), end_(reinterpret_cast<const char *>(end))
    {
        if (end_ - p_ >= 3 && std::memcmp(p_, "\xEF\xBB\xBF", 3) == 0) p_ += 3;  // a UTF-8 byte order mark
    }

    bool scan(GltfHeader &h)
    {
        // The members that glTF 2.0 makes arrays and glTF 1.0 made objects keyed by id.
        static const char *const arrays[] = {"accessors", "animations", "buffers",  "bufferViews", "cameras",
                                             "images",    "materials",  "meshes",   "nodes",       "samplers",
                                             "scenes",    "skins",      "textures"};
        bool ok = members([&](const std::string &key) {
            if (key == "asset" && peek('{'))
                return members([&](const std::string &k) {
                    if (k != "version") return skipValue();
                    h.hasAssetVersion = true;
                    h.assetVersionIsString = peek('"');
                    return h.assetVersionIsString ? string(&h.assetVersion) : skipValue();
                });
            if ((key == "extensionsRequired" || key == "extensionsUsed") && peek('[')) {
                std::vector<std::string> &list = key == "extensionsRequired" ? h.required : h.used;
                return elements([&] {
                    if (!peek('"')) return skipValue();
                    list.emplace_back();
                    return string(&list.back());
                });
            }
            if (h.objectNotArray.empty() && peek('{') &&
                std::find(std::begin(arrays), std::end(arrays), key) != std::end(arrays))
                h.objectNotArray = key;
            if (key == "scene" && !peekNumber()) h.sceneNotIndex = true;
            if (peek('[') && std::find(std::begin(arrays), std::end(arrays), key) != std::end(arrays))
                return checkMemberTypes(key, h);
            if (key == "version") h.gltf1Sign = "a top-level \"version\"";  // the plainest sign: named first
            else if (h.gltf1Sign.empty() && key == "scene" && peek('"'))
                h.gltf1Sign = "\"scene\" is a string (an id)";
            else if (h.gltf1Sign.empty() && h.objectNotArray == key)
                h.gltf1Sign = "\"" + key + "\" is an object keyed by id";
            return skipValue();
        });
        skipSpace();
        return ok && p_ == end_;
    }

private:
    // The elements of top-level array `array`, each member of kMemberTypes checked for its JSON type.
    bool checkMemberTypes(const std::string &array, GltfHeader &h)
    {
        size_t index = 0;
        return elements([&] {
            size_t element = index++;
            if (!peek('{')) return skipValue();
            return members([&](const std::string &member) {
                for (const MemberType &m : kMemberTypes) {
                    if ((std::strcmp(m.array, "*") != 0 && array != m.array) || member != m.member) continue;
                    JsonType found = typeHere();
                    if (found != m.type && h.wrongTypeCount++ < kMaxWrongTypes)
                        h.wrongTypes.push_back(array + "[" + std::to_string(element) + "]." + member + " is " +
                                               jsonTypeName(found) + ", not " + jsonTypeName(m.type));
                    break;
                }
                return skipValue();
            });
        });
    }

    JsonType typeHere()
    {
        skipSpace();
        switch (p_ < end_ ? *p_ : '\0') {
        case '"': return JsonType::String;
        case '{': return JsonType::Object;
        case '[': return JsonType::Array;
        case 't':
        case 'f': return JsonType::Bool;
        case 'n': return JsonType::Null;
        default: return JsonType::Number;
        }
    }

    void skipSpace()
    {
        while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\n' || *p_ == '\r')) ++p_;
    }
    bool peek(char c)
    {
        skipSpace();
        return p_ < end_ && *p_ == c;
    }
    bool peekNumber()
    {
        skipSpace();
        return p_ < end_ && (std::isdigit(static_cast<unsigned char>(*p_)) || *p_ == '-');
    }
    bool eat(char c)
    {
        if (!peek(c)) return false;
        ++p_;
        return true;
    }

    // A JSON string; escapes are decoded as far as names need (\uXXXX beyond ASCII becomes '?').
    bool string(std::string *out)
    {
        if (!eat('"')) return false;
        while (p_ < end_) {
            char c = *p_++;
            if (c == '"') return true;
            if (static_cast<unsigned char>(c) < 0x20) return false;
            if (c == '\\') {
                if (p_ >= end_) return false;
                c = *p_++;
                if (c == 'u') {
                    unsigned code = 0;
                    for (int i = 0; i < 4; i++, ++p_) {
                        if (p_ >= end_ || !std::isxdigit(static_cast<unsigned char>(*p_))) return false;
                        code = code * 16 + unsigned(std::isdigit(static_cast<unsigned char>(*p_))
                                                        ? *p_ - '0'
                                                        : std::tolower(static_cast<unsigned char>(*p_)) - 'a' + 10);
                    }
                    c = code < 0x80 ? static_cast<char>(code) : '?';
                } else {
                    const char *from = "\"\\/bfnrt", *to = "\"\\/\b\f\n\r\t";
                    const char *at = std::strchr(from, c);
                    if (!at || !c) return false;
                    c = to[at - from];
                }
            }
            if (out) *out += c;
        }
        return false;
    }

    // Any value, nested or not, by counting brackets (strings are read properly, so brackets inside them do not
    // count). Lenient about the grammar between the brackets: tinygltf checks that.
    bool skipValue()
    {
        size_t depth = 0;
        do {
            skipSpace();
            if (p_ >= end_) return false;
            char c = *p_;
            if (c == '"') {
                if (!string(nullptr)) return false;
            } else if (c == '{' || c == '[') {
                depth++, p_++;
            } else if (c == '}' || c == ']' || c == ',' || c == ':') {
                if (depth == 0) return false;
                if (c == '}' || c == ']') depth--;
                p_++;
            } else {  // number, true, false, null
                const char *start = p_;
                while (p_ < end_ && (std::isalnum(static_cast<unsigned char>(*p_)) || *p_ == '+' || *p_ == '-' ||
                                     *p_ == '.'))
                    ++p_;
                if (p_ == start) return false;
            }
        } while (depth > 0);
        return true;
    }

    // An object: onMember(key) is called with the input at the member's value, and must consume it.
    template <class F> bool members(F &&onMember)
    {
        if (!eat('{')) return false;
        if (eat('}')) return true;
        for (;;) {
            std::string key;
            if (!peek('"') || !string(&key) || !eat(':') || !onMember(key)) return false;
            if (!eat(',')) return eat('}');
        }
    }

    // An array: onElement() is called with the input at each element, and must consume it.
    template <class F> bool elements(F &&onElement)
    {
        if (!eat('[')) return false;
        if (eat(']')) return true;
        for (;;) {
            if (!onElement()) return false;
            if (!eat(',')) return eat(']');
        }
    }

    const char *p_;
    const char *end_;
};

// Compression extensions: their meshes have no plain vertex data (unless the file carries a fallback).
const char *compressionName(const std::string &extension)
{
    if (extension == "KHR_draco_mesh_compression") return "Draco compression";
    if (extension == "EXT_meshopt_compression" || extension == "KHR_meshopt_compression") return "meshopt compression";
    return nullptr;
}

// Required extensions that change only what the viewer does not draw anyway (textures, the finer points of
// materials, the file's own lights): the geometry, all that the shadows need, loads correctly without them.
bool ignorableExtension(const std::string &extension)
{
    auto starts = [&](const char *prefix) { return extension.rfind(prefix, 0) == 0; };
    return starts("KHR_materials_") || starts("KHR_texture_") || starts("EXT_texture_") ||
           extension == "KHR_lights_punctual";
}

// A name from the file, made safe for a one-line message.
std::string printable(const std::string &s)
{
    std::string out;
    for (char c : s.substr(0, 40)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
    return s.size() > 40 ? out + "..." : out;
}

// Throws for a file that is not glTF 2.0 or that requires an extension the viewer lacks.
void refuseUnsupported(const std::string &path, const GltfHeader &h)
{
    const std::string reads = " is not supported (dnsr_viewer reads glTF 2.0)";
    if (h.hasAssetVersion && !h.assetVersionIsString)
        fail(path, "asset.version is not a string (glTF 2.0 files say \"version\": \"2.0\")");
    if (h.hasAssetVersion && h.assetVersion.rfind("2.", 0) != 0)
        fail(path, "glTF " + printable(h.assetVersion) + reads);
    if (!h.hasAssetVersion && !h.gltf1Sign.empty())
        fail(path, "glTF 1.0" + reads + ": no asset.version, and " + h.gltf1Sign + " as in glTF 1.0");
    if (!h.hasAssetVersion) fail(path, "no asset.version (a glTF 2.0 file has \"asset\": {\"version\": \"2.0\"})");
    if (!h.objectNotArray.empty())  // in a file that says it is glTF 2.x
        fail(path, "\"" + h.objectNotArray + "\" is an object (keyed by id, as in glTF 1.0), but glTF " +
                       printable(h.assetVersion) + " wants an array");
    for (const std::string &e : h.required) {
        if (const char *name = compressionName(e)) fail(path, std::string(name) + " (" + e + ") is not supported");
        if (!ignorableExtension(e))
            fail(path, "the file requires extension " + printable(e) + ", which dnsr_viewer does not support");
    }
}

}  // namespace

Scene loadGltfScene(const std::string &path)
{
    std::vector<unsigned char> data = readSceneFile(path);
    // Decide by content rather than extension: a .glb starts with "glTF".
    bool binary = data.size() >= 4 && std::memcmp(data.data(), "glTF", 4) == 0;

    // The JSON: all of a .gltf; the first chunk of a .glb (header: magic, version, length; then the chunk's length
    // and type). A header that does not add up is left to tinygltf to report.
    const unsigned char *json = data.data(), *jsonEnd = data.data() + data.size();
    if (binary) {
        uint32_t word[4] = {};
        std::memcpy(word, data.data() + 4, std::min<size_t>(data.size() - 4, sizeof word));
        if (data.size() >= 8 && word[0] == 1)
            fail(path, "glTF 1.0 is not supported (dnsr_viewer reads glTF 2.0): a version 1 binary glTF file");
        if (data.size() >= 8 && word[0] != 2)
            fail(path, "binary glTF version " + std::to_string(word[0]) + " is not supported (dnsr_viewer reads "
                       "glTF 2.0)");
        bool jsonChunk = data.size() >= 20 && word[3] == 0x4E4F534Au && word[2] <= data.size() - 20;  // "JSON"
        json = jsonChunk ? data.data() + 20 : nullptr;
        jsonEnd = jsonChunk ? json + word[2] : nullptr;
    }
    // Nesting: the JSON chunk of a .glb, all of a .gltf (or of a .glb whose chunk cannot be found).
    if (jsonNesting(json ? json : data.data(), json ? jsonEnd : data.data() + data.size()) > kMaxJsonNesting)
        fail(path, "the JSON nests arrays and objects deeper than " + std::to_string(kMaxJsonNesting) +
                       " levels (dnsr_viewer's limit; glTF needs a few)");
    GltfHeader header;
    bool scanned = json && HeaderScanner(json, jsonEnd).scan(header);
    if (scanned) refuseUnsupported(path, header);

    // Compression named only in extensionsUsed: a conforming file then also carries uncompressed data, which is
    // what gets loaded. If that fails, the compression is the real reason.
    std::string usedCompression;
    for (const std::string &e : header.used)
        if (compressionName(e) && usedCompression.empty()) usedCompression = e;

    Scene scene;
    try {
        tinygltf::TinyGLTF gltf;
        gltf.SetImageLoader(skipImage, nullptr);
        gltf.SetFsCallbacks(tinygltf::FsCallbacks{uriExists, tinygltf::ExpandFilePath, readUri, refuseWrite, nullptr});
        tinygltf::Model model;
        std::string err, warn;
        // The bytes already read, so tinygltf opens no scene file itself; buffer URIs resolve next to the file.
        const std::string baseDir = std::filesystem::path(path).parent_path().string();
        bool ok = binary ? gltf.LoadBinaryFromMemory(&model, &err, &warn, data.data(),
                                                     static_cast<unsigned int>(data.size()), baseDir)
                         : gltf.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char *>(data.data()),
                                                    static_cast<unsigned int>(data.size()), baseDir);
        if (!ok) fail(path, err.empty() ? "tinygltf could not load the file" : err);
        Loader(path, model, scene).run();
        // What tinygltf accepted with a warning, or without one although the file is wrong: said, not fatal.
        if (!warn.empty()) std::fprintf(stderr, "viewer: %s: warning: %s\n", path.c_str(), oneLine(warn).c_str());
        if (header.wrongTypeCount > 0) {
            std::string list;
            for (const std::string &w : header.wrongTypes) list += (list.empty() ? "" : "; ") + w;
            if (header.wrongTypeCount > header.wrongTypes.size())
                list += "; " + std::to_string(header.wrongTypeCount - header.wrongTypes.size()) + " more";
            std::fprintf(stderr, "viewer: %s: warning: members of the wrong JSON type, ignored: %s\n", path.c_str(),
                         oneLine(list).c_str());
        }
        if (header.sceneNotIndex)
            std::fprintf(stderr, "viewer: %s: warning: \"scene\" is not an index; scene %d rendered\n", path.c_str(),
                         model.defaultScene >= 0 ? model.defaultScene : 0);
    } catch (const SceneError &e) {
        if (usedCompression.empty()) throw;
        std::string reason = e.what();
        if (reason.rfind(path + ": ", 0) == 0) reason.erase(0, path.size() + 2);
        fail(path, std::string(compressionName(usedCompression)) + " (" + usedCompression +
                       ") is not supported, and the file's uncompressed fallback does not load: " + reason);
    }

    scene.boundsMin = scene.boundsMax = scene.positions[0];
    for (const Vec3 &p : scene.positions) {
        scene.boundsMin = vmin(scene.boundsMin, p);
        scene.boundsMax = vmax(scene.boundsMax, p);
    }
    if (!isFinite(scene.boundsMax - scene.boundsMin) || length(scene.boundsMax - scene.boundsMin) > 1e15f)
        fail(path, "the scene's extent is too large to render");
    return scene;
}
