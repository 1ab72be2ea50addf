// The spume command's allocation function, linked into the executable only (and into the benchmark
// that measures the diffuse stage as the command runs it); no library replaces it. Two things need it:
// huge-page advice for the large blocks of the stages that ask for it (sim/core/huge_pages.h), and the
// size of an allocation that failed, for the out-of-memory message (sim/core/out_of_memory.h). Memory
// comes from malloc, as libstdc++'s operator new takes it, so its operator delete frees it. The array
// and nothrow forms of libstdc++ call this one. Under AddressSanitizer, whose allocator must pair every
// new with its own delete, the sanitizer's operator new stays.
#include <cstdlib>
#include <new>

#include "sim/core/huge_pages.h"
#include "sim/core/out_of_memory.h"
#include "sim/core/sanitizers.h"

#if !SPUME_ADDRESS_SANITIZER
void* operator new(std::size_t n) {
  for (;;) {
    if (void* p = std::malloc(n ? n : 1)) {
      if (n >= spume::kHugePageRequestBytes && spume::HugePagesForLargeBlocks::active()) spume::advise_huge_pages(p, n);
      return p;
    }
    std::new_handler handler = std::get_new_handler();
    if (!handler) {
      spume::record_failed_allocation(n);  // so the message can say how much was asked for
      throw std::bad_alloc();
    }
    handler();
  }
}
#endif
