// HaveViewerWindow, WakeViewerWindow and RunViewerWindow (viewer_window.h) for the program: the
// window itself (viewer_window.cpp) is a module of its own, quadrix-view.so, linked with SDL2,
// and loaded only by `quadrix view`. SDL2 brings about 40 shared libraries (sound, Wayland, X11,
// D-Bus, codecs); linked into the program they cost every quadrix process 10-20 ms before main
// on the test machines (an empty program linked like quadrix started in 34 ms, 14 ms without
// SDL2: docs/performance.md "Page faults and start-up").
//
// The module is looked for next to the program (the build tree), then at the installed place
// relative to it (QUADRIX_VIEW_MODULE_FROM_BIN, set by CMake: <libdir>/quadrix/quadrix-view.so).
// It resolves the rest of Quadrix against the program, which exports its symbols for it
// (ENABLE_EXPORTS). When it cannot be loaded, `quadrix view` says why and exits 1, and
// `quadrix view --bench` renders offscreen.
#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <cstdio>
#include <string>

#include "viewer_window.h"

namespace quadrix::cli {

namespace {

struct ViewModule {
    int (*run)(const ViewerSession*) = nullptr;
    void (*wake)() = nullptr;
    std::string error;  // why there is no window, when run is null
};

std::string ProgramDirectory() {
    char path[PATH_MAX];
    const ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
    if (n <= 0) return ".";
    std::string p(path, static_cast<std::size_t>(n));
    const std::size_t slash = p.rfind('/');
    return slash == std::string::npos ? "." : p.substr(0, slash);
}

ViewModule LoadModule() {
    ViewModule m;
#ifndef QUADRIX_HAVE_SDL2
    m.error =
        "this quadrix was built without SDL2 (Debian: libsdl2-dev), so `quadrix view` has no "
        "window; `quadrix view --bench N` renders offscreen";
    return m;
#else
    const std::string dir = ProgramDirectory();
    std::string tried;
    for (const std::string& path :
         {dir + "/quadrix-view.so", dir + "/" + QUADRIX_VIEW_MODULE_FROM_BIN}) {
        if (access(path.c_str(), F_OK) != 0) {
            tried += (tried.empty() ? "" : ", ") + path;
            continue;
        }
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* why = dlerror();
            m.error = std::string("cannot load the window module (SDL2): ") + (why ? why : path);
            return m;
        }
        m.run = reinterpret_cast<int (*)(const ViewerSession*)>(dlsym(handle, "quadrix_view_run"));
        m.wake = reinterpret_cast<void (*)()>(dlsym(handle, "quadrix_view_wake"));
        if (!m.run || !m.wake) {
            m.run = nullptr;
            m.error = "the window module " + path + " is not this quadrix's (no entry points)";
        }
        return m;
    }
    m.error = "the window module of `quadrix view` is missing (looked for " + tried +
              "); `quadrix view --bench N` renders offscreen";
    return m;
#endif
}

// Loaded once, on first use (thread-safe: a function-local static).
const ViewModule& Module() {
    static const ViewModule m = LoadModule();
    return m;
}

}  // namespace

bool HaveViewerWindow() { return Module().run != nullptr; }

void WakeViewerWindow() {
    if (const auto wake = Module().wake) wake();
}

int RunViewerWindow(const ViewerSession& session) {
    const ViewModule& m = Module();
    if (!m.run) {
        std::fprintf(stderr, "quadrix: error: %s\n", m.error.c_str());
        return 1;
    }
    return m.run(&session);
}

}  // namespace quadrix::cli
