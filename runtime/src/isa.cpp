// SPDX-License-Identifier: MIT
// Which kernel path runs: the paths compiled into this build (chosen by
// runtime/CMakeLists.txt for the target), what this CPU supports (CPUID and
// the OS's saved register state on x86-64), and the choice made at load.
#include <cstdlib>
#include <cstring>

#include "isa_select.h"

#if defined(POSEMORPH_KERNELS_X86) && (defined(__GNUC__) || defined(__clang__))
#include <cpuid.h>
#endif

namespace posemorph {
namespace {

struct IsaEntry {
  Isa isa;
  const char* name;
};
constexpr IsaEntry kIsaNames[] = {
    {Isa::kAuto, "auto"},     {Isa::kScalar, "scalar"}, {Isa::kSse2, "sse2"},          {Isa::kAvx2, "avx2"},
    {Isa::kAvx512, "avx512"}, {Isa::kNeon, "neon"},     {Isa::kWasmSimd, "wasm-simd"},
};

#if defined(POSEMORPH_KERNELS_X86)
struct X86Features {
  bool avx2 = false, avx512f = false;
};

// AVX2 needs the CPU flag and the OS saving the YMM state (XCR0 bits 1, 2);
// AVX-512F also the opmask and ZMM state (XCR0 bits 5, 6, 7).
X86Features DetectX86() {
  X86Features f;
#if defined(__GNUC__) || defined(__clang__)
  unsigned a = 0, b = 0, c = 0, d = 0;
  if (!__get_cpuid(1, &a, &b, &c, &d)) return f;
  const bool osxsave = (c >> 27) & 1u, avx = (c >> 28) & 1u;
  if (!osxsave || !avx) return f;
  unsigned xcr0_lo = 0, xcr0_hi = 0;
  __asm__ volatile("xgetbv" : "=a"(xcr0_lo), "=d"(xcr0_hi) : "c"(0));
  const bool ymm_state = (xcr0_lo & 0x6u) == 0x6u, zmm_state = (xcr0_lo & 0xE6u) == 0xE6u;
  if (!__get_cpuid_count(7, 0, &a, &b, &c, &d)) return f;
  f.avx2 = ymm_state && ((b >> 5) & 1u);
  f.avx512f = f.avx2 && zmm_state && ((b >> 16) & 1u);
#endif
  return f;
}

const X86Features& CpuX86() {
  static const X86Features features = DetectX86();
  return features;
}
#endif

}  // namespace

const char* IsaName(Isa isa) {
  for (const IsaEntry& e : kIsaNames)
    if (e.isa == isa) return e.name;
  return "unknown";
}

bool ParseIsa(const char* name, Isa* out) {
  if (!name) return false;
  for (const IsaEntry& e : kIsaNames)
    if (std::strcmp(e.name, name) == 0) {
      if (out) *out = e.isa;
      return true;
    }
  return false;
}

namespace detail {

const KernelTable* CompiledKernels(Isa isa) {
  switch (isa) {
    case Isa::kScalar:
      return &scalar::kKernels;
#if defined(POSEMORPH_KERNELS_X86)
    case Isa::kSse2:
      return &sse2::kKernels;
    case Isa::kAvx2:
      return &avx2::kKernels;
    case Isa::kAvx512:
      return &avx512::kKernels;
#endif
#if defined(POSEMORPH_KERNELS_NEON)
    case Isa::kNeon:
      return &neon::kKernels;
#endif
#if defined(POSEMORPH_KERNELS_WASM_SIMD)
    case Isa::kWasmSimd:
      return &wasm_simd::kKernels;
#endif
    default:
      return nullptr;
  }
}

bool SelectKernels(Isa requested, const KernelTable** out, Error* err) {
  Isa isa = requested;
  if (isa == Isa::kAuto) {
    const char* env = std::getenv("POSEMORPH_ISA");
    if (env && *env) {
      if (!ParseIsa(env, &isa)) {
        if (err) {
          err->code = ErrorCode::kUnsupportedIsa;
          std::snprintf(err->message, sizeof(err->message),
                        "POSEMORPH_ISA=%.64s is not a code path (auto, scalar, sse2, avx2, avx512, neon, wasm-simd)",
                        env);
        }
        return false;
      }
    }
    if (isa == Isa::kAuto) isa = BestIsa();
  }
  if (!IsaAvailable(isa)) {
    if (err) {
      err->code = ErrorCode::kUnsupportedIsa;
      std::snprintf(err->message, sizeof(err->message), "code path %s is %s (this build and CPU run: %s)", IsaName(isa),
                    CompiledKernels(isa) ? "not supported by this CPU" : "not compiled into this build",
                    AvailableIsaNames());
    }
    return false;
  }
  *out = CompiledKernels(isa);
  return true;
}

const char* AvailableIsaNames() {
  static char names[96] = {0};
  static const bool filled = [] {
    for (const IsaEntry& e : kIsaNames)
      if (e.isa != Isa::kAuto && IsaAvailable(e.isa)) {
        if (names[0]) std::strcat(names, " ");
        std::strcat(names, e.name);
      }
    return true;
  }();
  (void)filled;
  return names;
}

}  // namespace detail

bool IsaAvailable(Isa isa) {
  if (!detail::CompiledKernels(isa)) return false;
#if defined(POSEMORPH_KERNELS_X86)
  if (isa == Isa::kAvx2) return CpuX86().avx2;
  if (isa == Isa::kAvx512) return CpuX86().avx512f;
#endif
  return true;
}

Isa BestIsa() {
  constexpr Isa kFastestFirst[] = {Isa::kAvx512, Isa::kAvx2, Isa::kSse2, Isa::kNeon, Isa::kWasmSimd};
  for (Isa isa : kFastestFirst)
    if (IsaAvailable(isa)) return isa;
  return Isa::kScalar;
}

}  // namespace posemorph
