#!/bin/bash
# The later filter passes with their taps in a shared-memory apron (after) against fetching every tap through the
# texture cache (before): two dnsr-bench binaries, alternating twice at 4K fp32 over every scene and preset, once
# more for fp16 and the smaller sizes; then the after build's unit-test binary (parity, lights, render rectangles,
# output formats and filter pass counts, transient state) with the validation layer on this device.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical,all-lit,sky-90 --presets quality,balanced,fast --precisions fp32 --frames 200 --copy-runs 3 --warmup-ms 500"
B="--sizes 1920x1080,2560x1440,3840x2160 --scenes penumbra-heavy --presets quality,balanced --precisions fp32,fp16 --frames 200 --copy-runs 1 --warmup-ms 300"
for r in 1 2; do for b in before after; do DNSR_COMMIT=$b timeout 140 .gl/bench-$b $A --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1 || tail -3 $OUT/$b-$r.log; done; done
for b in before after; do DNSR_COMMIT=$b timeout 100 .gl/bench-$b $B --out $OUT/$b-sizes > $OUT/$b-sizes.log 2>&1 || tail -3 $OUT/$b-sizes.log; done
timeout 150 .gl/dnsr-tests tests::parity tests::lights::several tests::correctness::a_render_rect tests::correctness::every_output tests::correctness::render_rect_writes tests::transient::transient_images > $OUT/tests.txt 2>&1; echo "tests exit $?" >> $OUT/tests.txt
cd $OUT && for d in before-1 after-1 before-2 after-2 before-sizes after-sizes; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf before-? after-? *-sizes *.log && cat device.txt; grep -hE "test result|exit" tests.txt
awk '/^## /{h=$2} /^\| [0-9]+x[0-9]+ \| [a-z0-9% -]+ \| (quality|balanced|fast) \| [0-9]/{n=split($0,a,"|"); print h, a[2], a[3], a[4], "cls", a[6], "f0", a[7], "f1", a[8], "f2", a[9], "total", a[10]}' bench-all.md
