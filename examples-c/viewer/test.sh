#!/usr/bin/env bash
# Tests of the dnsr viewer: builds it against target/release/libdnsr.so, renders the default scene headless on
# lavapipe with the validation layer (any message fails), checks the images and that dnsr beats the 1-spp input
# against the many-ray reference, takes a window-mode screenshot under Xvfb, and feeds it broken glTF files
# (each must give exit status 2 and a one-line message, never a crash).
#
#   examples-c/viewer/test.sh            (VIEWER_DEVICE=<substring of a device name> picks another device)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
start=$SECONDS

export VIEWER_DEVICE="${VIEWER_DEVICE:-llvmpipe}"
unset VK_LOADER_DEBUG
build=build/viewer
viewer="$build/dnsr_viewer"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

fail() { echo "viewer tests: FAILED: $*" >&2; exit 1; }

# ---- Build ----
if command -v cargo >/dev/null; then
  cargo build --release --lib --quiet
elif [[ ! -f target/release/libdnsr.so ]]; then
  fail "no cargo and no target/release/libdnsr.so"
fi
cmake -S examples-c/viewer -B "$build" -DCMAKE_BUILD_TYPE=Release -DDNSR_LIB="$PWD/target/release/libdnsr.so" >/dev/null
cmake --build "$build" -j "$(nproc)" >/dev/null

# Prints "min max" of a PNG's samples (8-bit, as png_write.cpp writes them: filter 0, stored deflate).
png_range() {
  python3 - "$1" <<'PY'
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
pos, idat = 8, b""
while pos < len(data):
    n = struct.unpack(">I", data[pos:pos + 4])[0]
    kind, payload = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
    if kind == b"IHDR":
        w, h, depth, color = struct.unpack(">IIBB", payload[:10])
    elif kind == b"IDAT":
        idat += payload
    pos += 12 + n
channels = {0: 1, 2: 3, 6: 4}[color]
raw = zlib.decompress(idat)
row = w * channels + 1
assert len(raw) == row * h, "truncated image data"
pixels = b"".join(raw[y * row + 1:(y + 1) * row] for y in range(h))
print(min(pixels), max(pixels))
PY
}

check_not_blank() {
  [[ -s "$1" ]] || fail "$1 missing or empty"
  read -r lo hi < <(png_range "$1") || fail "$1 is not a readable PNG"
  (( hi - lo >= 32 )) || fail "$1 is blank (samples $lo..$hi)"
}

# ---- Headless, with validation ----
out="$tmp/headless"
status=0
"$viewer" --headless --validate --frames 8 --size 160x96 --out "$out" > "$tmp/headless.log" 2>&1 || status=$?
(( status == 0 )) || { cat "$tmp/headless.log"; fail "headless run exited with status $status"; }
for f in noisy denoised reference composite strip tiles; do check_not_blank "$out/$f.png"; done
[[ -s "$out/report.json" ]] || fail "no report.json"
quality=$(python3 - "$out/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
noisy, denoised = r["rmse"]["noisy"], r["rmse"]["denoised"]
assert r["width"] == 160 and r["height"] == 96 and r["frames"] == 8, "report size/frames"
assert r["dnsr_gpu_ms"]["frame"] >= 1, "no dnsr timings"
assert noisy > 0.02, f"the noisy shadow has almost no error ({noisy}): is the reference the same samples?"
ok = denoised < 0.7 * noisy
print(f"{'ok' if ok else 'BAD'} RMSE noisy {noisy:.4f} -> denoised {denoised:.4f} "
      f"(x{denoised / noisy:.2f}, PSNR {r['psnr_db']['denoised']:.1f} dB) on {r['device']}")
PY
) || fail "report.json check failed"
echo "headless: $quality"
[[ $quality == ok* ]] || fail "denoised RMSE is not below 0.7x the noisy RMSE"

# ---- Window mode under Xvfb (24-bit screen: Vulkan presentation needs a true-colour visual) ----
window="skipped (no xvfb-run)"
if command -v xvfb-run >/dev/null; then
  shot="$tmp/screenshot.png"
  status=0
  xvfb-run -a -s "-screen 0 1024x768x24" "$viewer" --validate --size 160x96 --frames 4 --screenshot "$shot" \
    > "$tmp/window.log" 2>&1 || status=$?
  (( status == 0 )) || { cat "$tmp/window.log"; fail "window run exited with status $status"; }
  check_not_blank "$shot"
  # The reference view accumulates while the camera stands still: exercises the progressive path.
  xvfb-run -a -s "-screen 0 1024x768x24" "$viewer" --validate --size 160x96 --frames 3 --view reference \
    --screenshot "$tmp/reference.png" > "$tmp/window.log" 2>&1 || status=$?
  (( status == 0 )) || { cat "$tmp/window.log"; fail "window run (reference view) exited with status $status"; }
  check_not_blank "$tmp/reference.png"
  # dnsr's own debug views (tile classification, sample count, variance, disocclusion) through the C API.
  for v in classification samples variance disocclusion; do
    xvfb-run -a -s "-screen 0 1024x768x24" "$viewer" --validate --size 160x96 --frames 3 --view "$v" \
      --screenshot "$tmp/$v.png" > "$tmp/window.log" 2>&1 || status=$?
    (( status == 0 )) || { cat "$tmp/window.log"; fail "window run ($v view) exited with status $status"; }
  done
  check_not_blank "$tmp/classification.png"
  check_not_blank "$tmp/samples.png"
  window="window screenshots ok (composite, reference, 4 dnsr debug views)"
  echo "window: $window"
fi

# ---- Bad input: exit status 2, a one-line message, no crash ----
python3 - "$tmp/bad" <<'PY'
import base64, json, os, struct, sys
out = sys.argv[1]
os.makedirs(out)

def gltf(positions, indices=None, position_type="VEC3", uri=None, scenes=True):
    data = b"".join(struct.pack("<3f", *p) for p in positions)
    idx = b"".join(struct.pack("<H", i) for i in (indices or []))
    pad = b"\0" * ((4 - len(data) % 4) % 4)
    blob = data + pad + idx
    doc = {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": len(blob),
                     "uri": uri or "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(data)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(positions), "type": position_type}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0}],
    }
    if indices:
        doc["bufferViews"].append({"buffer": 0, "byteOffset": len(data) + len(pad), "byteLength": len(idx)})
        doc["accessors"].append({"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"})
        doc["meshes"][0]["primitives"][0]["indices"] = 1
    if scenes:
        doc["scenes"] = [{"nodes": [0]}]
        doc["scene"] = 0
    return doc

tri = [(0, 0, 0), (1, 0, 0), (0, 0, 1)]
cases = {
    "missing_buffer": gltf(tri, uri="missing.bin"),
    "index_out_of_range": gltf(tri, indices=[0, 1, 7]),
    "nan_position": gltf([(0, 0, 0), (float("nan"), 0, 0), (0, 0, 1)]),
    "position_vec2": gltf(tri, position_type="VEC2"),
    "no_scenes": gltf(tri, scenes=False),
}
overrun = gltf(tri)
overrun["accessors"][0]["count"] = 1000  # the accessor runs past the end of its buffer view
cases["accessor_overrun"] = overrun
cycle = gltf(tri)
cycle["nodes"] = [{"mesh": 0, "children": [1]}, {"children": [0]}]  # node 0 is its own grandparent
cases["node_cycle"] = cycle
for name, doc in cases.items():
    with open(os.path.join(out, name + ".gltf"), "w") as f:
        json.dump(doc, f, allow_nan=True)  # NaN only ever appears inside the binary buffer
with open(os.path.join(out, "not_json.gltf"), "w") as f:
    f.write("{ this is not json")
with open(os.path.join(out, "truncated.glb"), "wb") as f:
    f.write(b"glTF" + struct.pack("<II", 2, 4096) + b"\x10\0\0\0JSON{")
PY
bad=0
for scene in "$tmp"/bad/*.gltf "$tmp"/bad/*.glb "$tmp/bad/does_not_exist.gltf"; do
  status=0
  "$viewer" "$scene" --headless --frames 1 --size 16x16 --out "$tmp/bad-out" > "$tmp/bad.out" 2> "$tmp/bad.err" \
    || status=$?
  name=$(basename "$scene")
  (( status < 128 )) || fail "$name: crashed (status $status): $(cat "$tmp/bad.err")"
  (( status == 2 )) || fail "$name: exit status $status, expected 2: $(cat "$tmp/bad.err")"
  lines=$(wc -l < "$tmp/bad.err")
  [[ $lines -eq 1 ]] || fail "$name: expected a one-line message, got $lines lines: $(cat "$tmp/bad.err")"
  echo "bad input $name: $(cat "$tmp/bad.err")"
  bad=$((bad + 1))
done

echo "viewer tests: ok (headless 160x96, 8 frames, validation clean: ${quality#ok }; ${window}; ${bad} bad inputs rejected with status 2; $((SECONDS - start)) s)"
