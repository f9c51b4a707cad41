#include "sanitizer_support.h"

#include <cstddef>

// AddressSanitizer: GCC defines __SANITIZE_ADDRESS__, clang (before 16) only answers
// __has_feature(address_sanitizer).
#if defined(__SANITIZE_ADDRESS__)
#define WIRERIG_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define WIRERIG_ASAN 1
#endif
#endif

#if defined(WIRERIG_ASAN)
#include <dlfcn.h>
#include <link.h>
#endif

namespace wirerig {

void PinLoadedLibrariesForLeakChecks() {
#if defined(WIRERIG_ASAN)
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void*) -> int {
        if (info->dlpi_name != nullptr && info->dlpi_name[0] == '/') {
          // RTLD_NOLOAD: only already-loaded objects; RTLD_NODELETE: never unload them. The
          // handle is deliberately kept (closing it would not unload the object anyway).
          (void)dlopen(info->dlpi_name, RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
        }
        return 0;
      },
      nullptr);
#endif
}

}  // namespace wirerig
