#!/bin/bash
# usage: buildvar.sh NAME FOLLOW SUB APRON STABLE_OFF EMA ALPHA
set -e
cd /work/exp
f=shaders/tile_classification.glsl
sed -i "s/^#define EXP_FOLLOW .*/#define EXP_FOLLOW $2/; s/^#define EXP_SUB .*/#define EXP_SUB $3/; s/^#define EXP_APRON .*/#define EXP_APRON $4/; s/^#define EXP_STABLE_OFF .*/#define EXP_STABLE_OFF $5/; s/^#define EXP_EMA .*/#define EXP_EMA $6/; s/^#define EXP_ALPHA .*/#define EXP_ALPHA $7/" $f
DNSR_BLESS=1 cargo test --release --lib bless_spirv 2>&1 | grep "test result"
cargo build --release --features demo --bin dnsr-accuracy 2>&1 | tail -1
cp target/release/dnsr-accuracy /tmp/acc-$1
