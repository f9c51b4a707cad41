// Sanitizer builds only: keeps every shared library loaded so far from being unloaded at exit.
// Mesa and glvnd dlclose their drivers when the process ends, after which LeakSanitizer can no
// longer name the module of their process-lifetime allocations, so the suppressions in
// tests/viewer/lsan.supp (by module) could not match. A no-op in ordinary builds.
#pragma once

namespace wirerig {

void PinLoadedLibrariesForLeakChecks();

}  // namespace wirerig
