#!/usr/bin/env bash
# Tests of the dnsr viewer: builds it against target/release/libdnsr.so, renders the default scene headless on
# lavapipe with the validation layer (any message fails), checks the images and that dnsr beats the 1-spp input
# against the many-ray reference, runs with and without penumbra guidance (--hit-distance) and against a saved
# reference, with half a ray per pixel (--checkerboard: the 1-ray run's rays for half the pixels, none for the
# others), with a second light (--lights 2: light 0 unchanged bit for bit, light 1 its own), checks that
# --validate counts validation messages only (not the Vulkan loader's notices) and that --help describes every
# option and key, takes a window-mode screenshot under Xvfb, and feeds it broken or unsupported scene files, also
# through an AddressSanitizer + UBSan build (each must give exit status 2 and a one-line message, never a crash or
# a hang; unsupported kinds of file must be named as such).
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
# The same viewer with AddressSanitizer and UBSan, for the bad-input cases only (they never reach Vulkan, so no
# driver leaks to suppress). A Debug build: a few seconds.
asan_build=build/viewer-asan
asan_viewer="$asan_build/dnsr_viewer"
cmake -S examples-c/viewer -B "$asan_build" -DCMAKE_BUILD_TYPE=Debug -DDNSR_VIEWER_SANITIZE=ON \
  -DDNSR_LIB="$PWD/target/release/libdnsr.so" >/dev/null
cmake --build "$asan_build" -j "$(nproc)" >/dev/null

# ---- --help: every option options.cpp parses, every key window.cpp handles, every view name ----
help=$("$viewer" --help) || fail "--help exited with status $?"
options=$(grep -o 'a == "-[-a-z]*"' examples-c/viewer/options.cpp | cut -d'"' -f2)
[[ $(wc -w <<<"$options") -ge 10 ]] || fail "found only $(wc -w <<<"$options") options in options.cpp: update this test"
for opt in $options; do grep -qF -- "$opt" <<<"$help" || fail "--help does not list $opt"; done
keys=$(grep -o 'case GLFW_KEY_[A-Z0-9]*' examples-c/viewer/window.cpp | sed 's/case GLFW_KEY_//')
[[ $(wc -w <<<"$keys") -ge 12 ]] || fail "found only $(wc -w <<<"$keys") keys in window.cpp: update this test"
for key in $keys; do
  word=$key
  [[ $key == ESCAPE ]] && word=Esc
  # A key is described when it stands alone followed by its meaning: "6 dnsr tile classification", "Esc/Q quit".
  grep -qE "(^|[ ,/])$word([ /])" <<<"$help" || fail "--help does not describe key $word"
done
for view in noisy denoised reference composite tiles classification samples variance disocclusion; do
  grep -qw -- "$view" <<<"$help" || fail "--help does not name the view $view"
done
echo "help: lists $(wc -w <<<"$options") options and $(wc -w <<<"$keys") keys"

# read_png(path): the samples of an 8-bit PNG (gray, RGB or RGBA, not interlaced, any row filters: stb_image_write
# picks one per row), row after row. A module for the checks below (python3 with PYTHONPATH="$tmp").
cat > "$tmp/viewer_png.py" <<'PY'
import struct, zlib

def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        n = struct.unpack(">I", data[pos:pos + 4])[0]
        kind, payload = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", payload[:13])
            assert depth == 8 and interlace == 0, "not an 8-bit, non-interlaced PNG"
        elif kind == b"IDAT":
            idat += payload
        pos += 12 + n
    bpp = {0: 1, 2: 3, 6: 4}[color]
    raw = zlib.decompress(idat)
    stride = w * bpp
    assert len(raw) == (stride + 1) * h, "truncated image data"
    # Undo each row's filter (PNG spec, section 9): 0 none, 1 sub, 2 up, 3 average, 4 Paeth.
    out, prev = bytearray(), bytearray(stride)
    for y in range(h):
        kind, row = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = row[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if kind == 1:
                row[i] = (row[i] + a) & 255
            elif kind == 2:
                row[i] = (row[i] + b) & 255
            elif kind == 3:
                row[i] = (row[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
            else:
                assert kind == 0, f"unknown PNG filter {kind}"
        out += row
        prev = row
    return bytes(out)
PY

# Prints "min max" of a PNG's samples.
png_range() {
  PYTHONPATH="$tmp" python3 -c 'import sys, viewer_png; p = viewer_png.read_png(sys.argv[1]); print(min(p), max(p))' \
    "$1"
}

check_not_blank() {
  [[ -s "$1" ]] || fail "$1 missing or empty"
  read -r lo hi < <(png_range "$1") || fail "$1 is not a readable PNG"
  (( hi - lo >= 32 )) || fail "$1 is blank (samples $lo..$hi)"
}

# ---- Headless, with validation (and penumbra guidance, the default: hit distances written and read) ----
out="$tmp/headless"
status=0
"$viewer" --headless --validate --frames 8 --size 160x96 --out "$out" > "$tmp/headless.log" 2>&1 || status=$?
(( status == 0 )) || { cat "$tmp/headless.log"; fail "headless run exited with status $status"; }
for f in noisy denoised reference composite strip tiles; do check_not_blank "$out/$f.png"; done
# Deflated (stb_image_write), not stored: the 646x96 RGB strip well under its 186 kB of raw samples.
(( $(stat -c %s "$out/strip.png") < 186048 / 2 )) || fail "strip.png is $(stat -c %s "$out/strip.png") bytes: not compressed"
[[ -s "$out/report.json" ]] || fail "no report.json"
quality=$(python3 - "$out/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
noisy, denoised = r["rmse"]["noisy"], r["rmse"]["denoised"]
assert r["width"] == 160 and r["height"] == 96 and r["frames"] == 8, "report size/frames"
assert r["dnsr_gpu_ms"]["frame"] >= 1, "no dnsr timings"
# The default is penumbra guidance on: the shadow pass writes hit distances and dnsr reads them.
assert r["hit_distance"] is True and 0 < r["light_angular_size_rad"] < 3.1416, "penumbra guidance not on"
assert r["crease"]["pixels"] > 0, "no lit pixel next to a shadowed one: the crease metric measured nothing"
assert noisy > 0.02, f"the noisy shadow has almost no error ({noisy}): is the reference the same samples?"
ok = denoised < 0.7 * noisy
print(f"{'ok' if ok else 'BAD'} RMSE noisy {noisy:.4f} -> denoised {denoised:.4f} "
      f"(x{denoised / noisy:.2f}, PSNR {r['psnr_db']['denoised']:.1f} dB) on {r['device']}")
PY
) || fail "report.json check failed"
echo "headless: $quality"
[[ $quality == ok* ]] || fail "denoised RMSE is not below 0.7x the noisy RMSE"

# ---- --gbuffer packed: linear depth and octahedral normals through dnsr passes compiled against custom callbacks
# (examples-c/custom_gbuffer): the same scene, validation clean, the same error against the same reference ----
status=0
"$viewer" --headless --validate --gbuffer packed --frames 8 --size 160x96 --out "$tmp/packed" \
  > "$tmp/packed.log" 2>&1 || status=$?
(( status == 0 )) || { cat "$tmp/packed.log"; fail "--gbuffer packed exited with status $status"; }
python3 - "$out/report.json" "$tmp/packed/report.json" <<'PY' || fail "--gbuffer packed check failed"
import json, sys
default, packed = (json.load(open(p)) for p in sys.argv[1:])
assert packed["gbuffer"] == "packed" and default["gbuffer"] == "default", "G-buffer mode not recorded"
assert packed["rmse"]["noisy"] == default["rmse"]["noisy"], "the packed run traced other rays"
d, p = default["rmse"]["denoised"], packed["rmse"]["denoised"]
# RG16 octahedral normals against RGBA16F ones: nearly, not exactly, the same edge stops.
assert abs(p - d) <= 1e-3, f"denoised RMSE {d:.5f} with dnsr's callbacks, {p:.5f} with the engine's"
print(f"packed G-buffer: denoised RMSE {p:.5f} (default {d:.5f})")
PY

# ---- --rays 4: four rays per pixel handed to dnsr as per-pixel visibility (DNSR_SHADOW_INPUT_VISIBILITY):
# validation clean, and a lower error than one ray on the same scene; --rays with --gbuffer packed is refused ----
status=0
"$viewer" --headless --validate --rays 4 --frames 8 --size 160x96 --out "$tmp/rays" > "$tmp/rays.log" 2>&1 || status=$?
(( status == 0 )) || { cat "$tmp/rays.log"; fail "--rays 4 exited with status $status"; }
python3 - "$out/report.json" "$tmp/rays/report.json" <<'PY' || fail "--rays 4 check failed"
import json, sys
one, four = (json.load(open(p)) for p in sys.argv[1:])
assert one["rays_per_pixel"] == 1 and four["rays_per_pixel"] == 4, "rays per pixel not recorded"
d1, d4 = one["rmse"]["denoised"], four["rmse"]["denoised"]
assert d4 < d1, f"4 rays per pixel denoised to RMSE {d4:.5f}, no better than 1 ray ({d1:.5f})"
print(f"rays per pixel: denoised RMSE 1 ray {d1:.5f}, 4 rays {d4:.5f}")
PY
status=0
"$viewer" --headless --rays 2 --gbuffer packed --frames 1 --size 16x16 --out "$tmp/bad-rays" > /dev/null 2> "$tmp/rays.err" ||
  status=$?
(( status == 2 )) && grep -qF -- "--gbuffer packed takes one ray per pixel" "$tmp/rays.err" ||
  fail "--rays 2 --gbuffer packed: status $status, message: $(cat "$tmp/rays.err")"

# ---- --checkerboard: half a ray per pixel (DNSR_SHADOW_INPUT_CHECKERBOARD), against the 1-ray headless run above
# (same size, frames and camera): validation clean; the last frame traced exactly the 1-ray run's rays for the
# pixels of its phase and no others (its hit mask, report.json's fingerprint, is the 1-ray run's with the other
# pixels' bits cleared: shadow.comp skipped their rays), and noisy.png gives the others their traced neighbours'
# mean; the denoised RMSE is below the noisy one and at most 2x the 1-ray run's. 2x: after 8 frames each pixel has
# 4 rays of its own instead of 8 (sqrt(2) = 1.41x on the noise alone) and the neighbours' mean smears edges on top
# (1.6x measured on lavapipe); a phase dnsr and the shader disagree on gives about 10x. With --rays 2 or --gbuffer
# packed it is refused ----
status=0
"$viewer" --headless --validate --checkerboard --frames 8 --size 160x96 --out "$tmp/checkerboard" \
  > "$tmp/checkerboard.log" 2>&1 || status=$?
(( status == 0 )) || { cat "$tmp/checkerboard.log"; fail "--checkerboard exited with status $status"; }
checkerboard=$(PYTHONPATH="$tmp" python3 - "$out" "$tmp/checkerboard" <<'PY'
import json, struct, sys, viewer_png
one_dir, cb_dir = sys.argv[1:]
one, cb = (json.load(open(f"{d}/report.json")) for d in (one_dir, cb_dir))
assert one["checkerboard"] is False and cb["checkerboard"] is True, "checkerboard not recorded"
w, h = cb["width"], cb["height"]
phase = (cb["frames"] - 1) % 2  # the last frame's: the phase alternates from 0
rays, noisy = (viewer_png.read_png(f"{d}/noisy.png") for d in (one_dir, cb_dir))  # 0 occluded, 255 lit
tiles_x = (w + 7) // 8
words = [0] * (tiles_x * ((h + 3) // 4))
for y in range(h):
    for x in range(w):
        i = y * w + x
        if (x + y) % 2 == phase:
            assert noisy[i] == rays[i], f"pixel ({x}, {y}) traced another ray than the 1-ray run's"
            words[y // 4 * tiles_x + x // 8] |= (rays[i] == 0) << (y % 4 * 8 + x % 8)
        else:
            near = [rays[(y + dy) * w + x + dx] / 255 for dx, dy in ((-1, 0), (1, 0), (0, -1), (0, 1))
                    if 0 <= x + dx < w and 0 <= y + dy < h]
            assert noisy[i] == int(sum(near) / len(near) * 255 + 0.5), f"pixel ({x}, {y}): not its neighbours' mean"
fnv = 0xcbf29ce484222325
for byte in struct.pack(f"<{len(words)}I", *words):
    fnv = (fnv ^ byte) * 0x100000001b3 % 2**64
assert cb["per_light"][0]["hit_mask_fnv1a"] == f"{fnv:016x}", "the hit mask holds rays of the untraced pixels"
d1, noisy_rmse, dc = one["rmse"]["denoised"], cb["rmse"]["noisy"], cb["rmse"]["denoised"]
assert dc < noisy_rmse, f"checkerboard not denoised: RMSE noisy {noisy_rmse:.5f}, denoised {dc:.5f}"
assert dc <= 2 * d1, f"checkerboard denoised RMSE {dc:.5f} is over 2x the 1-ray run's ({d1:.5f})"
print(f"denoised RMSE 1 ray {d1:.5f}, checkerboard {dc:.5f} (x{dc / d1:.2f}, at most 2x; its noisy "
      f"{noisy_rmse:.5f}); shadow pass {one['viewer_gpu_ms']['shadow']:.2f} -> {cb['viewer_gpu_ms']['shadow']:.2f} ms")
PY
) || fail "--checkerboard check failed"
echo "checkerboard: $checkerboard"
for bad in "--rays 2:--checkerboard takes --rays 1" "--gbuffer packed:--checkerboard takes --gbuffer default"; do
  status=0
  # ${bad%%:*} unquoted: two words.
  "$viewer" --headless --checkerboard ${bad%%:*} --frames 1 --size 16x16 --out "$tmp/bad-cb" > /dev/null \
    2> "$tmp/cb.err" || status=$?
  (( status == 2 )) && grep -qF -- "${bad#*:}" "$tmp/cb.err" ||
    fail "--checkerboard ${bad%%:*}: status $status, message: $(cat "$tmp/cb.err")"
done

# ---- --hybrid: cascaded shadow maps, dnsr's classifier and rays only for the pixels it lists (vkCmdDispatchIndirect
# on its counts), against full tracing of the same size, frames and camera (the headless run above, with penumbra
# guidance like the hybrid run, and one without): validation clean; part of the receivers traced, the rest
# decided; every traced pixel's ray the full run's (the same sample, and the classifier's interval must not cut off
# its occluder); hardly any decided pixel against the reference's majority; the denoised RMSE within 10% of full
# tracing's (3.5% measured on lavapipe with the default preset, Quality: the cascades' verdicts are exact, but a few
# outer-penumbra pixels whose blockers fall between the taps are decided lit every frame instead of averaging their
# rays). Then without guidance, reversed rays, one cascade, 8 taps and a cut-off: within 15% (12.6% measured with
# Quality, 6.7% with Balanced, whose own error without guidance is a quarter higher, so the decided pixels' fixed
# error weighs less). Unsupported combinations and bad settings are usage errors ----
for mode in "--hit-distance off" "--hybrid" "--hybrid --hit-distance off --reverse-rays --cascades 1 --taps 8 --tile-cutoff 2" \
            "--hybrid --gbuffer packed"; do
  status=0
  name=$(echo "$mode" | tr -dc 'a-z0-9')
  # $mode unquoted: several words.
  "$viewer" --headless --validate $mode --frames 8 --size 160x96 --out "$tmp/$name" > "$tmp/hybrid.log" 2>&1 ||
    status=$?
  (( status == 0 )) || { cat "$tmp/hybrid.log"; fail "$mode exited with status $status"; }
done
check_not_blank "$tmp/hybrid/hybrid.png"
hybrid=$(PYTHONPATH="$tmp" python3 - "$tmp" "$out" <<'PY'
import json, sys, viewer_png
tmp, guided_dir = sys.argv[1:]
full, hybrid, other, guided = (json.load(open(f"{d}/report.json")) for d in (
    f"{tmp}/hitdistanceoff", f"{tmp}/hybrid", f"{tmp}/hybridhitdistanceoffreverserayscascades1taps8tilecutoff2",
    guided_dir))
assert full["hybrid"] is None and hybrid["hybrid"]["cascades"] == 2 and other["hybrid"]["reverse_rays"], "hybrid settings"
assert hybrid["hit_distance"] and guided["hit_distance"] and not other["hit_distance"], "guidance not recorded"
assert full["traced"]["fraction"] == 1.0, "full tracing did not trace every receiver"
for r in (hybrid, other):
    t = r["traced"]
    assert 0.05 < t["fraction"] < 0.9 and t["rays_saved"] > 0 and t["tiles_traced"] < t["tiles"], f"traced {t}"
    assert t["decided_wrong"] <= 0.002 * t["receivers"], f"{t['decided_wrong']} decided pixels against the reference"
    assert r["viewer_gpu_ms"]["classify"] > 0 and r["viewer_gpu_ms"]["cascades"] > 0, "no hybrid timings"
    assert r["dnsr_gpu_ms"]["classify"] > 0, "no classifier time from dnsr_context_get_classifier_timings"
# Traced pixels (orange or dark red in hybrid.png, the grid darker) took the full run's ray.
w, h = hybrid["width"], hybrid["height"]
colours = viewer_png.read_png(f"{tmp}/hybrid/hybrid.png")  # RGB
rays_full, rays_hybrid = (viewer_png.read_png(f"{tmp}/{d}/noisy.png") for d in ("hitdistanceoff", "hybrid"))
traced = [i for i in range(w * h) if colours[3 * i] - colours[3 * i + 2] > 60]
assert len(traced) == hybrid["traced"]["rays"], f"{len(traced)} traced pixels in hybrid.png, report says {hybrid['traced']['rays']}"
cut = sum(rays_full[i] != rays_hybrid[i] for i in traced)
assert cut == 0, f"{cut} traced pixels' rays differ from full tracing's: the interval cut off their occluder"
for h, f, what, bound in ((hybrid, guided, "guided", 1.1), (other, full, "unguided", 1.15)):
    dh, df = h["rmse"]["denoised"], f["rmse"]["denoised"]
    assert dh <= bound * df, f"hybrid denoised RMSE {dh:.5f} over {bound}x full tracing's {df:.5f} ({what})"
print(f"{hybrid['traced']['fraction']:.1%} of the receivers traced ({other['traced']['fraction']:.1%} with 1 cascade, "
      f"8 taps, cut-off 2, reversed rays), {hybrid['traced']['decided_wrong']} decided against the reference; "
      f"denoised RMSE {hybrid['rmse']['denoised']:.5f} against full tracing's {guided['rmse']['denoised']:.5f} "
      f"(unguided: {other['rmse']['denoised']:.5f}, {full['rmse']['denoised']:.5f})")
PY
) || fail "--hybrid check failed"
echo "hybrid: $hybrid"
# The classifier compiled against the packed G-buffer's callbacks (linear depth, octahedral RG16 normals) decides
# what dnsr's own does on the default G-buffer, up to the normals' rounding in its tangent-plane test.
python3 - "$tmp/hybrid/report.json" "$tmp/hybridgbufferpacked/report.json" <<'PY' || fail "--hybrid --gbuffer packed check failed"
import json, sys
default, packed = (json.load(open(p)) for p in sys.argv[1:])
assert packed["gbuffer"] == "packed" and packed["hybrid"], "packed hybrid run not recorded"
rd, rp = default["traced"]["rays"], packed["traced"]["rays"]
assert abs(rp - rd) <= max(2, 0.01 * rd), f"{rp} rays traced with the engine's classifier callbacks, {rd} with dnsr's"
d, p = default["rmse"]["denoised"], packed["rmse"]["denoised"]
assert abs(p - d) <= 1e-3, f"denoised RMSE {d:.5f} with dnsr's callbacks, {p:.5f} with the engine's"
print(f"hybrid, packed G-buffer: {rp} rays traced (default {rd}), denoised RMSE {p:.5f} (default {d:.5f})")
PY
for bad in "--point-light:--hybrid takes the directional light" "--lights 2:--hybrid takes one light" \
           "--rays 2:--hybrid takes one ray per pixel" \
           "--taps 12:--taps wants 8, 16, 24 or 32, got '12'" "--cascades 5:--cascades wants a number in 1..4" \
           "--blocker-offset -1:--blocker-offset wants scene radii in 0..1"; do
  status=0
  # ${bad%%:*} unquoted: two words.
  "$viewer" --headless --hybrid ${bad%%:*} --frames 1 --size 16x16 --out "$tmp/bad-hybrid" > /dev/null \
    2> "$tmp/hybrid.err" || status=$?
  (( status == 2 )) && grep -qF -- "${bad#*:}" "$tmp/hybrid.err" ||
    fail "--hybrid ${bad%%:*}: status $status, message: $(cat "$tmp/hybrid.err")"
done

# ---- --normal-detail: normal-map-like bumps. With --normal-detail-for dnsr only dnsr's packed normals get them: the
# shadow rays (the noisy image) stay those of the smooth normals bit for bit, and dnsr's output changes; with all,
# the rays' facing test takes them too. Validation clean; bad values are usage errors ----
for mode in "--gbuffer packed" "--gbuffer packed --normal-detail 0.5 --normal-detail-for dnsr" "--normal-detail 0.5"; do
  name=$(echo "$mode" | tr -dc 'a-z0-9')
  # $mode unquoted: several words.
  "$viewer" --headless --validate $mode --frames 4 --size 96x64 --out "$tmp/$name" > "$tmp/detail.log" 2>&1 ||
    { cat "$tmp/detail.log"; fail "$mode failed"; }
done
cmp -s "$tmp/gbufferpacked/noisy.png" "$tmp/gbufferpackednormaldetail05normaldetailfordnsr/noisy.png" ||
  fail "--normal-detail-for dnsr changed the shadow rays"
cmp -s "$tmp/gbufferpacked/denoised.png" "$tmp/gbufferpackednormaldetail05normaldetailfordnsr/denoised.png" &&
  fail "--normal-detail-for dnsr did not reach dnsr's normals"
cmp -s "$tmp/gbufferpacked/noisy.png" "$tmp/normaldetail05/noisy.png" && fail "--normal-detail 0.5 left the rays' facing test alone"
for bad in "--normal-detail 2:--normal-detail wants" "--normal-detail-for dnsr:--normal-detail-for dnsr takes --gbuffer packed" \
           "--normal-detail-for some:--normal-detail-for wants all or dnsr"; do
  status=0
  # ${bad%%:*} unquoted: two words.
  "$viewer" --headless ${bad%%:*} --frames 1 --size 16x16 --out "$tmp/bad-detail" > /dev/null 2> "$tmp/detail.err" || status=$?
  (( status == 2 )) && grep -qF -- "${bad#*:}" "$tmp/detail.err" ||
    fail "${bad%%:*}: status $status, message: $(cat "$tmp/detail.err")"
done
echo "normal detail: the shadow rays kept with --normal-detail-for dnsr, dnsr's output changed"

# ---- --lights 2: a second light (the first turned 100 degrees about the up axis), both denoised by one
# dnsr_lights_record call. For the default inputs, --rays 2 (a visibility image per light), --gbuffer packed and
# --checkerboard (both lights' masks traced for the same half of the pixels, one phase in the shared dispatch),
# each against the same run with one light (dnsr_shadows_record): validation clean; light 0's hit mask and
# denoised shadow bit for bit the same (report.json's fingerprints of the float readback: dnsr_lights_record gives
# each light what dnsr_shadows_record gives it alone, and light 0's rays keep their seeds); light 1 traced towards
# another light (its reference shadows elsewhere) and denoised. Bad light counts are usage errors ----
for extra in "" "--rays 2" "--gbuffer packed" "--checkerboard"; do
  for n in 1 2; do
    status=0
    # $extra unquoted: none, one or two words.
    "$viewer" --headless --validate --lights $n $extra --frames 4 --size 64x48 --out "$tmp/lights$n" \
      > "$tmp/lights.log" 2>&1 || status=$?
    (( status == 0 )) || { cat "$tmp/lights.log"; fail "--lights $n $extra exited with status $status"; }
  done
  for f in noisy denoised reference; do check_not_blank "$tmp/lights2/${f}_light1.png"; done
  PYTHONPATH="$tmp" python3 - "$tmp" "${extra:-default inputs}" <<'PY' || fail "--lights 2 $extra check failed"
import json, sys, viewer_png
tmp, inputs = sys.argv[1:]
one, two = (json.load(open(f"{tmp}/lights{n}/report.json")) for n in (1, 2))
assert one["lights"] == 1 and two["lights"] == 2 and len(two["per_light"]) == 2, "light count not recorded"
alone, light0, light1 = one["per_light"][0], two["per_light"][0], two["per_light"][1]
assert light0 == alone, f"light 0 changed when a second light came: {alone} alone, {light0} with light 1"
assert light1["hit_mask_fnv1a"] != light0["hit_mask_fnv1a"], "light 1's hit mask is light 0's"
assert light1["denoised_fnv1a"] != light0["denoised_fnv1a"], "light 1's denoised shadow is light 0's"
# Another light, not light 0 with other random numbers: the references (sky is lit in both) disagree somewhere.
ref0, ref1 = (viewer_png.read_png(f"{tmp}/lights2/{f}.png") for f in ("reference", "reference_light1"))
apart = sum(abs(a - b) > 128 for a, b in zip(ref0, ref1)) / len(ref0)
assert apart > 0.02, f"light 1 shadows the same pixels as light 0 (they disagree on {apart:.1%})"
noisy, denoised = light1["rmse"]["noisy"], light1["rmse"]["denoised"]
assert denoised < noisy, f"light 1 not denoised: RMSE noisy {noisy:.4f}, denoised {denoised:.4f}"
print(f"lights ({inputs}): light 0 the same bit for bit with a second light; light 1 shadows "
      f"{apart:.0%} of the pixels otherwise, RMSE noisy {noisy:.4f} -> denoised {denoised:.4f}")
PY
done
for n in 0 3 two; do
  status=0
  "$viewer" --headless --lights $n --frames 1 --size 16x16 --out "$tmp/bad-lights" > /dev/null 2> "$tmp/lights.err" ||
    status=$?
  (( status == 2 )) && grep -qF -- "--lights wants a number in 1..2, got '$n'" "$tmp/lights.err" ||
    fail "--lights $n: status $status, message: $(cat "$tmp/lights.err")"
done

# ---- dnsr presets: Quality through dnsr_settings_init_preset, validation clean; a bad name is a usage error ----
# Also the unguided path (--hit-distance off), and a reference saved by one run and measured against by another
# (the guided Quality run: same frames, so the same last frame; the RMSE must then be that of a rendered one).
status=0
"$viewer" --headless --validate --preset quality --hit-distance off --frames 4 --size 64x48 --out "$tmp/quality" \
  --save-reference "$tmp/quality.ref" > "$tmp/quality.log" 2>&1 || status=$?
(( status == 0 )) || { cat "$tmp/quality.log"; fail "--preset quality exited with status $status"; }
grep -q '"preset": "quality"' "$tmp/quality/report.json" || fail "report.json does not name the quality preset"
grep -q '"hit_distance": false' "$tmp/quality/report.json" || fail "report.json does not say guidance is off"
status=0
"$viewer" --headless --validate --preset quality --hit-distance on --frames 4 --size 64x48 --out "$tmp/guided" \
  --load-reference "$tmp/quality.ref" > "$tmp/guided.log" 2>&1 || status=$?
(( status == 0 )) || { cat "$tmp/guided.log"; fail "--hit-distance on --load-reference exited with status $status"; }
python3 - "$tmp/quality/report.json" "$tmp/guided/report.json" <<'PY' || fail "--load-reference check failed"
import json, sys
off, on = (json.load(open(p)) for p in sys.argv[1:])
assert off["hit_distance"] is False and on["hit_distance"] is True, "guidance setting not recorded"
assert on["reference_file"] and on["reference_samples"] == off["reference_samples"], "reference not loaded"
assert on["rmse"]["noisy"] == off["rmse"]["noisy"], "guidance changed the hit mask, or the loaded reference differs"
PY
status=0
"$viewer" --headless --hit-distance maybe --frames 1 --size 16x16 --out "$tmp/bad-hd" > /dev/null 2> "$tmp/hd.err" ||
  status=$?
(( status == 2 )) && grep -qF -- "--hit-distance wants on or off, got 'maybe'" "$tmp/hd.err" ||
  fail "--hit-distance maybe: status $status, message: $(cat "$tmp/hd.err")"
status=0
"$viewer" --headless --preset best --frames 1 --size 16x16 --out "$tmp/bad-preset" > /dev/null 2> "$tmp/preset.err" ||
  status=$?
(( status == 2 )) && grep -qF -- "--preset wants fast, balanced or quality, got 'best'" "$tmp/preset.err" ||
  fail "--preset best: status $status, message: $(cat "$tmp/preset.err")"
echo "presets: quality ran clean unguided and guided (against the saved reference), 'best' and 'maybe' refused"

# ---- --set: single settings after the preset ----
# Every DnsrSettings field of the header is a name --set takes (a new setting cannot be left out), a changed
# setting changes the output against the same reference and report.json lists it, and a name dnsr does not have
# (status 2) and a value out of dnsr's range (status 1, dnsr's own message) are refused.
fields=$(awk '/^typedef struct DnsrSettings/,/^} DnsrSettings;/' include/dnsr.h | grep -oE '^  (uint32_t|float) [a-zA-Z0-9]+;' |
  awk '{print $2}' | tr -d ';')
[[ $(wc -w <<<"$fields") -ge 20 ]] || fail "found only $(wc -w <<<"$fields") DnsrSettings fields in include/dnsr.h"
for f in $fields; do
  "$viewer" --set "$f=1x" > /dev/null 2> "$tmp/set.err" && fail "--set $f=1x accepted"
  grep -qF -- "--set $f wants a finite number" "$tmp/set.err" || fail "--set does not know DnsrSettings::$f: $(cat "$tmp/set.err")"
done
status=0
"$viewer" --headless --validate --preset quality --hit-distance off --frames 4 --size 64x48 --out "$tmp/set" \
  --load-reference "$tmp/quality.ref" --set filterPasses=1,minCurrentWeight=0.5 > "$tmp/set.log" 2>&1 || status=$?
(( status == 0 )) || { cat "$tmp/set.log"; fail "--set filterPasses=1,minCurrentWeight=0.5 exited with status $status"; }
python3 - "$tmp/quality/report.json" "$tmp/set/report.json" <<'PY' || fail "--set check failed"
import json, sys
plain, changed = (json.load(open(p)) for p in sys.argv[1:])
assert changed["settings"] == {"filterPasses": 1, "minCurrentWeight": 0.5}, changed.get("settings")
assert "settings" not in plain, "a run without --set lists settings"
assert len(changed["dnsr_gpu_ms"]["filter"]) == 1, changed["dnsr_gpu_ms"]
assert changed["rmse"]["noisy"] == plain["rmse"]["noisy"] and changed["rmse"]["denoised"] != plain["rmse"]["denoised"]
PY
status=0
"$viewer" --headless --set filterPass=1 --frames 1 --size 16x16 --out "$tmp/bad-set" > /dev/null 2> "$tmp/set.err" ||
  status=$?
(( status == 2 )) && grep -qF -- "--set wants NAME=VALUE with NAME one of filterPasses" "$tmp/set.err" ||
  fail "--set filterPass=1: status $status, message: $(cat "$tmp/set.err")"
status=0
"$viewer" --headless --set normalPower=300 --frames 1 --size 16x16 --out "$tmp/bad-set" > /dev/null 2> "$tmp/set.err" ||
  status=$?
(( status == 1 )) && grep -qF "setting normalPower is 300; it must be in [0, 256]" "$tmp/set.err" ||
  fail "--set normalPower=300: status $status, message: $(cat "$tmp/set.err")"
echo "--set: takes all $(wc -w <<<"$fields") DnsrSettings fields, changes the output, refuses unknown names and values out of range"

# ---- --debug-view: the last frame's dnsr output is a debug view; the frames before it are the same run ----
for name in variance run; do
  status=0
  "$viewer" --headless --validate --preset quality --hit-distance off --frames 4 --size 64x48 --out "$tmp/debug-$name" \
    --load-reference "$tmp/quality.ref" --debug-view "$name" > "$tmp/debug-view.log" 2>&1 || status=$?
  (( status == 0 )) || { cat "$tmp/debug-view.log"; fail "--debug-view $name exited with status $status"; }
  python3 - "$tmp/quality/report.json" "$tmp/debug-$name/report.json" "$name" <<'PY' || fail "--debug-view $name check failed"
import json, sys
plain, view = (json.load(open(p)) for p in sys.argv[1:3])
assert plain["debug_view"] is None and view["debug_view"] == sys.argv[3], (plain["debug_view"], view["debug_view"])
assert view["per_light"][0]["hit_mask_fnv1a"] == plain["per_light"][0]["hit_mask_fnv1a"], "not the same frames"
assert view["per_light"][0]["denoised_fnv1a"] != plain["per_light"][0]["denoised_fnv1a"], "the view is the shadow"
PY
done
for bad in "--headless --debug-view shadows" "--debug-view variance"; do
  status=0
  # shellcheck disable=SC2086
  "$viewer" $bad --frames 1 --size 16x16 --out "$tmp/bad-view" > /dev/null 2> "$tmp/view.err" || status=$?
  (( status == 2 )) && grep -qF -- "--debug-view" "$tmp/view.err" || fail "$bad: status $status, message: $(cat "$tmp/view.err")"
done
echo "--debug-view variance and run: the last frame's output is the view (same frames before it); a bad name and window mode refused"

# ---- Do no harm: a fixed subset of the procedural scene family (family.py; make viewer-accuracy runs 100) ----
# Ten seeded scenes (with and without a ground plane, hard and soft lights, point lights), a still camera, the
# Quality preset: never worse than the 1-spp input, exact pixels within 1/255 (hard shadows only: RMSE <= 0.002),
# shadowed silhouettes within 1/255 on average, thin features keep 80% of their contrast.
python3 examples-c/viewer/family.py "$viewer" "$tmp/family" --first 1000 --count 10 --presets quality \
  --camera still --check quality > "$tmp/family.out" 2>&1 || fail "do no harm: $(tail -n 20 "$tmp/family.out")"
echo "do no harm: $(tail -n 1 "$tmp/family.out")"
# One of them with its own camera, an orbit: a staircase whose lit tops stand above the shadowed ground, both facing
# up, so that a young pixel's history footprint holds both (the footprint leaves out texels at another depth:
# docs/do-no-harm.md, "Footprint texels at this depth"; before it, RMSE 0.0025 where the input is exact).
python3 examples-c/viewer/family.py "$viewer" "$tmp/family-orbit" --first 1005 --count 1 --presets quality \
  --check quality > "$tmp/family-orbit.out" 2>&1 || fail "do no harm, orbit: $(tail -n 20 "$tmp/family-orbit.out")"
echo "do no harm, orbit: $(tail -n 1 "$tmp/family-orbit.out")"

# ---- --validate counts validation messages, not the Vulkan loader's notices ----
# With VK_INSTANCE_LAYERS naming the layer, the loader warns through the same debug messenger that it adds the
# layer from the environment (pMessageIdName "Loader Message", type GENERAL): that is no validation failure.
status=0
VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation "$viewer" --headless --validate --frames 2 --size 32x32 \
  --out "$tmp/env-layers" > "$tmp/env-layers.log" 2>&1 || status=$?
(( status == 0 )) ||
  { cat "$tmp/env-layers.log"; fail "--validate with VK_INSTANCE_LAYERS set exited with status $status"; }
notices=$(grep -c '^loader notice' "$tmp/env-layers.log" || true)
# The control: real validation-layer messages must still count. Best-practices validation (switched on here
# through the environment) reports the viewer's use of VK_EXT_debug_utils, a debugging extension.
status=0
VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation VK_LAYER_ENABLES=VK_VALIDATION_FEATURE_ENABLE_BEST_PRACTICES_EXT \
  "$viewer" --headless --validate --frames 1 --size 16x16 --out "$tmp/best-practices" \
  > "$tmp/best-practices.log" 2>&1 || status=$?
counted=$(grep -c '^validation: ' "$tmp/best-practices.log" || true)
if (( counted > 0 )); then
  (( status == 1 )) || { cat "$tmp/best-practices.log"; fail "$counted validation message(s) but exit status $status"; }
  control="$counted best-practices message(s) still fail it"
else
  control="control skipped: best-practices validation reported nothing here"
fi
echo "validate: VK_INSTANCE_LAYERS set: status 0 ($notices loader notice(s) shown, not counted); $control"

# ---- Window mode under Xvfb (24-bit screen: Vulkan presentation needs a true-colour visual) ----
window="skipped (no xvfb-run)"
if command -v xvfb-run >/dev/null; then
  shot="$tmp/screenshot.png"
  status=0
  xvfb-run -a -s "-screen 0 1024x768x24" "$viewer" --validate --size 160x96 --frames 4 --screenshot "$shot" \
    > "$tmp/window.log" 2>&1 || status=$?
  (( status == 0 )) || { cat "$tmp/window.log"; fail "window run exited with status $status"; }
  check_not_blank "$shot"
  # The reference view accumulates while the camera stands still: exercises the progressive path (and the
  # window without penumbra guidance).
  xvfb-run -a -s "-screen 0 1024x768x24" "$viewer" --validate --size 160x96 --frames 3 --view reference \
    --hit-distance off --screenshot "$tmp/reference.png" > "$tmp/window.log" 2>&1 || status=$?
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
  # Two lights (one dnsr_lights_record call) lighting the composite together.
  xvfb-run -a -s "-screen 0 1024x768x24" "$viewer" --validate --size 160x96 --frames 3 --lights 2 \
    --screenshot "$tmp/lights.png" > "$tmp/window.log" 2>&1 || status=$?
  (( status == 0 )) || { cat "$tmp/window.log"; fail "window run (--lights 2) exited with status $status"; }
  check_not_blank "$tmp/lights.png"
  # Hybrid mode's views: what decided each pixel, and the pixels traced per tile.
  for v in hybrid traced; do
    xvfb-run -a -s "-screen 0 1024x768x24" "$viewer" --validate --size 160x96 --frames 3 --hybrid --view "$v" \
      --screenshot "$tmp/$v.png" > "$tmp/window.log" 2>&1 || status=$?
    (( status == 0 )) || { cat "$tmp/window.log"; fail "window run (--hybrid, $v view) exited with status $status"; }
    check_not_blank "$tmp/$v.png"
  done
  window="window screenshots ok (composite, reference, 4 dnsr debug views, two lights, 2 hybrid views)"
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

# Files that are valid, but not what the viewer reads: each must be named for what it is.
def write_json(name, doc):
    with open(os.path.join(out, name), "w") as f:
        json.dump(doc, f)

def glb(name, doc, version=2):
    text = json.dumps(doc).encode()
    text += b" " * ((4 - len(text) % 4) % 4)
    with open(os.path.join(out, name), "wb") as f:
        if version == 1:  # KHR_binary_glTF: magic, version, length, content length, content format 0 (JSON)
            f.write(b"glTF" + struct.pack("<IIII", 1, 20 + len(text), len(text), 0) + text)
        else:
            f.write(b"glTF" + struct.pack("<III", 2, 20 + len(text), len(text)) + b"JSON" + text)

# glTF 1.0: objects keyed by id where 2.0 has arrays, and "scene" an id.
gltf1 = {
    "asset": {"version": "1.0"},
    "scene": "defaultScene",
    "scenes": {"defaultScene": {"nodes": ["node_1"]}},
    "nodes": {"node_1": {"meshes": ["mesh_1"], "children": []}},
    "meshes": {"mesh_1": {"primitives": [{"attributes": {"POSITION": "accessor_pos"}, "mode": 4}]}},
    "accessors": {"accessor_pos": {"bufferView": "view_1", "byteOffset": 0, "byteStride": 12,
                                   "componentType": 5126, "count": 3, "type": "VEC3"}},
    "bufferViews": {"view_1": {"buffer": "buffer_1", "byteOffset": 0, "byteLength": 36, "target": 34962}},
    "buffers": {"buffer_1": {"uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(36)).decode(),
                             "byteLength": 36, "type": "arraybuffer"}},
}
write_json("gltf1.gltf", gltf1)
glb("gltf1.glb", gltf1, version=1)
# Older still: no "asset" object, a top-level "version" instead.
gltf1_old = {k: v for k, v in gltf1.items() if k != "asset"}
gltf1_old["version"] = "1.0"
write_json("gltf1_top_level_version.gltf", gltf1_old)

# Draco: the primitive's data is in the extension's compressed buffer view; its accessors have no bufferView.
draco = gltf(tri, indices=[0, 1, 2])
for a in draco["accessors"]:
    del a["bufferView"]
draco["meshes"][0]["primitives"][0]["extensions"] = {
    "KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}}
draco["extensionsUsed"] = ["KHR_draco_mesh_compression"]
write_json("draco_used_no_fallback.gltf", draco)  # the compression only "used": no fallback data either
draco["extensionsRequired"] = ["KHR_draco_mesh_compression"]
write_json("draco_required.gltf", draco)
glb("draco_required.glb", draco)

# meshopt: a buffer view whose bytes live compressed in another buffer (no fallback buffer data).
meshopt = gltf(tri)
meshopt["buffers"].append({"byteLength": 36, "extensions": {"EXT_meshopt_compression": {"fallback": True}}})
meshopt["bufferViews"][0] = {"buffer": 1, "byteOffset": 0, "byteLength": 36, "extensions": {
    "EXT_meshopt_compression": {"buffer": 0, "byteOffset": 0, "byteLength": 36, "byteStride": 12,
                                "mode": "ATTRIBUTES", "count": 3}}}
meshopt["extensionsUsed"] = meshopt["extensionsRequired"] = ["EXT_meshopt_compression"]
write_json("meshopt_required.gltf", meshopt)

# An extension the viewer has never heard of, required.
unknown = gltf(tri)
unknown["extensionsUsed"] = unknown["extensionsRequired"] = ["EXT_made_up_geometry"]
write_json("unknown_required_extension.gltf", unknown)

# Buffer URIs that name no regular file (the files are made below): a FIFO, a directory, a character device.
write_json("buffer_fifo.gltf", gltf(tri, uri="fifo.bin"))
write_json("buffer_directory.gltf", gltf(tri, uri="directory.bin"))
write_json("buffer_dev_zero.gltf", gltf(tri, uri="zero.bin"))
# "extras" nested 20,000 deep (tinygltf's recursive parser overflowed the stack), and 300 deep under a key of its own.
deep = gltf(tri)
deep["extras"] = "@DEEP@"
with open(os.path.join(out, "deep_extras.gltf"), "w") as f:
    f.write(json.dumps(deep).replace('"@DEEP@"', "[" * 20000 + "]" * 20000))
with open(os.path.join(out, "deep_300.gltf"), "w") as f:
    f.write(json.dumps(deep).replace('"@DEEP@"', '{"a": ' * 300 + "0" + "}" * 300))
# A PNG named .gltf: tinygltf's parse error quotes the bytes; the message must stay printable.
with open(os.path.join(out, "png_bytes.gltf"), "wb") as f:
    f.write(b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\0\x10\0\0\0\x10\x08\x02\0\0\0\x90\x91h6")
PY
# Not files at all: a directory (tinygltf used to ask for 2^63 bytes) and a FIFO (open() used to block forever).
mkdir "$tmp/bad/directory.gltf"
mkfifo "$tmp/bad/fifo.gltf"
# The same as buffer URIs: tinygltf's own file reading blocked on the FIFO too.
mkdir "$tmp/bad/directory.bin"
mkfifo "$tmp/bad/fifo.bin"
ln -s /dev/zero "$tmp/bad/zero.bin"

# The message each of these must give (the other cases: any one-line message).
declare -A expect=(
  [directory.gltf]="directory.gltf is a directory, not a glTF file"
  [fifo.gltf]="fifo.gltf is a FIFO (named pipe), not a glTF file"
  [gltf1.gltf]="glTF 1.0 is not supported (dnsr_viewer reads glTF 2.0)"
  [gltf1.glb]="glTF 1.0 is not supported (dnsr_viewer reads glTF 2.0)"
  [gltf1_top_level_version.gltf]="glTF 1.0 is not supported (dnsr_viewer reads glTF 2.0)"
  [draco_required.gltf]="Draco compression (KHR_draco_mesh_compression) is not supported"
  [draco_required.glb]="Draco compression (KHR_draco_mesh_compression) is not supported"
  [draco_used_no_fallback.gltf]="Draco compression (KHR_draco_mesh_compression) is not supported"
  [meshopt_required.gltf]="meshopt compression (EXT_meshopt_compression) is not supported"
  [unknown_required_extension.gltf]="requires extension EXT_made_up_geometry"
  [deep_extras.gltf]="the JSON nests arrays and objects deeper than 256 levels"
  [deep_300.gltf]="the JSON nests arrays and objects deeper than 256 levels"
  [buffer_fifo.gltf]="fifo.bin is a FIFO (named pipe), not a buffer or image file"
  [buffer_directory.gltf]="directory.bin is a directory, not a buffer or image file"
  [buffer_dev_zero.gltf]="zero.bin is a character device, not a buffer or image file"
)
bad=0
for v in "$viewer" "$asan_viewer"; do
  [[ $v == "$asan_viewer" ]] && label=" (ASan+UBSan)" || label=""
  for scene in "$tmp"/bad/*.gltf "$tmp"/bad/*.glb "$tmp/bad/does_not_exist.gltf"; do
    status=0
    # timeout: a viewer that hangs (as on the FIFO) fails the test instead of stalling it.
    timeout 20 "$v" "$scene" --headless --frames 1 --size 16x16 --out "$tmp/bad-out" > "$tmp/bad.out" \
      2> "$tmp/bad.err" || status=$?
    name=$(basename "$scene")$label
    (( status != 124 )) || fail "$name: still running after 20 s (hangs)"
    (( status < 128 )) || fail "$name: crashed (status $status): $(cat "$tmp/bad.err")"
    (( status == 2 )) || fail "$name: exit status $status, expected 2: $(cat "$tmp/bad.err")"
    lines=$(wc -l < "$tmp/bad.err")
    [[ $lines -eq 1 ]] || fail "$name: expected a one-line message, got $lines lines: $(cat "$tmp/bad.err")"
    want=${expect[$(basename "$scene")]:-}
    [[ -z $want ]] || grep -qF -- "$want" "$tmp/bad.err" ||
      fail "$name: the message should say '$want': $(cat "$tmp/bad.err")"
    ! LC_ALL=C grep -q '[^[:print:]]' "$tmp/bad.err" || fail "$name: unprintable bytes in the message: $(cat -v "$tmp/bad.err")"
    [[ -n $label ]] || echo "bad input $name: $(cat "$tmp/bad.err")"
    bad=$((bad + 1))
  done
done

# ---- Triangle strips and fans (primitive modes 5 and 6) load as triangle lists: a quad each, two triangles ----
python3 - "$tmp/modes" <<'PY'
import base64, json, os, struct, sys
out = sys.argv[1]
os.makedirs(out)
for name, mode, quad in (("strip", 5, [(0, 0, 0), (1, 0, 0), (0, 0, 1), (1, 0, 1)]),
                         ("fan", 6, [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)])):
    data = b"".join(struct.pack("<3f", *p) for p in quad)
    doc = {"asset": {"version": "2.0"},
           "buffers": [{"byteLength": len(data),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
           "bufferViews": [{"buffer": 0, "byteLength": len(data)}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                          "min": [0, 0, 0], "max": [1, 0, 1]}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": mode}]}],
           "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}
    with open(os.path.join(out, name + ".gltf"), "w") as f:
        json.dump(doc, f)
    if name == "strip":  # the same with "scene" as a string: tinygltf ignores it without a word
        with open(os.path.join(out, "scene_string.gltf"), "w") as f:
            json.dump(dict(doc, scene="0"), f)
        # Members of the wrong type in a material, a texture and names: tinygltf ignores them without a word.
        bad = dict(doc, materials=[{"name": 7, "doubleSided": "yes"}], textures=[{"source": "0"}],
                   meshes=[dict(doc["meshes"][0], name=["quad"])], nodes=[{"mesh": 0, "name": None}])
        with open(os.path.join(out, "wrong_types.gltf"), "w") as f:
            json.dump(bad, f)
PY
for mode in strip fan; do
  "$viewer" "$tmp/modes/$mode.gltf" --headless --frames 1 --size 16x16 --out "$tmp/modes/out-$mode" > /dev/null \
    2> "$tmp/modes/$mode.err" || fail "triangle $mode: $(cat "$tmp/modes/$mode.err")"
  triangles=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["triangles"])' "$tmp/modes/out-$mode/report.json")
  [[ $triangles == 2 ]] || fail "triangle $mode: $triangles triangles, expected 2"
done
"$viewer" "$tmp/modes/scene_string.gltf" --headless --frames 1 --size 16x16 --out "$tmp/modes/out-scene" > /dev/null \
  2> "$tmp/modes/scene.err" || fail "\"scene\" as a string: $(cat "$tmp/modes/scene.err")"
grep -qF 'warning: "scene" is not an index; scene 0 rendered' "$tmp/modes/scene.err" ||
  fail "\"scene\" as a string: no warning: $(cat "$tmp/modes/scene.err")"
"$viewer" "$tmp/modes/wrong_types.gltf" --headless --frames 1 --size 16x16 --out "$tmp/modes/out-types" > /dev/null \
  2> "$tmp/modes/types.err" || fail "members of the wrong type: $(cat "$tmp/modes/types.err")"
for want in 'materials[0].name is a number, not a string' 'materials[0].doubleSided is a string, not a boolean' \
            'meshes[0].name is an array, not a string' '1 more'; do
  grep -qF -- "$want" "$tmp/modes/types.err" || fail "members of the wrong type: no '$want' in: $(cat "$tmp/modes/types.err")"
done
[[ $(wc -l < "$tmp/modes/types.err") -eq 1 ]] || fail "members of the wrong type: not one line: $(cat "$tmp/modes/types.err")"
echo "triangle strips and fans: a quad each, 2 triangles; \"scene\" as a string and members of the wrong type: rendered with a warning"

echo "viewer tests: ok (headless 160x96, 8 frames, validation clean: ${quality#ok }; --checkerboard: $checkerboard;" \
  "--lights 2: light 0 bit for bit the same, light 1 its own (default inputs, --rays 2, --gbuffer packed," \
  "--checkerboard); ${window}; ${bad} bad inputs" \
  "rejected with status 2, half of them by the ASan+UBSan build; $((SECONDS - start)) s)"
