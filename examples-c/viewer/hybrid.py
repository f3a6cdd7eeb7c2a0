#!/usr/bin/env python3
"""Hybrid shadows against full tracing, in the viewer: for every scene, size and sun size, the same 16 frames (an
orbiting camera) rendered tracing every receiver's shadow ray and in hybrid mode (--hybrid: cascades, dnsr's
classifier, rays for the listed pixels only), both with penumbra guidance (the viewer's default; in hybrid mode only
the traced pixels have a hit distance) and, with --unguided, both without. Writes OUT/hybrid.json (every
report.json) and OUT/hybrid.md (the table):

- traced: the receivers whose ray hybrid mode traced, and the rays it saved;
- decided wrong: receivers the cascades decided against the reference's majority (lit < 0.5 decided lit, or > 0.5
  decided shadowed);
- GPU ms: median over frames 2..16 of the viewer's timestamps: the shadow rays and dnsr for full tracing; the
  classifier, the listed rays and dnsr for hybrid mode; the cascades apart (an engine renders its shadow maps anyway,
  the viewer traces them);
- RMSE of the denoised shadow against the reference (REFERENCE_RAYS rays per pixel), every run of a row against the
  same one (the first run saves it, the others load it: the viewer checks their last frames' depth is the same).

usage: hybrid.py VIEWER OUT_DIR [--sizes 1920x1080,3840x2160] [--suns 0.27,3] [--reference-rays 1024] [--unguided]
                 SCENE...
"""
import argparse
import json
import subprocess
import time
from pathlib import Path

FRAMES = 16


def run(viewer, scene, size, sun, out, extra):
    args = [viewer, scene, "--headless", "--frames", str(FRAMES), "--size", size, "--light-angle", sun, "--out", out]
    done = subprocess.run(args + extra, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=900)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(args + extra)} failed ({done.returncode}):\n{done.stdout}")
    return json.loads((Path(out) / "report.json").read_text())


def row(scene, size, sun, runs):
    full, hybrid = runs["full"], runs["hybrid"]
    f, h = full["viewer_gpu_ms_median"], hybrid["viewer_gpu_ms_median"]
    t = hybrid["traced"]
    rmse = {name: r["rmse"]["denoised"] for name, r in runs.items()}
    return {
        "scene": Path(scene).stem, "size": size, "sun_deg": float(sun),
        "traced_fraction": t["fraction"], "rays_saved": t["rays_saved"], "receivers": t["receivers"],
        "decided_wrong": t["decided_wrong"],
        "full_ms": {"rays": f["shadow"], "dnsr": f["dnsr"], "total": f["shadow"] + f["dnsr"]},
        "hybrid_ms": {"cascades": h["cascades"], "classify": h["classify"], "rays": h["shadow"], "dnsr": h["dnsr"],
                      "total": h["classify"] + h["shadow"] + h["dnsr"]},
        "rmse": rmse,
    }


def markdown(rows, device, reference_rays, unguided):
    out = [f"Device: {device}. {FRAMES} frames, orbiting camera, penumbra guidance on; GPU ms are medians over frames "
           f"2..{FRAMES}; RMSE of the last frame's denoised shadow against a {reference_rays}-ray reference.", "",
           "| scene | size | sun radius | traced | rays saved | decided wrong | full: rays + dnsr ms | "
           "hybrid: classify + rays + dnsr ms | speed-up | cascades ms | RMSE full | RMSE hybrid |"
           + (" RMSE unguided: full, hybrid |" if unguided else ""),
           "|---|---|---|---|---|---|---|---|---|---|---|---|" + ("---|" if unguided else "")]
    for r in rows:
        f, h, e = r["full_ms"], r["hybrid_ms"], r["rmse"]
        line = (f"| {r['scene']} | {r['size']} | {r['sun_deg']:g} deg | {r['traced_fraction']:.1%} | "
                f"{r['rays_saved']:,} | {r['decided_wrong']} | {f['rays']:.2f} + {f['dnsr']:.2f} = {f['total']:.2f} | "
                f"{h['classify']:.2f} + {h['rays']:.2f} + {h['dnsr']:.2f} = {h['total']:.2f} | "
                f"{f['total'] / h['total']:.2f}x | {h['cascades']:.2f} | {e['full']:.4f} | {e['hybrid']:.4f} "
                f"({e['hybrid'] / e['full'] - 1:+.1%}) |")
        if unguided:
            line += (f" {e['full_unguided']:.4f}, {e['hybrid_unguided']:.4f} "
                     f"({e['hybrid_unguided'] / e['full_unguided'] - 1:+.1%}) |")
        out.append(line)
    return "\n".join(out) + "\n"


def main():
    p = argparse.ArgumentParser()
    p.add_argument("viewer")
    p.add_argument("out")
    p.add_argument("scenes", nargs="+")
    p.add_argument("--sizes", default="1920x1080,3840x2160")
    p.add_argument("--suns", default="0.27,3")
    p.add_argument("--reference-rays", default="1024")
    p.add_argument("--unguided", action="store_true")
    a = p.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    variants = [("full", []), ("hybrid", ["--hybrid"])]
    if a.unguided:
        variants += [("full_unguided", ["--hit-distance", "off"]), ("hybrid_unguided", ["--hybrid", "--hit-distance", "off"])]
    rows, reports, device = [], [], "?"
    start = time.monotonic()
    for scene in a.scenes:
        for size in a.sizes.split(","):
            for sun in a.suns.split(","):
                ref = str(out / "reference.bin")
                runs = {}
                for i, (name, extra) in enumerate(variants):
                    reference = (["--reference-samples", a.reference_rays, "--save-reference", ref] if i == 0
                                 else ["--load-reference", ref])
                    runs[name] = run(a.viewer, scene, size, sun, str(out / name), extra + reference)
                device = runs["full"]["device"]
                reports.append(runs)
                rows.append(row(scene, size, sun, runs))
                r = rows[-1]
                print(f"{time.monotonic() - start:6.1f} s {Path(scene).stem} {size} sun {sun}: "
                      f"traced {r['traced_fraction']:.1%}, {r['full_ms']['total']:.2f} -> "
                      f"{r['hybrid_ms']['total']:.2f} ms, RMSE {r['rmse']['full']:.4f} -> {r['rmse']['hybrid']:.4f}",
                      flush=True)
                # After every row: a run cut short keeps what it measured.
                (out / "hybrid.json").write_text(json.dumps({"rows": rows, "reports": reports}, indent=1))
                (out / "hybrid.md").write_text(markdown(rows, device, a.reference_rays, a.unguided))
    Path(out / "reference.bin").unlink(missing_ok=True)


if __name__ == "__main__":
    main()
