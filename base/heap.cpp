#include "base/heap.h"

#include <cstdlib>  // defines __GLIBC__ where the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace xshade {

void keep_freed_heap() {
#if defined(__GLIBC__)
  // Twice the map threshold for the trim one, as glibc pairs them when it moves them itself.
  constexpr int kMapThreshold = 4 * 1024 * 1024;
  mallopt(M_MMAP_THRESHOLD, kMapThreshold);
  mallopt(M_TRIM_THRESHOLD, 2 * kMapThreshold);
#endif
}

}  // namespace xshade
