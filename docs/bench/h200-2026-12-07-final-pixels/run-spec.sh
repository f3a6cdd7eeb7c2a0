#!/bin/bash
# The filter's tests of final pixels behind DNSR_SPEC_STABLE_HISTORY: dnsr-bench built from the commit that does it
# (`spec`, its own SPIR-V) against df70ac7's binary (`new`, its own SPIR-V) and df70ac7's binary with the
# final pixels taken out (`nofinal`, shader overrides as in run.sh). Balanced and Quality, penumbra-heavy, 4K fp32,
# one round. Shader overrides must declare the built-in variant's specialization constants, so `spec` runs as its
# own binary.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy --presets balanced,quality --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 200"
O=""; for s in tile_classification_r16f filter filter_final_r16f filter_later filter_later_final_r16f; do O="$O --shader-override $s=.gl/nofinal-$s.spv"; done
timeout 40 .gl/bench $A $O --out /tmp/d-nofinal > /dev/null 2>&1 || echo "nofinal failed"
timeout 40 .gl/bench $A --out /tmp/d-new > /dev/null 2>&1 || echo "new failed"
timeout 40 .gl/bench5 $A --out /tmp/d-spec > /dev/null 2>&1 || echo "spec failed"
for n in nofinal new spec; do (echo "## $n"; cat /tmp/d-$n/bench.md) >> $OUT/bench-spec.md; done
cd $OUT
awk '/^## /{h=$2} /^## Pipelines/{h=""} h!="" && /^\| 3840x2160 \| [^|]+ \| (balanced|quality) \| [0-9.]+ \| [0-9]/{print h, $0}' bench-spec.md | cut -c1-120
