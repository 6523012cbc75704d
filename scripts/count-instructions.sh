#!/usr/bin/env bash
# Executed instructions per point of the batch entry points at each dispatch level, on x86_64
# (valgrind's callgrind: portable, sse2, avx2; valgrind does not run AVX-512) and on aarch64
# (qemu-user's translation-block log: portable, neon). Emulated timings say nothing about a real
# core; these counts are what docs/performance.md gives for aarch64, beside x86_64's.
#
# Each count runs `shade_loop` (tools/src/bin/shade_loop.rs) for one call and for three, and
# divides the difference by the 2·4096 points of the two extra calls, so start-up and set-up
# cancel. Needs valgrind, and for aarch64 the cross tools .ci/run installs
# (gcc-aarch64-linux-gnu, libc6-dev-arm64-cross, qemu-user-static) and
# `rustup target add aarch64-unknown-linux-gnu`.
#
# Run from the repository root: bash scripts/count-instructions.sh (writes
# docs/instruction-counts.md).
set -euo pipefail

forms=(batch gbuffer_f32 gbuffer_rgba8 gbuffer_albedo8_rgba8)
target_dir=${CARGO_TARGET_DIR:-target}

cargo build --release -p phong-tools --bin shade_loop --quiet
CARGO_TARGET_AARCH64_UNKNOWN_LINUX_GNU_LINKER=aarch64-linux-gnu-gcc \
  cargo build --release -p phong-tools --bin shade_loop --quiet --target aarch64-unknown-linux-gnu
x86="$target_dir/release/shade_loop"
arm="$target_dir/aarch64-unknown-linux-gnu/release/shade_loop"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Instructions executed by `$x86 form level calls`, by callgrind.
x86_count() {
  valgrind --tool=callgrind --callgrind-out-file="$work/cg" "$x86" "$@" > /dev/null 2>&1
  awk '/^summary:/ {print $2; exit}' "$work/cg"
}

# Instructions executed by `$arm form level calls` under qemu: every translation block's
# instruction count (from the `in_asm` log) times its executions (the `exec` log, unchained so
# that every execution is logged).
arm_count() {
  qemu-aarch64-static -L /usr/aarch64-linux-gnu -d in_asm,exec,nochain -D "$work/q" \
    "$arm" "$@" > /dev/null 2>&1
  awk '
    /^IN:/ { block = ""; next }
    /^0x[0-9a-f]+: +[0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f] / {
      pc = $1; sub(/:$/, "", pc)
      if (block == "") { block = pc; size[block] = 0 }
      size[block]++
      next
    }
    /^$/ { block = ""; next }
    /^Trace/ {
      # "Trace 0: host [flags/guest pc/...]": the guest pc, zero-padded.
      split($0, field, "/"); pc = field[2]; sub(/^0+/, "", pc)
      runs["0x" pc]++
    }
    END { for (pc in runs) total += runs[pc] * size[pc]; printf "%d\n", total }
  ' "$work/q"
}

per_point() {
  local count=$1 form=$2 level=$3
  local one three
  one=$($count "$form" "$level" 1)
  three=$($count "$form" "$level" 3)
  awk -v a="$one" -v b="$three" 'BEGIN { printf "%.1f", (b - a) / (2 * 4096) }'
}

table=$(
  echo "| form | x86_64 portable | x86_64 SSE2 | x86_64 AVX2 | aarch64 portable | aarch64 NEON |"
  echo "|---|---:|---:|---:|---:|---:|"
  for form in "${forms[@]}"; do
    row="| \`$form\`"
    for level in portable sse2 avx2; do
      row+=" | $(per_point x86_count "$form" "$level")"
    done
    for level in portable neon; do
      row+=" | $(per_point arm_count "$form" "$level")"
    done
    echo "$row |"
  done
)

host=$(lscpu | awk -F: '/Model name/ { sub(/^ +/, "", $2); print $2; exit }')
# The last commit that changed the crate's code, which is what the counts measure.
commit=$(git log -1 --format=%h -- src)
git diff --quiet HEAD -- src || commit="$commit, with uncommitted changes to src/"

cat > docs/instruction-counts.md <<EOF
# Executed instructions per point

Written by \`bash scripts/count-instructions.sh\` on $(date -u +%Y-%m-%d), on $host, for the
crate's code of commit $commit.

Instructions executed per point by the batch entry points at each dispatch level this host or
qemu runs: x86_64's counted by valgrind's callgrind (which does not run AVX-512), aarch64's
from qemu-user's log of translated blocks and of their executions. Each count is the
difference between one call and three of \`shade_loop\` (tools/src/bin/shade_loop.rs) over the
benches' 4096 points, divided by the 8192 points of the two extra calls: start-up cancels, and
each point's share of a call's set-up is included. Phong, one point light:

- \`batch\`: \`shade_batch\`, one material at s = 20.5 (\`batch_frac\` in docs/performance.md);
- \`gbuffer_*\`: \`gbuffer_4096\`'s rows, a per-point surface (shininess in [2, 128]) and a
  shadow factor per point, into \`f32\` planes, into RGBA8, and into RGBA8 with the albedo
  read as 8-bit sRGB texels.

$table

An emulator's timings say nothing about a real core, and these counts do not give its speed
either: that depends on how many instructions it retires per cycle. They give the work per
point. NEON holds 16 lanes in four 128-bit vectors and AVX2 in two 256-bit ones, both with
fused multiply-adds; SSE2 has four vectors and no fused multiply-add; \`Portable\` is the same
kernel source on \`[f32; 16]\` arrays, vectorised by LLVM alone.
EOF
echo "wrote docs/instruction-counts.md"
