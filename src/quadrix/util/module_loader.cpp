#include "quadrix/util/module_loader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <map>
#include <mutex>
#include <vector>

namespace quadrix {

namespace {

std::string HostDirectory() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&ModuleSearchPath), &info) == 0 || !info.dli_fname)
        return ".";
    const std::string p = info.dli_fname;
    const std::size_t slash = p.rfind('/');
    return slash == std::string::npos ? "." : p.substr(0, slash);
}

std::vector<std::string> SearchDirectories() {
    std::vector<std::string> dirs;
    if (const char* env = std::getenv("QUADRIX_MODULE_DIR"); env && *env) return {env};
    const std::string host = HostDirectory();
    dirs.push_back(host);
#ifdef QUADRIX_MODULE_DIR_FROM_BIN
    dirs.push_back(host + "/" + QUADRIX_MODULE_DIR_FROM_BIN);
#endif
    dirs.push_back(host + "/quadrix");
#ifdef QUADRIX_MODULE_DIR_INSTALLED
    dirs.push_back(QUADRIX_MODULE_DIR_INSTALLED);
#endif
#ifdef QUADRIX_MODULE_DIR_BUILD
    dirs.push_back(QUADRIX_MODULE_DIR_BUILD);
#endif
    return dirs;
}

struct Loaded {
    void* handle = nullptr;
    std::string error;  // why handle is null
};

Loaded Load(const std::string& file) {
    Loaded m;
    for (const std::string& dir : SearchDirectories()) {
        const std::string path = dir + "/" + file;
        if (access(path.c_str(), F_OK) != 0) continue;
        m.handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!m.handle) {
            const char* why = dlerror();
            m.error = "cannot load " + path + ": " + (why ? why : "dlopen failed");
        }
        return m;
    }
    m.error = "the module " + file + " is missing (looked in " + ModuleSearchPath() +
              "; the environment variable QUADRIX_MODULE_DIR names the directory to use)";
    return m;
}

}  // namespace

std::string ModuleSearchPath() {
    std::string s;
    for (const std::string& d : SearchDirectories()) s += (s.empty() ? "" : ", ") + d;
    return s;
}

void* LoadModuleSymbol(const char* file, const char* symbol, std::string* error) {
    static std::mutex mutex;
    static std::map<std::string, Loaded> modules;
    const std::lock_guard<std::mutex> lock(mutex);
    auto it = modules.find(file);
    if (it == modules.end()) it = modules.emplace(file, Load(file)).first;
    const Loaded& m = it->second;
    if (!m.handle) {
        if (error) *error = m.error;
        return nullptr;
    }
    void* p = dlsym(m.handle, symbol);
    if (!p && error)
        *error = std::string("the module ") + file + " has no " + symbol +
                 " (is it from another build of Quadrix?)";
    return p;
}

}  // namespace quadrix
