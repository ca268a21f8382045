#include "memory_policy.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace cli_support {

void keep_freed_memory_in_heap() {
#if defined(__GLIBC__)
  // Blocks up to 1 GiB come from the heap, and the heap's free top is not trimmed below 1 GiB.
  // A failure leaves glibc's defaults, which are correct, only slower.
  constexpr int one_gib = 1 << 30;
  mallopt(M_MMAP_THRESHOLD, one_gib);
  mallopt(M_TRIM_THRESHOLD, one_gib);
#endif
}

}  // namespace cli_support
